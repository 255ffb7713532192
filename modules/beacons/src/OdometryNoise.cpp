#include <mrloc/beacons/OdometryNoise.h>

#include <cmath>

namespace mrloc::beacons {

Eigen::Matrix3d OdometryNoise::of(const mrpt::poses::CPose2D& delta) const {
    const double d = std::hypot(delta.x(), delta.y()), turn = std::abs(delta.phi());
    const double sxy = perMetre * d + 1e-4;
    const double sphi = phiPerRad * turn + phiPerMetre * d + 1e-4;
    // the walk: at 67 Hz the per-reading terms alone add up to 5 % of their sd over a metre,
    // while velocity commands integrated (MRCLAM) drift far more than that
    const double vxy = sxy * sxy + walkXY * walkXY * d;
    const double vphi =
        sphi * sphi + walkPhiPerRad * walkPhiPerRad * turn + walkPhiPerMetre * walkPhiPerMetre * d;
    return Eigen::Vector3d(vxy, vxy, vphi).asDiagonal();
}

}  // namespace mrloc::beacons
