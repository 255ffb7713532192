#pragma once
// The formation marching along a route, and the dead-reckoning robot it is compared with
// (seed 003 sec. 5), in the error-model mode: each move ends where the paper's measured
// per-step errors put it (seed 003 fig. 11), for fast Monte Carlo.
#include <mrloc/formation/DeadReckoning.h>
#include <mrloc/formation/Formation.h>
#include <mrloc/formation/PaperValues.h>
#include <mrpt/random/RandomGenerators.h>

#include <vector>

namespace mrloc::formation {

/** Where a move really ends, around the vertex that the real beacons define (seed 003
 *  fig. 11): lateral (along the new triangle's base) and longitudinal (across it) errors.
 *  The paper gives each axis's mean absolute error and its standard deviation; the
 *  magnitude is drawn from the gamma distribution with that mean and deviation (positive,
 *  skewed like the paper's CDFs), its sign fair. */
struct VertexErrorModel {
    double lateralMean = paper::kLateralMean, lateralSd = paper::kLateralSd;  ///< m
    double longitudinalMean = paper::kLongitudinalMean;                       ///< m
    double longitudinalSd = paper::kLongitudinalSd;                           ///< m
};

/** A magnitude from gamma(mean, sd) (Marsaglia-Tsang on MRPT's generator), signed fairly. */
double drawAxisError(double mean, double sd, mrpt::random::CRandomGenerator& rng);

struct MarchOptions {
    FormationOptions formation;
    double wheelRadius = 0.035;  ///< m: speed = wheelRadius x wheelSpeed (the paper's R was lost)
    double wheelSpeed = paper::kWheelSpeedFast;  ///< rad/s, the intended wheel speed
    size_t maxMoves = 100000;                    ///< a route that needs more is refused
    /** How a move's error carries on to the next (doc/formation.md). The paper says only that
     *  the per-step errors "accumulate with each successive movement". */
    enum class Carry {
        /** The new vertex moves with the mean offset of its two base beacons (the robot
         *  sets itself against them), plus its own error: the default. */
        Base,
        /** The real anchor reflected across the real base, plus the error. */
        Reflection,
        /** Where Algorithm 1 converges among the real beacons, plus the error. */
        AlgorithmOne
    } carry = Carry::Base;
};

/** Where seed 003 Algorithm 1 leaves the moving robot, given the real beacons: the anchor on
 *  the rear camera's axis, base beacons b1 and b2 at +-d_t pixels from it (d_t set for a
 *  perfect triangle of `side`). For a perfect triangle, the reflection b1 + b2 - anchor. */
TPoint2D algorithmOneVertex(const TPoint2D& b1, const TPoint2D& b2, const TPoint2D& anchor,
                            double side);

/** A step's own error (seed 003 fig. 11): its true end against the true anchor reflected
 *  across the true base (the vertex of a perfect triangle on them), along the base from b1
 *  to b2 (lateral) and across it (longitudinal), m. */
struct StepError {
    double lateral = 0, longitudinal = 0;
};
StepError stepError(const TPoint2D& b1, const TPoint2D& b2, const TPoint2D& anchor,
                    const TPoint2D& end);

/** Where a move really ends (the error-model mode): the vertex the carry model gives among
 *  the real beacons, plus the per-step error drawn along and across the real base.
 *  `ideal` and `actual`: every robot's believed and real position. */
TPoint2D moveEnd(const Move& move, const std::vector<TPoint2D>& ideal,
                 const std::vector<TPoint2D>& actual, const MarchOptions& options,
                 const VertexErrorModel& errors, mrpt::random::CRandomGenerator& rng);

/** One move of the march. */
struct MoveRecord {
    double time = 0;  ///< s, when the move ended
    size_t robot = 0;
    TPoint2D ideal;   ///< where the robot believes it is: the perfect vertex
    TPoint2D actual;  ///< where it is
    double error() const { return (actual - ideal).norm(); }
};

struct MarchResult {
    std::vector<MoveRecord> moves;
    std::vector<TPoint2D> ideal, actual;  ///< every robot at the end
    bool arrived = false;                 ///< every waypoint reached
    /** Seed 003's error at the destination: the last mover's actual against ideal vertex. */
    double finalError() const { return moves.empty() ? 0 : moves.back().error(); }
};

/** N robots from initialStrip march through `route` (waypoints; each counts as reached
 *  when a robot's vertex is within side / sqrt(3) of it: every point is that near a lattice
 *  vertex). Each move's real end is where options.carry says (the ideal target shifted by
 *  the base's errors, the reflection of the real anchor across the real base, or Algorithm
 *  1's vertex on the real base), plus the error model's draw. Time: each move's path at the
 *  robot's speed. */
MarchResult march(size_t robots, const std::vector<TPoint2D>& route,
                  const std::vector<Obstacle>& obstacles, const MarchOptions& options,
                  const VertexErrorModel& errors, mrpt::random::CRandomGenerator& rng);

}  // namespace mrloc::formation
