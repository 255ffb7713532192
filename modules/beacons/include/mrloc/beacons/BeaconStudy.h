#pragma once
// What a beacon set covers and how many agents it serves ([beacons_study], issue 30): a Monte
// Carlo of the beacon system's trials at test points, with the simulator's shot physics
// (simulateShot: the [ultrasonic] link as calibrated on seed 001 Table 3, the [sensors] noise)
// and the receiver's fix of mode = fixes (BeaconTracker::fixOnly). Seed 001 claims that active
// heads cover a wider area with about half the beacons of fixed ones (abstract, section 1),
// that one set should cover 6 m x 6 m (section 6), and that heads turned to different agents
// serve them at once "with no interference" (section 1); this measures each.
//
// A trial: the RF beacon picks the beacons_per_fix beacons whose bursts the link predicts
// loudest at the receiver's reported position, their heads aim (active: at the receiver;
// fixed: at each head's fixed aim point), each fires shots_per_beacon times, one shot per
// shot_interval, while the receiver moves at `speed`; the fix is stamped at the last shot.
// Heads are taken as already pointing at the reported position (an active head follows its
// robot between trials), so slewing costs no time here; the closed-loop simulator has it.
#include <mrloc/beacons/BeaconMap.h>
#include <mrloc/beacons/BeaconRanging.h>
#include <mrloc/beacons/BeaconTracker.h>
#include <mrloc/beacons/Multilateration.h>
#include <mrloc/beacons/PaperValues.h>
#include <mrloc/beacons/Ultrasonic.h>
#include <mrloc/common/IniSection.h>
#include <mrloc/common/KeyTable.h>
#include <mrpt/math/TPoint2D.h>

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace mrloc::beacons {

/** The receiver's method: the fix of mode = fixes as [beacons] configures it. */
struct StudyMethod {
    bool threeD = false;
    Residual residual = Residual::Range;
    bool delayCompensation = false;
    int shotsPerBeacon = 1;
    bool jitterWeights = false;
    /** Seed 001's fix (eq. 4-10): 3-D, squared residual, one shot, no compensation. */
    static StudyMethod paper() { return {true, Residual::SquaredRange, false, 1, false}; }
    bool operator==(const StudyMethod& o) const {
        return threeD == o.threeD && residual == o.residual &&
               delayCompensation == o.delayCompensation && shotsPerBeacon == o.shotsPerBeacon &&
               jitterWeights == o.jitterWeights;
    }
    /** "3-D squared, 1 shot" style words for tables. */
    std::string describe() const;
};

/** A room, its ceiling beacons and how their heads aim. */
struct StudyRoom {
    double sizeX = 6, sizeY = 6;
    BeaconMap beacons;
    bool active = true;  ///< heads aim at the receiver; else each at fixedAim (else straight down)
    std::map<int, Eigen::Vector3d> fixedAim;
};

/** What stays the same across a study's trials. */
struct StudyHardware {
    UltrasonicOptions ultrasonic;
    SensorOptions sensors;
    double receiverHeight = 0.5;  ///< m above the floor; the 2-D fix knows it
    double shotInterval = 0.03;   ///< s between two shots
    int beaconsPerFix = 4;        ///< beacons fired per trial (the loudest predicted)
    double speed = 0;             ///< receiver speed (m/s), heading drawn per trial
    /** The run's [beacons] fix options (range_sigma, max_gdop, mirror); the method sets the
     *  residual, the known height and the delay model. */
    TrackerOptions tracker;
};

struct TrialOutcome {
    bool fixed = false;  ///< a fix was made
    double error = 0;    ///< its horizontal error against the receiver at the last shot (m)
};

/** One trial at `at` (floor coordinates). */
TrialOutcome runTrial(const StudyRoom& room, const StudyHardware& hw, const StudyMethod& method,
                      const mrpt::math::TPoint2D& at, mrpt::random::CRandomGenerator& rng);

/** The pass mark of a covered room: every test point fixed in at least `reception` of its
 *  trials (seed 001's 90 %) with every error under `errorBound` (its next goal, 50 mm). */
struct CoverageCriteria {
    double reception = paper::kGoodReception;
    double errorBound = paper::kGoalMaxErrorM;
};

struct PointStats {
    mrpt::math::TPoint2D at;
    int trials = 0, fixes = 0;
    double meanError = 0, maxError = 0;  ///< over the fixes (0 without one)
    double reception() const { return trials ? double(fixes) / trials : 0.0; }
};

struct CoverageResult {
    std::vector<PointStats> points;
    bool complete = true;  ///< false: stopped at the first failing point (stats partial)
    double minReception() const;
    double meanError() const;  ///< over every fix
    double maxError() const;
    /** The points that meet the criteria. */
    size_t pointsCovered(const CoverageCriteria& c) const;
    bool covers(const CoverageCriteria& c) const {
        return complete && !points.empty() && pointsCovered(c) == points.size();
    }
};

/** `trials` trials at each point, on common::threadCount() threads; each point's trials are
 *  drawn from its own generator (seeded from `seed` and the point's index), so the result does
 *  not depend on the threads. With stopAtFailure the first point found failing ends it
 *  (complete = false), for searches that need only the verdict. */
CoverageResult evaluateCoverage(const StudyRoom& room, const StudyHardware& hw,
                                const StudyMethod& method,
                                const std::vector<mrpt::math::TPoint2D>& points, int trials,
                                uint64_t seed, const CoverageCriteria& criteria,
                                bool stopAtFailure = false);

/** Test points on a square grid of `spacing`, `wallMargin` from the walls, centred. */
std::vector<mrpt::math::TPoint2D> testGrid(double sizeX, double sizeY, double spacing,
                                           double wallMargin);

/** `n` ceiling beacons spread over the room: the centroids of a centroidal Voronoi
 *  tessellation (Lloyd's iteration from a Halton start, on a fine grid of the floor), the
 *  layout that minimises the mean squared distance from a floor point to its nearest
 *  beacon. Ids 1..n. */
BeaconMap spreadBeacons(double sizeX, double sizeY, double ceiling, int n);

/** Fixed heads of a coverage layout: each straight down (its Voronoi cell's centre). */
std::map<int, Eigen::Vector3d> straightDown(const BeaconMap& beacons);

/** A sizeX x sizeY room with `n` spread beacons on the ceiling, heads active or, fixed,
 *  straight down. */
StudyRoom spreadRoom(double sizeX, double sizeY, double ceiling, int n, bool active);

/** How the RF beacon shares the ultrasonic channel between agents. */
enum class Channel {
    Shared,        ///< one agent per epoch, in turn (mrloc's simulator)
    Simultaneous,  ///< several per epoch, heads turned to each, zones apart (seed 001 sec. 1)
    Unchecked,     ///< several per epoch without the zone check: what interference costs
};
const char* channelName(Channel c);

/** Serving several agents (seed 001 section 1): per epoch the RF beacon takes agents longest
 *  waiting first; on a shared channel one, otherwise every agent it can give its own loudest
 *  beacons (not taken by another, their geometry no worse than 1.5 times the GDOP of the
 *  agent's own loudest set) such that, with zones checked, no beacon of one is predicted
 *  audible at another's receiver: its mean level there below the detection threshold by 3
 *  fading sigmas. The shots of one slot fly at once; a receiver that hears several
 *  triggers on the earliest (the tone decoder cannot tell them apart), so an interfering
 *  burst that arrives first becomes a wrong range. Agents stand at random places at least
 *  1 m apart. */
struct AgentsResult {
    int agents = 1;
    Channel channel = Channel::Shared;
    std::string aiming;   ///< words, set by the caller
    double seconds = 0;   ///< simulated channel time per layout
    int layouts = 0;      ///< random placements of the agents
    double meanRate = 0;  ///< fixes per second per agent, mean over agents and layouts
    double minRate = 0;   ///< the least served agent's
    double meanAgentsPerEpoch = 0;
    double meanError = 0, maxError = 0;  ///< over every fix (m)
    size_t fixes = 0, shots = 0;
    size_t interfered = 0;  ///< shots whose reading came from another agent's burst
    size_t overBound = 0;   ///< fixes with an error over the bound
};
AgentsResult serveAgents(const StudyRoom& room, const StudyHardware& hw, const StudyMethod& method,
                         int agents, Channel channel, double seconds, int layouts, uint64_t seed,
                         double errorBound);

/** Section [beacons_study]: which studies run after localization, and their sizes. */
struct StudyOptions {
    /** Upper bounds (doc/errors.md): they size the study's loops. */
    static constexpr int kMaxTrials = 10000, kMaxBeacons = 64, kMaxAgents = 32, kMaxValues = 32;
    static constexpr double kMaxSide = 50;

    bool enabled = false;                 ///< the section is there
    int choiceTrials = 100;               ///< per test point, the method-choice table (0: none)
    double grid = 0.5, wallMargin = 0.5;  ///< test points (m)
    int trials = 10;                      ///< per test point (seed 001: 10)
    CoverageCriteria criteria;
    double ceiling = 2.5, receiverHeight = 0.5;  ///< m
    int beaconsPerFix = 4;
    std::vector<double> coverageSizes{3, 4, 5, 6, 7, 8};  ///< square rooms (m)
    int coverageBeacons = paper::kSectionBeacons;         ///< one section
    std::vector<double> countSizes{3, 4, 5, 6, 8};
    int countMax = 48;
    std::vector<double> beamAngles{20, 30, 40, 50, 60, 70, 80};  ///< deg
    std::vector<double> beaconCounts{3, 4, 5, 6, 8, 10, 12};
    std::vector<double> speeds{0, 0.1, 0.2, 0.3, 0.5, 1.0};  ///< m/s
    std::vector<double> agents{1, 2, 4, 8};
    double agentsSize = 6;  ///< square room of the agents study (m)
    int agentsBeacons = 12;
    double agentsTime = 10;  ///< s of channel time per layout
    int agentsLayouts = 5;

    /** Every key: name, member, bounds, unit, doc (doc/ini.md's table is made from it). */
    static const common::KeyTable<StudyOptions>& keys();
    void load(const mrpt::config::CConfigFileBase& ini, const std::string& section);
    void save(mrpt::config::CConfigFileBase& target, const std::string& section) const;
    /** Trials the whole study runs at most (the work estimate), for a run of `runPoints`
     *  test points in a room of roomX x roomY m. */
    double trialsAtMost(size_t runPoints, double roomX, double roomY) const;
};

}  // namespace mrloc::beacons
