#include <mrloc/common/Error.h>
#include <mrloc/formation/Routes.h>

namespace mrloc::formation {

std::vector<mrpt::math::TPoint2D> route(const std::string& name) {
    // (1.5, 0.65): the centre of the four robots' starting rhombus (initialStrip, side 1.5)
    if (name == "many_turns")
        return {{1.5, 0.65}, {20, 0.65}, {20, 15}, {5, 15}, {5, 30}, {25, 30}, {25, 45}, {40, 45}};
    if (name == "patrol") return {{1.5, 0.65}, {30, 0.65}, {30, 20}, {1.5, 20}, {1.5, 0.65}};
    throw Error("formation: route '" + name + "': expected many_turns or patrol");
}

}  // namespace mrloc::formation
