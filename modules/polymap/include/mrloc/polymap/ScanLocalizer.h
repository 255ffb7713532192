#pragma once
// Global localization from real laser scans in a building's map (doc/polymap.md, "Real
// scans"): seed 002's hypothesis generation and elimination, carried from exact visibility
// polygons to what a real scanner gives (any field of view, missing returns, clutter, a
// sensor offset on the robot, unknown heading).
//
//  - A beam *agrees* with a pose when its range is within the tolerance of the range the map
//    predicts along it. A beam much *shorter* is clutter (a person, a chair: allowed, not
//    counted either way). A beam much *longer* passes through a wall of the map: evidence
//    against the pose. The agreement is the fraction of returning beams that agree.
//  - Hypotheses from the first scan: every free position on a grid, every heading (or the
//    known one), scored against a 360-degree profile of ranges cast once per position; the
//    best distinct candidates refined by pattern search on a truncated quadratic cost; those
//    within `keepMargin` of the best agreement kept, ranked.
//  - Passive elimination: each later scan, the hypotheses moved by the odometry since the
//    last and refined locally, a hypothesis dropped when it trails the best by more than the
//    margin on two scans running, or sees through walls. One left: localized; it is then
//    tracked scan by scan at a bounded cost.
#include <mrloc/polymap/WallMap.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>

#include <optional>
#include <vector>

