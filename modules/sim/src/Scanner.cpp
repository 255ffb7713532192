#include <mrloc/sim/Scanner.h>

#include <cmath>

namespace mrloc::sim {

namespace {

/** An empty scan of `options.rays` beams 2 pi / N apart (MRPT spaces beams by
 *  aperture / (N - 1)). */
mrpt::obs::CObservation2DRangeScan::Ptr emptyScan(const ScannerOptions& o) {
    auto scan = mrpt::obs::CObservation2DRangeScan::Create();
    const size_t n = size_t(o.rays);
    scan->aperture = float(2 * M_PI * double(n - 1) / double(n));
    scan->rightToLeft = true;
    scan->maxRange = float(o.maxRange);
    scan->stdError = float(o.rangeSigma);
    scan->resizeScan(n);
    return scan;
}

}  // namespace

mrpt::obs::CObservation2DRangeScan::Ptr scanWorld(const World& world,
                                                  const mrpt::poses::CPose2D& pose, double height,
                                                  const ScannerOptions& o,
                                                  mrpt::random::CRandomGenerator& rng) {
    auto scan = emptyScan(o);
    scan->sensorPose = mrpt::poses::CPose3D(0, 0, height, 0, 0, 0);
    const octomap::point3d origin(float(pose.x()), float(pose.y()), float(height));
    for (size_t i = 0; i < scan->getScanSize(); ++i) {
        const double a = pose.phi() + scan->getScanAngle(i);
        octomap::point3d hit;
        const bool blocked = world.octree().castRay(
            origin, octomap::point3d(float(std::cos(a)), float(std::sin(a)), 0), hit,
            /*ignoreUnknownCells=*/true, o.maxRange);
        const double range = blocked ? double((hit - origin).norm()) : INFINITY;
        const double noise = rng.drawGaussian1D(0, o.rangeSigma);
        const bool valid = range <= o.maxRange;
        scan->setScanRange(i, float(valid ? std::max(0.0, range + noise) : o.maxRange));
        scan->setScanRangeValidity(i, valid);
    }
    return scan;
}

mrpt::obs::CObservation2DRangeScan::Ptr scanFloorPlan(const common::Polygon& plan,
                                                      const mrpt::poses::CPose2D& pose,
                                                      const ScannerOptions& o,
                                                      mrpt::random::CRandomGenerator& rng) {
    auto scan = emptyScan(o);
    const size_t n = size_t(o.rays);
    const common::TPoint2D origin{pose.x(), pose.y()};
    for (size_t i = 0; i < n; ++i) {
        const double a = pose.phi() + scan->getScanAngle(i);
        const auto hit = plan.rayCast(origin, {std::cos(a), std::sin(a)}, plan.epsilon());
        const double noise = rng.drawGaussian1D(0, o.rangeSigma);
        const bool valid = hit && *hit <= o.maxRange;
        scan->setScanRange(i, float(valid ? std::max(0.0, *hit + noise) : o.maxRange));
        scan->setScanRangeValidity(i, valid);
    }
    return scan;
}

}  // namespace mrloc::sim
