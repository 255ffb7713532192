#include <mrloc/common/Error.h>
#include <mrloc/formation/FormationScene.h>
#include <mrloc/sim/PinholeCamera.h>

namespace mrloc::formation {

FormationScene::FormationScene(size_t robots, const MarkerOptions& markers) {
    sim::WorldOptions world;
    scene_ = sim::makeWorldScene(world, false);
    for (size_t r = 0; r < robots; ++r) {
        robots_.push_back(robotObjects(r, markers));
        scene_->insert(robots_.back());
    }
}

mrpt::poses::CPose2D FormationScene::local(const mrpt::poses::CPose2D& world) const {
    return {world.x() - origin_.x, world.y() - origin_.y, world.phi()};
}

void FormationScene::place(size_t robot, const mrpt::poses::CPose2D& pose) {
    const auto p = local(pose);
    robots_.at(robot)->setPose(mrpt::poses::CPose3D(p.x(), p.y(), 0, p.phi(), 0, 0));
}

void FormationScene::show(size_t robot, bool visible) { robots_.at(robot)->setVisibility(visible); }

}  // namespace mrloc::formation
