#include <mrloc/common/Error.h>
#include <mrloc/sim/PinholeCamera.h>
#include <mrpt/math/CMatrixFixed.h>
#include <mrpt/opengl/CBox.h>
#include <mrpt/opengl/CDisk.h>
#include <mrpt/opengl/CFBORender.h>

#include <cmath>

namespace mrloc::sim {

mrpt::opengl::COpenGLScene::Ptr makeWorldScene(const WorldOptions& w, bool withWalls) {
    auto scene = mrpt::opengl::COpenGLScene::Create();
    scene->getViewport()->setCustomBackgroundColor({0.85f, 0.9f, 0.95f});
    // MRPT's default depth range (0.01 to 10000 m) leaves too little depth resolution at a
    // few metres: a marker 1 m in front of a wall 9 m away lost to the wall.
    scene->getViewport()->setViewportClipDistances(0.05f, 500.0f);
    auto floor = mrpt::opengl::CDisk::Create(200.0f, 0.0f);
    floor->setColor_u8(120, 120, 120);
    scene->insert(floor);
    // The walls stand just outside the room so that nothing inside is clipped by them.
    const double t = 0.05, X = w.sizeX, Y = w.sizeY, H = w.height;
    const mrpt::math::TPoint3D walls[4][2] = {{{-t, -t, 0}, {X + t, 0, H}},
                                              {{-t, Y, 0}, {X + t, Y + t, H}},
                                              {{-t, 0, 0}, {0, Y, H}},
                                              {{X, 0, 0}, {X + t, Y, H}}};
    for (const auto& wall : walls) {
        if (!withWalls) break;
        auto box = mrpt::opengl::CBox::Create(wall[0], wall[1]);
        box->setColor_u8(215, 210, 200);
        scene->insert(box);
    }
    for (const auto& b : w.obstacles) {
        auto box = mrpt::opengl::CBox::Create(b.min, b.max);
        box->setColor_u8(90, 90, 100);
        scene->insert(box);
    }
    return scene;
}

mrpt::poses::CPose3D cameraPoseLooking(const mrpt::math::TPoint3D& p, double yaw, double pitch) {
    // Camera axes in the world: +Z forward (yaw, pitched down), +X right, +Y down.
    const double cy = std::cos(yaw), sy = std::sin(yaw), cp = std::cos(pitch), sp = std::sin(pitch);
    mrpt::math::CMatrixDouble33 R;
    R(0, 0) = sy, R(0, 1) = -sp * cy, R(0, 2) = cp * cy;
    R(1, 0) = -cy, R(1, 1) = -sp * sy, R(1, 2) = cp * sy;
    R(2, 0) = 0, R(2, 1) = -cp, R(2, 2) = -sp;
    const mrpt::math::CVectorFixedDouble<3> t(std::array<double, 3>{p.x, p.y, p.z}.data());
    return mrpt::poses::CPose3D::FromRotationAndTranslation(R, t);
}

struct PinholeCamera::Impl {
    mrpt::img::TCamera intrinsics;
    mrpt::opengl::CFBORender fbo;
    mrpt::opengl::CCamera camera;
    explicit Impl(const mrpt::img::TCamera& k) : intrinsics(k), fbo(k.ncols, k.nrows) {
        camera.set6DOFMode(true);
        camera.setProjectiveFromPinhole(k);
    }
};

PinholeCamera::PinholeCamera(const mrpt::img::TCamera& intrinsics) {
    // MRPT's renderer reads the picture back row after row without padding: a row of 3 x
    // width bytes that is not a whole number of 4-byte words overran the picture's memory.
    if (intrinsics.ncols % 4 != 0 || intrinsics.ncols == 0 || intrinsics.nrows == 0)
        throw Error("pinhole camera: the picture's width must be a positive multiple of 4 px (" +
                    std::to_string(intrinsics.ncols) + " x " + std::to_string(intrinsics.nrows) +
                    ")");
    impl_ = std::make_unique<Impl>(intrinsics);
}
PinholeCamera::~PinholeCamera() = default;

const mrpt::img::TCamera& PinholeCamera::intrinsics() const { return impl_->intrinsics; }

mrpt::img::CImage PinholeCamera::render(const mrpt::opengl::COpenGLScene& scene,
                                        const mrpt::poses::CPose3D& cameraPose) {
    impl_->camera.setPose(cameraPose);
    impl_->fbo.setCamera(scene, impl_->camera);
    mrpt::img::CImage view;
    impl_->fbo.render_RGB(scene, view);
    if (view.getWidth() != impl_->intrinsics.ncols || view.getHeight() != impl_->intrinsics.nrows)
        throw Error("pinhole camera: the renderer returned a picture of the wrong size");
    return view;
}

}  // namespace mrloc::sim
