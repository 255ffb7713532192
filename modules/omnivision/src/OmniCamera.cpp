#include <mrloc/common/Error.h>
#include <mrloc/omnivision/OmniCamera.h>
#include <mrloc/sim/PinholeCamera.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/opengl/CCylinder.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace mrloc::omnivision {

TrueSighting sightingsOf(const std::vector<mrpt::poses::CPose2D>& poses, size_t observer,
                         const OmniCameraOptions& o, const LineOfSight& clear) {
    TrueSighting out;
    const auto& me = poses[observer];
    for (size_t j = 0; j < poses.size(); ++j) {
        if (j == observer) continue;
        const double dx = poses[j].x() - me.x(), dy = poses[j].y() - me.y();
        const double dist = std::hypot(dx, dy);
        if (o.maxRange > 0 && dist > o.maxRange) continue;
        bool blocked = false;
        for (size_t k = 0; k < poses.size() && !blocked; ++k) {
            if (k == observer || k == j) continue;
            const double kx = poses[k].x() - me.x(), ky = poses[k].y() - me.y();
            const double along = (kx * dx + ky * dy) / dist;
            if (along <= 0 || along >= dist) continue;
            blocked = std::abs(kx * dy - ky * dx) / dist < o.markerRadius;
        }
        // an obstacle between the cameras (at their height) hides the band as well
        if (blocked || (clear && !clear({me.x(), me.y(), o.cameraHeight},
                                        {poses[j].x(), poses[j].y(), o.cameraHeight})))
            continue;
        out.bearings.push_back(mrpt::math::wrapToPi(std::atan2(dy, dx) - me.phi()));
        out.robots.push_back(int(j));
    }
    return out;
}

mrpt::obs::CObservationBearingRange::Ptr senseBearings(
    const std::vector<mrpt::poses::CPose2D>& poses, size_t observer, const OmniCameraOptions& o,
    mrpt::random::CRandomGenerator& rng, const LineOfSight& clear) {
    auto seen = sightingsOf(poses, observer, o, clear);
    std::vector<size_t> order(seen.bearings.size());
    std::iota(order.begin(), order.end(), 0);
    for (size_t i = order.size(); i > 1; --i)  // Fisher-Yates with MRPT's generator
        std::swap(order[i - 1], order[size_t(rng.drawUniform32bit() % i)]);
    auto obs = mrpt::obs::CObservationBearingRange::Create();
    obs->fieldOfView_yaw = float(2 * M_PI);
    obs->fieldOfView_pitch = 0;
    obs->maxSensorDistance = float(o.maxRange);
    obs->sensor_std_yaw = float(o.bearingSigma);
    obs->sensorLocationOnRobot = mrpt::poses::CPose3D(0, 0, o.cameraHeight, 0, 0, 0);
    for (size_t i : order) {
        mrpt::obs::CObservationBearingRange::TMeasurement m;
        m.range = 0;  // unknown: a camera measures directions only
        m.yaw =
            float(mrpt::math::wrapToPi(seen.bearings[i] + rng.drawGaussian1D(0, o.bearingSigma)));
        m.pitch = 0;
        m.landmarkID = -1;  // identity unknown: every robot carries the same marker
        obs->sensedData.push_back(m);
    }
    return obs;
}

struct OmniRenderer::Impl {
    OmniCameraOptions o;
    sim::WorldOptions world;
    sim::PinholeCamera camera;
    static mrpt::img::TCamera intrinsicsOf(const Panorama& pano) {
        mrpt::img::TCamera k;
        k.ncols = uint32_t(pano.viewWidth);
        k.nrows = uint32_t(pano.height);
        k.setIntrinsicParamsFromValues(pano.focal(), pano.focal(), 0.5 * pano.viewWidth,
                                       0.5 * pano.height);
        return k;
    }
    Impl(const OmniCameraOptions& opts, const sim::WorldOptions& w)
        : o(opts), world(w), camera(intrinsicsOf(opts.panorama)) {}
};

OmniRenderer::OmniRenderer(const OmniCameraOptions& o, const sim::WorldOptions& world)
    : impl_(std::make_unique<Impl>(o, world)) {}
OmniRenderer::~OmniRenderer() = default;

mrpt::img::CImage OmniRenderer::render(const std::vector<mrpt::poses::CPose2D>& poses,
                                       size_t observer) {
    const auto& o = impl_->o;
    const auto& pano = o.panorama;
    // The paper's open room: with the walls drawn behind the bands, 3 of the 10 triangles of
    // omnivision_5robots.ini were lost (doc/omnivision.md); obstacles are drawn.
    auto scene = sim::makeWorldScene(impl_->world, true);
    for (size_t j = 0; j < poses.size(); ++j) {
        if (j == observer) continue;  // the camera sits inside its own band
        auto band = mrpt::opengl::CCylinder::Create(o.markerRadius, o.markerRadius, o.markerHeight);
        band->setColor_u8(230, 20, 20);
        band->enableLight(false);  // flat colour: the detector thresholds it
        band->setLocation(poses[j].x(), poses[j].y(), o.cameraHeight - 0.5 * o.markerHeight);
        scene->insert(band);
    }
    mrpt::img::CImage strip(pano.width(), pano.height, mrpt::img::CH_RGB);
    const auto& me = poses[observer];
    for (int k = 0; k < pano.views; ++k) {
        const auto view =
            impl_->camera.render(*scene, sim::cameraPoseLooking({me.x(), me.y(), o.cameraHeight},
                                                                me.phi() + pano.viewAzimuth(k)));
        strip.drawImage(k * pano.viewWidth, 0, view);
    }
    return strip;
}

}  // namespace mrloc::omnivision
