#include <mrloc/common/Error.h>
#include <mrloc/common/Localizer.h>

namespace mrloc::common {

std::optional<mrpt::poses::CPose3D> Localizer::latestEstimate(const std::string& robot) const {
    const auto all = estimates();
    const auto it = all.find(robot);
    if (it == all.end() || it->second.empty()) return std::nullopt;
    return it->second.back().pose;
}

void LocalizerRegistry::add(const std::string& name, Factory factory) {
    if (factories_.count(name)) throw Error("localizer '" + name + "' registered twice");
    factories_[name] = std::move(factory);
}

std::unique_ptr<Localizer> LocalizerRegistry::create(const std::string& name) const {
    const auto it = factories_.find(name);
    if (it == factories_.end()) {
        std::string known;
        for (const auto& n : names()) known += (known.empty() ? "" : ", ") + n;
        throw Error("unknown localization method '" + name + "' (known: " + known + ")");
    }
    return it->second();
}

std::vector<std::string> LocalizerRegistry::names() const {
    std::vector<std::string> out;
    for (const auto& [name, f] : factories_) out.push_back(name);
    return out;
}

}  // namespace mrloc::common
