#pragma once
// Position fixes from beacon time-of-flight ranges (seed 001 section 4).
//
// The paper's solver is Gauss-Newton on the residuals of squared ranges, eq. (6)
// f_i = ||x - x_i||^2 - r_i^2, with the pseudo-inverse step of eq. (10). The variant on the
// ranges themselves, f_i = ||x - x_i|| - r_i, is the maximum-likelihood fix for Gaussian
// range noise and is better conditioned (its Jacobian rows are unit vectors). Both start
// from a closed-form linear solution, so no initial guess is needed.
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace mrloc::beacons {

struct RangeMeasurement {
    Eigen::Vector3d beacon;  ///< beacon position (m)
    double range = 0;        ///< measured distance (m)
    int beaconId = -1;
    /** This range's own standard deviation (m), for a fix that weights each range by it;
     *  0: MultilaterationOptions::rangeSigma, as every range without one. */
    double sigma = 0;
};

enum class Residual {
    SquaredRange,  ///< seed 001 eq. (6): f_i = ||x - x_i||^2 - r_i^2
    Range          ///< f_i = ||x - x_i|| - r_i
};

/** Which of the two mirror solutions to keep when all beacons lie in one plane (three
 *  beacons always do; ceiling-mounted ones usually do). */
enum class MirrorRule {
    Below,         ///< smaller z: beacons on the ceiling, receivers under them (seed 001)
    Above,         ///< larger z
    NearestToHint  ///< closer to MultilaterationOptions::hint (e.g. the last estimate)
};

struct MultilaterationOptions {
    Residual residual = Residual::Range;
    int maxIterations = 20;
    double tolerance = 1e-10;           ///< stop when the step is shorter (m, relative to 1 + |x|)
    std::optional<double> knownHeight;  ///< 2-D variant: the receiver's z is known
    MirrorRule mirror = MirrorRule::Below;
    std::optional<Eigen::Vector3d> hint;
    double rangeSigma = 0.01;  ///< range noise std. dev. (m), scales the covariance
    double maxGdop = 1e3;      ///< a fix with a larger GDOP is reported IllConditioned
};

enum class FixStatus {
    Ok,
    InvalidInput,       ///< NaN, infinite or negative range or beacon coordinate
    TooFewRanges,       ///< fewer than 3 ranges
    CoincidentBeacons,  ///< the beacons are (nearly) one point
    CollinearBeacons,   ///< a circle (3-D) or an unresolvable mirror pair (2-D) of solutions
    IllConditioned,     ///< e.g. the receiver in the plane of three beacons: GDOP too large
    AmbiguousMirror,    ///< beacons in a vertical plane and no hint to pick a side
    NotConverged
};

const char* toString(FixStatus s);

struct Fix {
    FixStatus status = FixStatus::InvalidInput;
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  ///< first order, from rangeSigma
    double gdop = 0;         ///< sqrt(trace((H^T H)^-1)), H: unit line-of-sight rows
    double rmsResidual = 0;  ///< RMS of ||x - x_i|| - r_i at the solution (m)
    int iterations = 0;
    /** Coplanar beacons: the other solution, mirrored through the beacons' plane. */
    bool mirrorAmbiguous = false;
    Eigen::Vector3d mirrorPosition = Eigen::Vector3d::Zero();

    bool ok() const { return status == FixStatus::Ok; }
};

Fix multilaterate(const std::vector<RangeMeasurement>& ranges,
                  const MultilaterationOptions& options = {});

/** A fix tolerant of one bad range: if the all-ranges fix has an RMS residual above
 *  `outlierThreshold` and at least 4 ranges (5 in 3-D) remain, the best leave-one-out fix is
 *  returned instead; `rejectedIndex` tells which range was left out (-1 if none). Up to 12
 *  ranges every one is tried; of more, the 12 the linearised fit finds most suspect
 *  (largest r_i^2 / (1 - h_ii)), so the cost is O(n log n) in the ranges. */
Fix robustMultilaterate(const std::vector<RangeMeasurement>& ranges,
                        const MultilaterationOptions& options, double outlierThreshold,
                        int* rejectedIndex = nullptr);

/** sigma * sqrt(trace((H^T H)^-1)) at the true position: the Cramer-Rao bound on the RMS
 *  position error of any unbiased fix with range noise sigma. */
double cramerRaoBound(const std::vector<Eigen::Vector3d>& beacons, const Eigen::Vector3d& truth,
                      double sigma, bool knownHeight = false);

}  // namespace mrloc::beacons
