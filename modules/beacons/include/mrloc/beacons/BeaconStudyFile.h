#pragma once
// The beacon study's results (beacons.study.json in the run folder) and the study that makes
// them from the resolved run: the method-choice table on the run's own test points, coverage
// over room sizes, the fewest beacons that cover a room, the sweeps and the agents served.
#include <mrloc/beacons/BeaconLocalizer.h>
#include <mrloc/beacons/BeaconStudy.h>
#include <mrloc/common/Log.h>
#include <mrloc/sim/Scenario.h>

#include <string>
#include <vector>

namespace mrloc::beacons {

/** One receiver method and aiming at the run's test points (the method-choice table). */
struct StudyChoiceRow {
    std::string aiming, method;
    bool paper = false;       ///< seed 001's fix
    bool configured = false;  ///< the run's own [beacons] method
    std::vector<PointStats> points;
};

/** One room, beacon set, aiming and method over a grid of test points. */
struct StudyGridRow {
    std::string part;  ///< "coverage" (room side), "beam" (deg), "beacons" (count), "speed" (m/s)
    double value = 0;
    std::string variant;  ///< the heads' aiming, and the method where it is not the run's
    int beacons = 0;
    double roomX = 0, roomY = 0;
    double minReception = 0, meanError = 0, maxError = 0;
    int points = 0, pointsCovered = 0;
    bool covers = false;
};

/** The fewest beacons that cover a square room. */
struct StudyCountRow {
    double size = 0;
    std::string aiming;
    int fewest = 0;                                        ///< 0: none up to count_max
    double minReception = 0, meanError = 0, maxError = 0;  ///< with that many
};

struct BeaconStudyFile {
    std::string method;  ///< the run's receiver method, described
    double roomX = 0, roomY = 0;
    int trials = 0, choiceTrials = 0;
    CoverageCriteria criteria;
    std::string beaconsPerFix;  ///< words: how many fire per trial
    std::vector<StudyChoiceRow> choices;
    std::vector<StudyGridRow> grids;
    std::vector<StudyCountRow> counts;
    std::vector<AgentsResult> agents;

    static std::string path(const std::string& dir) { return dir + "/beacons.study.json"; }
    void write(const std::string& dir) const;
    /** Throws mrloc::Error naming the file on a malformed one. */
    static BeaconStudyFile read(const std::string& dir);
};

/** The hardware a run's study uses: its [ultrasonic] and [sensors]. */
struct StudySetup {
    StudyOptions options;
    UltrasonicOptions ultrasonic;
    SensorOptions sensors;
};

/** Runs every part `setup.options` asks for, in the run's room (`scenario`) with the run's
 *  beacons, aiming and receiver method (`run`). Deterministic for a seed, whatever the
 *  threads. */
BeaconStudyFile runStudy(const StudySetup& setup, const BeaconOptions& run,
                         const sim::ScenarioConfig& scenario, uint64_t seed,
                         const common::Log& log = common::silentLog());

}  // namespace mrloc::beacons
