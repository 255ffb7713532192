#pragma once
// Beyond the paper: a least-squares layout over every identified bearing and every
// measured distance (the conventional method's |AB|, the proposed method's odometers),
// with its covariance. Unknowns are each robot's position and heading at each instant; a
// stopped robot (A and B of the proposed method) has one pose for all instants. The frame
// is the paper's: A at the origin, B on the x axis. Gauss-Newton from the paper's layout.
#include <mrloc/omnivision/Geometry.h>
#include <mrloc/omnivision/TriangleSearch.h>

#include <functional>
#include <optional>
#include <vector>

namespace mrloc::omnivision {

/** A measured distance between robot i at instant si and robot j at instant sj. */
struct DistanceMeasurement {
    size_t si = 0;
    int i = 0;
    size_t sj = 0;
    int j = 0;
    double distance = 0, sigma = 0;
};

struct RefinementProblem {
    std::vector<Snapshot> snapshots;                        ///< the instants
    std::vector<Labels> labels;                             ///< per instant
    std::vector<std::vector<std::optional<Vec2>>> initial;  ///< [instant][robot]
    std::vector<int> stationary;  ///< robots that did not move between the instants
    std::vector<DistanceMeasurement> distances;
    double bearingSigma = 0.1 * M_PI / 180;  ///< rad
    /** If set, a bearing's sigma from where it is in the camera's image (a bearing in the
     *  robot frame, rad): a rendered strip's pixels span less angle off a view's axis. */
    std::function<double(double)> bearingSigmaAt;
    /** The same camera and the same still target at two instants give the same image: its
     *  bearing is one measurement, not two (rendered cameras; a real camera's noise would
     *  differ between the frames). */
    bool stillViewsRepeat = false;
    int a = 0, b = 1;  ///< the frame: A at (0,0), B on the x axis
};

struct RefinedLayout {
    std::vector<std::vector<std::optional<Vec2>>> position;   ///< [instant][robot]
    std::vector<std::vector<std::optional<double>>> heading;  ///< [instant][robot], rad
    /** [instant][robot]: of (x, y, heading), m^2, m rad, rad^2; zero where the frame fixes a
     *  coordinate (A's x and y, B's y). */
    std::vector<std::vector<Eigen::Matrix3d>> covariance;
    double rmsBearingResidual = 0;  ///< rad
    size_t bearings = 0;            ///< measurements used
    int iterations = 0;
};

/** Throws mrloc::Error if A or B is not placed at the first instant or the problem is
 *  singular (a robot constrained by fewer than two bearings, no distance). */
RefinedLayout refineLayout(const RefinementProblem& p);

}  // namespace mrloc::omnivision
