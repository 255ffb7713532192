#include <mrloc/sim/Scanner.h>

#include <cmath>

namespace mrloc::sim {

mrpt::obs::CObservation2DRangeScan::Ptr scanFloorPlan(const common::Polygon& plan,
                                                      const mrpt::poses::CPose2D& pose,
                                                      const ScannerOptions& o,
                                                      mrpt::random::CRandomGenerator& rng) {
    auto scan = mrpt::obs::CObservation2DRangeScan::Create();
    const size_t n = size_t(o.rays);
    scan->aperture = float(2 * M_PI * double(n - 1) / double(n));
    scan->rightToLeft = true;
    scan->maxRange = float(o.maxRange);
    scan->stdError = float(o.rangeSigma);
    scan->resizeScan(n);
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
