#pragma once
// The noise of one odometry increment, as the beacon tracker's EKF and its particle start-up
// both take it (doc/beacons.md, "Odometry noise"): per reading, in proportion to the
// increment (MRPT's Gaussian motion model, and mrloc's simulator), plus a random walk along
// the path whose variance grows with the distance and the turn whatever the reading rate.
#include <mrpt/poses/CPose2D.h>

#include <Eigen/Core>

namespace mrloc::beacons {

struct OdometryNoise {
    double perMetre = 0.05, phiPerRad = 0.05, phiPerMetre = 0.02;  ///< per reading
    double walkXY = 0, walkPhiPerRad = 0, walkPhiPerMetre = 0;     ///< per sqrt(m), sqrt(rad)

    /** Variances of x, y (robot frame) and phi of the increment `delta`, on the diagonal. */
    Eigen::Matrix3d of(const mrpt::poses::CPose2D& delta) const;
};

}  // namespace mrloc::beacons
