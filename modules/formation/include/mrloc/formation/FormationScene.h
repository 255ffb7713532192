#pragma once
// The formation as the moving robot's cameras see it, built once per march: every robot's
// body and tags (robotObjects) in one scene, moved between moves rather than rebuilt (a
// robot's tag textures are made and uploaded once).
//
// The scene is drawn about an origin the caller sets near the camera: the renderer works in
// single precision, and 30 m from the scene's origin a robot's body (2 cm behind its tags)
// showed through them. A scene's GL buffers belong to the renderer that first drew it: draw
// it with one sim::PinholeCamera only.
#include <mrloc/formation/Markers.h>
#include <mrloc/sim/World.h>
#include <mrpt/math/TPoint2D.h>

#include <vector>

namespace mrloc::formation {

class FormationScene {
 public:
    /** `robots` robots (tag ids 4 r + side), on a grey floor without walls. */
    FormationScene(size_t robots, const MarkerOptions& markers);

    /** Where the scene's origin is in the world (m); place() again after changing it. */
    void setOrigin(const mrpt::math::TPoint2D& origin) { origin_ = origin; }
    const mrpt::math::TPoint2D& origin() const { return origin_; }
    /** Robot r at its world pose. */
    void place(size_t robot, const mrpt::poses::CPose2D& pose);
    /** Shows or hides robot r (the moving robot is not in its own view). */
    void show(size_t robot, bool visible);
    /** A world pose in the scene's frame (for the camera's pose). */
    mrpt::poses::CPose2D local(const mrpt::poses::CPose2D& world) const;

    const mrpt::opengl::COpenGLScene& scene() const { return *scene_; }
    size_t robots() const { return robots_.size(); }

 private:
    mrpt::opengl::COpenGLScene::Ptr scene_;
    std::vector<mrpt::opengl::CSetOfObjects::Ptr> robots_;
    mrpt::math::TPoint2D origin_{0, 0};
};

}  // namespace mrloc::formation
