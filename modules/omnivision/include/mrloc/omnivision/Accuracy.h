#pragma once
// Monte Carlo accuracy of the methods on a known layout (seed 000 gives no figures): the
// relative error of all pairwise distances against the angle noise (0.05, 0.1, 0.5 deg)
// and against the odometer (or LiDAR) noise, for the paper's solution and after the
// least-squares refinement. Bearings are drawn directly (the simulator's bearings mode)
// for the sightings of a real run, so visibility is the run's.
#include <mrloc/common/Log.h>
#include <mrloc/omnivision/TriangleSearch.h>
#include <mrpt/poses/CPose2D.h>

#include <string>
#include <vector>

namespace mrloc::omnivision {

struct AccuracyLayout {
    std::vector<mrpt::poses::CPose2D> before, after;      ///< true poses at t_b and t_e
    std::vector<std::vector<int>> seenBefore, seenAfter;  ///< [observer] -> robots seen
    bool proposed = true;                                 ///< else conventional (after only)
    int a = 0, b = 1;                                     ///< stopped or measured pair
};

struct AccuracyPoint {
    std::string axis;          ///< "angle" or "distance" (the one varied)
    double angleSigmaDeg = 0;  ///< bearing noise
    double distanceSigma = 0;  ///< relative odometer (LiDAR) noise
    double paper = 0;          ///< mean over trials of the median relative distance error
    double refined = 0;        ///< same after the refinement
    int trials = 0, failures = 0;
};

/** Runs `trials` trials per noise level; deterministic for a seed. */
std::vector<AccuracyPoint> accuracySweep(const AccuracyLayout& layout, int trials,
                                         unsigned long seed,
                                         const common::Log& log = common::silentLog());

}  // namespace mrloc::omnivision