namespace mrloc::polymap {

using mrpt::math::TPose2D;

/** One scan's beams in the robot's frame. */
struct ScanBeamSet {
    std::vector<double> angle;  ///< direction in the robot's frame (rad), the sensor's yaw added
    std::vector<double> range;  ///< m; NaN: no return (invalid flag, or at the max range)
    TPose2D sensor;             ///< the sensor's pose on the robot (x, y, yaw)
    double maxRange = 0;
    double sigma = 0;  ///< the scan's stdError
    size_t returns = 0;
    double time = 0;
};

/** Any aperture and resolution; throws mrloc::Error naming the scan if it has fewer than 8
 *  beams or a range that is not finite. */
ScanBeamSet beamSetOf(const mrpt::obs::CObservation2DRangeScan& scan);

/** The beam model a pose's scan likelihood is scored with (Thrun, Burgard and Fox,
 *  "Probabilistic Robotics" 2005, sec. 6.3, MRPT's beam model for range scans): a returning
 *  beam of range r where the map predicts z* has the density
 *    hit N(r; z*, sigma) + shortReading / z* [r < z*] + random / maxRange,
 *  sigma half the beam tolerance. Short readings (people, furniture in front of a mapped
 *  wall) are any range in front of the wall alike; random ones (glass, a door open since the
 *  map was made: a beam through a mapped wall) any range at all. A real map's beams through
 *  walls are thus evidence against a pose, weighed with the rest, not a share that refuses
 *  it. */
struct BeamModel {
    static constexpr double hit = 0.75, shortReading = 0.2, random = 0.05;
    /** A pose whose beams through walls are more than the random share makes likely is
     *  refused: the chance of as many, out of its returning beams, each random with
     *  probability `random`, below this (one-sided binomial tail). SENA's first scan on
     *  malaga-cs-fac-building: 309 returning beams, refused from 29 (9.4 %) on; the true
     *  pose has 19 (6.1 %). localization_demo's first scan in the 20 x 12 m hall (a wrong
     *  map): its best pose has 58 of 359 (16 %; refused from 33). */
    static constexpr double throughTail = 1e-3;
};

/** The model explains `through` beams through walls out of `returns` (BeamModel::throughTail). */
bool throughBeamsAreRandom(size_t through, size_t returns);

struct BeamAgreement {
    size_t returns = 0, agree = 0, through = 0;
    /** Sum over the returning beams of log(p(r | pose, map) / p0(r)), p the beam model and p0
     *  = 1 / maxRange the scan explained without the map (any range alike): positive when
     *  the map explains the scan better than noise does, the refusal's test. */
    double logRatio = 0;
    double meanLogRatio() const { return returns ? logRatio / double(returns) : 0; }
    /** Shorter beams where the map has a wall farther along (clutter in front of it), as
     *  opposed to beams into space the map leaves empty (unknown beyond the scan's reach). */
    size_t clutter = 0;
    double cost = 0;  ///< sum of min(e^2, tolerance^2): the refinement's
    double agreement() const { return returns ? double(agree) / double(returns) : 0; }
    double throughFraction() const { return returns ? double(through) / double(returns) : 0; }
    double clutterFraction() const { return returns ? double(clutter) / double(returns) : 0; }
};

/** The robot at `robot`: each `stride`-th beam against the map, within `tolerance`. */
BeamAgreement scoreScan(const WallMap& map, const ScanBeamSet& beams, const TPose2D& robot,
                        double tolerance, size_t stride = 1);
/** Only the counts and the cost (no logRatio): what the pattern search steps on. */
BeamAgreement costOfScan(const WallMap& map, const ScanBeamSet& beams, const TPose2D& robot,
                         double tolerance, size_t stride);

struct ScanLocalizerOptions {
    double tolerance = 0.2;      ///< m: a beam agrees within this
    double positionStep = 0.25;  ///< m: the first scan's search grid
    /** The step grows until the free space (or the region) holds at most this many grid
     *  positions: the first scan's cost stays bounded in a large building. */
    size_t maxPositions = 20000;
    double headingStep = 2;         ///< deg: the first scan's headings
    std::optional<double> heading;  ///< rad: known heading (searched within 2 steps)
    double keepMargin = 0.1;    ///< agreement below the best by more: not a hypothesis / dropped
    double minAgreement = 0.3;  ///< agreement below this: never a hypothesis
    /** Fraction of beams through walls above this: rejected. 1 (off) by default: the beam
     *  model weighs them (BeamModel); a pose is refused when the map explains its scan no
     *  better than noise (BeamAgreement::logRatio <= 0). */
    double maxThrough = 1;
    /** Fraction of beams stopped short in front of a mapped wall above this: rejected. The
     *  truth of MRPT's two logs has 0.03 and 0.11; the same scans in a wrong map 0.48-0.55. */
    double maxClutter = 0.35;
    size_t maxHypotheses = 100;  ///< the best this many are kept (bounds each scan's cost)
    double mergeDistance = 0.5;  ///< m: candidates nearer (and within mergeAngle) are one
    double mergeAngle = 10;      ///< deg
    /** The robot's position is searched in this box only (pf-localization's init_PDF box);
     *  none: the whole map. */
    std::optional<std::pair<TPoint2D, TPoint2D>> region;
};

struct PoseHypothesis {
    TPose2D pose;  ///< the robot's
    BeamAgreement score;
    int trailing = 0;     ///< scans running it trailed the best by more than the margin
    size_t rank = 0;      ///< 1-based, among the first scan's hypotheses
    double evidence = 0;  ///< agreements summed over the scans it lived: kept when two merge
    std::vector<std::pair<double, TPose2D>> path;  ///< (time, pose) at every scan it lived
};

struct SearchStats {
    size_t positions = 0, headings = 0, poses = 0, refined = 0;
    double positionStep = 0;  ///< m: the grid step used
    double runnerUp = 0;  ///< agreement of the best pose not kept (how near the next place came)
};

/** Hypotheses from one scan, best first. */
std::vector<PoseHypothesis> globalHypotheses(const WallMap& map, const ScanBeamSet& beams,
                                             const ScanLocalizerOptions& options,
                                             SearchStats* stats = nullptr);

/** Pattern search from `start` (steps halving from step / angleStep down to 1 cm / 0.1 deg)
 *  on the truncated quadratic cost; the result scored with every beam. */
PoseHypothesis refinePose(const WallMap& map, const ScanBeamSet& beams, const TPose2D& start,
                          double tolerance, double step, double angleStep, size_t stride);

/** Hypotheses of one robot, eliminated scan by scan as it drives (the passive elimination). */
class PassiveElimination {
 public:
    PassiveElimination(const WallMap& map, const ScanLocalizerOptions& options,
                       std::vector<PoseHypothesis> hypotheses, double time);
    /** A later scan, after `motion` (the odometry's increment since the last scan) and
     *  `travelled` metres of odometry path in total since the first scan. */
    void update(const TPose2D& motion, double travelled, const ScanBeamSet& beams);

    const std::vector<PoseHypothesis>& live() const { return live_; }
    size_t initial() const { return initial_; }
    std::optional<double> uniqueTime, uniqueDistance;  ///< when one was left (s since start, m)
    size_t scans = 1;

 private:
    const WallMap* map_;
    ScanLocalizerOptions options_;
    std::vector<PoseHypothesis> live_;
    size_t initial_ = 0;
    double startTime_ = 0;
};

}  // namespace mrloc::polymap
