#include <mrloc/common/Localizer.h>

namespace mrloc::common {

std::optional<mrpt::poses::CPose3D> Localizer::latestEstimate(const std::string& robot) const {
    const auto all = estimates();
    const auto it = all.find(robot);
    if (it == all.end() || it->second.empty()) return std::nullopt;
    return it->second.back().pose;
}

}  // namespace mrloc::common
