#pragma once
// An off-screen pinhole camera (MRPT's CFBORender: EGL, no display needed) for any camera
// pose and intrinsics, and the scene it looks at: the world's floor, walls and obstacles,
// to which a method adds each robot's markers. Seed 000's omni panorama (four views) and
// seed 003's front and rear cameras are all such views.
//
// Lifetime and threads (MRPT 2.5's CFBORender, measured): when a renderer is destroyed, the
// other renderers of the same thread can no longer draw, and one destroyed after that throws
// from its destructor; so a thread holds one camera at a time (the app releases a
// simulation's payload, and its cameras, as soon as the simulation ends). Renderers on
// different threads draw at the same time and may be destroyed in any order (the pixel
// experiment's workers each hold one). A scene's GL buffers belong to the renderer that first
// drew it: a scene drawn by a camera since destroyed must be built again.
#include <mrloc/sim/World.h>
#include <mrpt/img/CImage.h>
#include <mrpt/img/TCamera.h>
#include <mrpt/opengl/COpenGLScene.h>
#include <mrpt/poses/CPose3D.h>

#include <memory>

namespace mrloc::sim {

/** The world as a camera sees it: a grey floor, the room's four walls (light; `walls`
 *  false leaves the room open) and the obstacles (darker boxes). Markers are inserted by
 *  the caller. */
mrpt::opengl::COpenGLScene::Ptr makeWorldScene(const WorldOptions& world, bool walls = true);

/** A camera pose in the world from where it is and where it looks: position, heading
 *  (yaw, rad) and pitch (rad, positive down), in MRPT's camera convention (+Z forward,
 *  +X right, +Y down). */
mrpt::poses::CPose3D cameraPoseLooking(const mrpt::math::TPoint3D& position, double yaw,
                                       double pitch = 0);

class PinholeCamera {
 public:
    /** One rendering context of intrinsics.ncols x intrinsics.nrows pixels, reused for
     *  every picture. Throws mrloc::Error unless ncols is a positive multiple of 4. */
    explicit PinholeCamera(const mrpt::img::TCamera& intrinsics);
    ~PinholeCamera();
    const mrpt::img::TCamera& intrinsics() const;

    /** Renders the scene from a camera at `cameraPose` (cameraPoseLooking()). */
    mrpt::img::CImage render(const mrpt::opengl::COpenGLScene& scene,
                             const mrpt::poses::CPose3D& cameraPose);

 private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace mrloc::sim
