// A run's work as a whole (method/Work.h, doc/errors.md "Work"): the budget's arithmetic, and
// runs whose keys are each allowed but whose product is not, refused with one line before
// anything is written, or announced with their estimate.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/method/Work.h>
#include <mrloc/sim/Scenario.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <filesystem>
#include <optional>
#include <regex>
#include <set>

#include "AllMethods.h"
#include "MrlocCli.h"
#include "RunSetup.h"
#include "TestPaths.h"

using namespace mrloc;
using namespace mrloc::testing_cli;
namespace fs = std::filesystem;

namespace {

method::WorkItem item(const std::string& keys, double seconds, bool parallel = false) {
    method::WorkItem w;
    w.what = "a part";
    w.keys = keys;
    w.seconds = seconds;
    w.parallel = parallel;
    return w;
}

/** The announcement `mrloc run` would print for the INI on 2 cores, if any. */
std::optional<std::string> announced(const method::Registry& registry, const std::string& ini,
                                     bool localizing = true, bool simulating = true) {
    const auto setup = app::loadSetup(registry, ini, std::nullopt, simulating);
    return method::checkWork(app::workOf(setup, simulating, localizing), 2);
}

std::string messageOf(const std::vector<method::WorkItem>& items, unsigned cores) {
    try {
        method::checkWork(items, cores);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(Work, TheBudgetNamesTheHeaviestPartsKeys) {
    using B = method::WorkBudget;
    EXPECT_FALSE(method::checkWork({}, 2));
    EXPECT_FALSE(method::checkWork({item("[a] x", B::kAnnounceSeconds)}, 2));
    // long: announced with the estimate and the part that weighs most
    const auto line =
        method::checkWork({item("[a] x", 20), item("[b] y", 100, true), item("[c] z", 30)}, 2);
    ASSERT_TRUE(line);
    EXPECT_EQ(*line, "this run: about 1.7 min on 2 cores, most of it a part ([b] y)");
    // a parallel part counts once per core; beyond the budget, refused by its keys
    EXPECT_EQ(messageOf({item("[b] y", 1.5 * B::kSeconds, true)}, 2), "");
    const std::string slow =
        messageOf({item("[a] x", 10), item("[b] y", 3 * B::kSeconds, true)}, 2);
    EXPECT_EQ(slow.rfind("[b] y: a part would take about 9.0 h on 2 cores", 0), 0u) << slow;
    auto big = item("[d] w", 1);
    big.bytes = 2 * B::kBytes;
    EXPECT_EQ(messageOf({big}, 2).rfind("[d] w: a part would write about 8.0 GB", 0), 0u);
    auto huge = item("[e] v", 1);
    huge.memory = 2 * B::kMemory;
    EXPECT_EQ(messageOf({huge}, 2).rfind("[e] v: a part would hold about 2.0 GB at once", 0), 0u);
}

TEST(Work, AProductOfAllowedKeysBeyondTheBudgetIsRefusedBeforeAnythingIsWritten) {
    // each key allowed: 1000 Hz, 1e5 rays; together 120 s x 1000 Hz x 1e5 rays, about 42 GB
    // of rawlog (the issue's 10 Hz wrote 381 MB in 55 s)
    const std::string ini = writeIniFrom(
        writeIniFrom(config("polymap_steps"), "work_scans", "duration = 0.1", "duration = 120"),
        "work_scans", "scan_rays         = 1440", "scan_rays = 100000\nscan_rate = 1000");
    const std::string out = tmp("work_scans");
    for (const std::string verb : {"simulate", "run"}) {
        const auto r = mrlocCmd(verb + " " + ini + " --out " + out);
        EXPECT_EQ(r.code, 1) << r.output;
        EXPECT_EQ(r.output.rfind("mrloc " + verb + ": error: ", 0), 0u) << r.output;
        EXPECT_NE(r.output.find("[polymap] scan_rate x scan_rays, the vertices (steps x branches_per_step), x "
                              "[scenario] duration: "),
                  std::string::npos)
            << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
        EXPECT_FALSE(fs::exists(out));
    }
}

TEST(Work, LargeExperimentsAreAnnouncedWithTheirEstimate) {
    method::Registry registry;
    app::registerAllMethods(registry);
    // formation: runs = 100000 (allowed) is an hour of marches; framesync: 10,000 seeds
    const std::string formation = writeIniFrom(config("formation_many_turns"), "work_runs",
                                               "runs        = 100", "runs = 100000");
    const auto fLine = announced(registry, formation);
    ASSERT_TRUE(fLine);
    EXPECT_NE(fLine->find("[formation] runs x (experiment_routes x experiment_speeds"),
              std::string::npos)
        << *fLine;
    EXPECT_TRUE(announced(registry, formation, false) == std::nullopt)
        << "simulate runs no experiment";
    const std::string framesync =
        writeIniFrom(config("framesync_corridor"), "work_seeds", "experiment_seeds       = 50",
                     "experiment_seeds = 10000");
    const auto sLine = announced(registry, framesync);
    ASSERT_TRUE(sLine);
    // 10,000 + 20 x 9 sweep runs of 12,500 steps x 2 robots (measured: 210 runs in 11 s)
    EXPECT_NE(sLine->find("min on 2 cores, most of it the experiment's 10180 simulated runs"),
              std::string::npos)
        << *sLine;
    // the shipped configurations stay within the budget (those for logs recorded elsewhere,
    // config/*_librsf.ini..., simulate nothing: their work is the localization alone)
    for (const auto& e : fs::directory_iterator(std::string(MRLOC_SOURCE_DIR) + "/config")) {
        if (e.path().extension() != ".ini") continue;
        mrpt::config::CConfigFile ini(e.path().string());
        const bool simulates = sim::ScenarioOptions::describesSimulation(ini, "scenario");
        EXPECT_NO_THROW(announced(registry, e.path().string(), true, simulates)) << e.path();
    }
}

TEST(Work, PolymapsSweepIsEstimatedAndAnAbsurdOneRefused) {
    method::Registry registry;
    app::registerAllMethods(registry);
    // the shipped sweep: measured 42 s for the whole run on 2 cores, announced as about 43 s
    const auto line = announced(registry, config("polymap_sweep"));
    ASSERT_TRUE(line);
    EXPECT_NE(line->find("most of it the sweep's 270 localizations ([polymap] sweep_steps x "
                         "sweep_starts x elimination)"),
              std::string::npos)
        << *line;
    // 700 and 800 steps (each allowed): maps of 16,804 and 19,204 vertices, 120
    // localizations of 3.5 to 4.7 min each, about 8 h
    const std::string ini =
        writeIniFrom(config("polymap_sweep"), "work_sweep", "sweep_steps       = 3 6 12 21 42",
                     "sweep_steps = 3 700 800");
    const std::string out = tmp("work_sweep");
    const auto r = mrlocCmd("run " + ini + " --out " + out);
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("[polymap] sweep_steps x sweep_starts x elimination: "),
              std::string::npos)
        << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_FALSE(fs::exists(out));
}

namespace {

/** A key that multiplies a method's work (doc/errors.md "Work", "Cost keys"), set on a
 *  shipped configuration; `given` is set first on both sides (a key that matters only with
 *  another: scan_rays with a scan rate). `more`: the value asks more work than the
 *  configuration's (false: less, e.g. fewer routes). */
struct CostKey {
    const char* config;
    const char* section;
    const char* key;
    const char* value;
    bool more = true;
    const char* given = "";  ///< "section.key=value", or none
};

const CostKey kCostKeys[] = {
    // the simulation, every method
    {"quickstart", "scenario", "duration", "120"},
    {"quickstart", "scenario", "dt", "0.005"},
    {"beacons_multi_robot", "scenario", "robots", "slow", false},
    // formation: the experiment's marches and drives, the pixel mode and its experiment
    {"formation_many_turns", "formation", "runs", "200"},
    {"formation_many_turns", "formation", "experiment_speeds", "5.8 2.9 1"},
    {"formation_many_turns", "formation", "experiment_speeds", "5.8 0.5"},
    {"formation_many_turns", "formation", "experiment_routes", "many_turns", false,
     "formation.camera_starts=0"},
    {"formation_many_turns", "formation", "experiment_robots_max", "14"},
    {"formation_many_turns", "formation", "robots", "8"},
    {"formation_many_turns", "formation", "side", "0.75"},
    {"formation_many_turns", "formation", "wheel_radius", "0.01"},
    {"formation_many_turns", "formation", "dr_period", "0.05"},
    {"formation_many_turns", "formation", "camera_starts", "0", false},
    {"formation_many_turns", "formation", "mode", "pixel"},
    {"formation_pixel", "formation", "camera_width", "1280"},
    {"formation_pixel", "formation", "camera_rows", "400"},
    {"formation_pixel", "formation", "pixel_runs", "2"},
    {"formation_pixel", "formation", "robots", "6"},
    {"formation_pixel", "formation", "side", "1", true, "formation.pixel_runs=1"},
    {"formation_pixel", "formation", "experiment_speeds", "5.8 2.9 1", true,
     "formation.pixel_runs=1"},
    {"formation_pixel", "formation", "experiment_routes", "many_turns", false,
     "formation.pixel_runs=1"},
    {"formation_pixel", "formation", "camera_width", "1280", true, "formation.pixel_runs=1"},
    // omnivision: the identification, the panoramas, the accuracy sweep
    {"omnivision_swarm", "omnivision", "swarm", "40"},
    {"omnivision_swarm", "omnivision", "pairs", "R01 R02, R03 R04, R05 R06", true,
     "scenario.duration=40"},
    {"omnivision_5robots", "omnivision", "views", "6"},
    {"omnivision_5robots", "omnivision", "view_width", "1024"},
    {"omnivision_5robots", "omnivision", "view_height", "128"},
    {"omnivision_5robots", "omnivision", "accuracy_trials", "200"},
    // polymap: the scans, the experiment, the sweep, the randomized columns
    {"polymap_steps", "polymap", "scan_rate", "10"},
    {"polymap_steps", "polymap", "scan_rays", "2880", true, "polymap.scan_rate=10"},
    {"polymap_steps", "scenario", "duration", "240", true, "polymap.scan_rate=10"},
    {"polymap_steps", "polymap", "steps", "8", true, "polymap.scan_rate=10"},
    {"polymap_steps", "polymap", "branches_per_step", "3", true, "polymap.scan_rate=10"},
    {"polymap_sweep", "polymap", "elimination", "cells", false},
    {"polymap_sweep", "polymap", "random_points", "100 500 1000"},
    {"polymap_sweep", "polymap", "sweep_steps", "3 6 12 21 42 50"},
    {"polymap_sweep", "polymap", "sweep_starts", "16"},
    {"polymap_sweep", "polymap", "steps", "8"},
    {"polymap_sweep", "polymap", "branches_per_step", "3"},
    // framesync: the sonars and the experiment's runs
    {"framesync_corridor", "framesync", "experiment_seeds", "100"},
    {"framesync_corridor", "framesync", "experiment_sweep_seeds", "30"},
    {"framesync_corridor", "framesync", "experiment_noise", "0.0025 0.005 0.01 0.02 0.04 0.08"},
    {"framesync_corridor", "framesync", "experiment_drift", "0.5 1 2 4 8"},
    // beacons: the study's trials
    {"beacons_paper_room", "beacons_study", "trials", "20"},
    {"beacons_paper_room", "beacons_study", "choice_trials", "200"},
    {"beacons_paper_room", "beacons_study", "grid", "0.25"},
    {"beacons_paper_room", "beacons_study", "wall_margin", "1", false},
    {"beacons_paper_room", "beacons_study", "coverage_sizes", "3 4 5 6 7 8 10"},
    {"beacons_paper_room", "beacons_study", "count_sizes", "3 4 5 6 8 10"},
    {"beacons_paper_room", "beacons_study", "count_max", "60"},
    {"beacons_paper_room", "beacons_study", "beam_angles", "20 30 40 50 60 70 80 90"},
    {"beacons_paper_room", "beacons_study", "beacon_counts", "3 4 5 6 8 10 12 16"},
    {"beacons_paper_room", "beacons_study", "speeds", "0 0.1 0.2 0.3 0.5 1 2"},
    {"beacons_paper_room", "beacons_study", "agents", "1 2 4 8 10"},
    {"beacons_paper_room", "beacons_study", "agents_layouts", "10"},
    {"beacons_paper_room", "beacons_study", "agents_time", "20"},
};

/** section.key=value as an override. */
std::vector<app::KeyOverride> overridesOf(const std::string& given) {
    if (given.empty()) return {};
    return {app::parseOverride(given, "--set")};
}

/** The INI keys a work item's `keys` text names: every word after a [section] tag that the
 *  run's effective.ini holds in that section ("[polymap] scan_rate x scan_rays"). */
std::set<std::string> keysNamed(const std::string& text, const mrpt::config::CConfigFileBase& eff) {
    std::set<std::string> out;
    const std::regex token(R"(\[([a-z_.0-9]+)\]|([a-z_0-9]+))");
    std::string section;
    for (std::sregex_iterator it(text.begin(), text.end(), token), end; it != end; ++it) {
        if ((*it)[1].matched) {
            section = (*it)[1];
            continue;
        }
        const std::string word = (*it)[2];
        if (!section.empty() && eff.keyExists(section, word)) out.insert(section + "." + word);
    }
    return out;
}

/** The estimate's three measures for `mrloc run` (simulation and localization), over the
 *  parts that name `key` ("section.key"): the parts a key multiplies must move with it, not
 *  another part that happens to grow with a key of the same name. */
struct Estimate {
    double seconds = 0, bytes = 0, memory = 0;
};

Estimate estimateOf(const method::Registry& registry, const std::string& ini,
                    const std::vector<app::KeyOverride>& overrides, const std::string& key) {
    const auto setup = app::loadSetup(registry, ini, std::nullopt, true, "", overrides);
    mrpt::config::CConfigFileMemory eff(app::effectiveIni(setup));
    Estimate e;
    for (const auto& w : app::workOf(setup, true, true))
        if (keysNamed(w.keys, eff).count(key))
            e.seconds += w.seconds, e.bytes += w.bytes, e.memory = std::max(e.memory, w.memory);
    return e;
}

}  // namespace

TEST(Work, EveryCostKeyMovesTheEstimate) {
    method::Registry registry;
    app::registerAllMethods(registry);
    for (const auto& k : kCostKeys) {
        SCOPED_TRACE(std::string(k.config) + ": [" + k.section + "] " + k.key + " = " + k.value);
        const std::string ini = config(k.config);
        const std::string key = std::string(k.section) + "." + k.key;
        auto given = overridesOf(k.given);
        const Estimate before = estimateOf(registry, ini, given, key);
        given.push_back({k.section, k.key, k.value, "--set"});
        const Estimate after = estimateOf(registry, ini, given, key);
        // one measure moves the asked way, the time not the other way (a key may move a small
        // part: choice_trials adds 1 % to beacons_paper_room's study, beam_angles 0.3 %)
        const auto moved = [&](double a, double b) {
            return k.more ? b > a * (1 + 1e-6) : a > b * (1 + 1e-6);
        };
        const auto against = [&](double a, double b) { return k.more ? b < a : a < b; };
        EXPECT_TRUE(moved(before.seconds, after.seconds) || moved(before.bytes, after.bytes) ||
                    moved(before.memory, after.memory))
            << "seconds " << before.seconds << " -> " << after.seconds << ", bytes "
            << before.bytes << " -> " << after.bytes << ", memory " << before.memory << " -> "
            << after.memory;
        EXPECT_FALSE(against(before.seconds, after.seconds));
    }
}

TEST(Work, EveryKeyAnEstimateNamesIsACostKeyTested) {
    // an estimate that names a key (its WorkItem::keys) is tested above by varying it: a key
    // added to an estimate without its test, or a test left behind by a renamed key, fails
    method::Registry registry;
    app::registerAllMethods(registry);
    std::set<std::string> tested;
    for (const auto& k : kCostKeys) tested.insert(std::string(k.section) + "." + k.key);
    std::set<std::string> named;
    for (const auto& k : kCostKeys) {
        auto overrides = overridesOf(k.given);
        overrides.push_back({k.section, k.key, k.value, "--set"});
        for (const auto& o : {std::vector<app::KeyOverride>{}, overrides}) {
            const auto setup = app::loadSetup(registry, config(k.config), std::nullopt, true, "", o);
            mrpt::config::CConfigFileMemory eff(app::effectiveIni(setup));
            for (const auto& w : app::workOf(setup, true, true)) {
                const auto keys = keysNamed(w.keys, eff);
                EXPECT_FALSE(keys.empty()) << k.config << ": " << w.keys << " names no key";
                for (const auto& key : keys) {
                    named.insert(key);
                    EXPECT_EQ(tested.count(key), 1u)
                        << k.config << ": the estimate's part '" << w.what << "' names " << key
                        << ", which no CostKey varies";
                }
            }
        }
    }
    for (const auto& key : tested)
        EXPECT_EQ(named.count(key), 1u) << key << " is varied but no estimate names it";
}

TEST(Work, TheCostKeysTheEstimateMissedAreEstimatedAndTheAbsurdRefusedAtOnce) {
    method::Registry registry;
    app::registerAllMethods(registry);
    // formation: dead reckoning is costed per step, so a slow wheel is a long experiment
    // (experiment_speeds = 0.01 ran 80 s; estimated about 74 s), and fig. 15's marches by
    // their robots (experiment_robots_max = 50: a march of 50 robots is about 4 s)
    const auto slow = announced(
        registry, writeIniFrom(config("formation_many_turns"), "work_slow",
                               "runs        = 100", "runs = 100\nexperiment_speeds = 0.01"));
    ASSERT_TRUE(slow);
    EXPECT_NE(slow->find("wheel_radius x experiment_speeds x dr_period"), std::string::npos)
        << *slow;
    const auto many = announced(
        registry, writeIniFrom(config("formation_many_turns"), "work_many",
                               "runs        = 100", "runs = 100\nexperiment_robots_max = 50"));
    ASSERT_TRUE(many);
    EXPECT_NE(many->find(" h on 2 cores"), std::string::npos) << *many;
    // the pixel mode by its camera: 4096 x 4096 simulated in 93 s (estimated about 95 s)
    const auto big = announced(
        registry, writeIniFrom(writeIniFrom(config("formation_pixel"), "work_pixels",
                                            "camera_width    = 640 ", "camera_width = 4096 "),
                               "work_pixels", "camera_rows     = 200 ", "camera_rows = 4096 "));
    ASSERT_TRUE(big);
    EXPECT_NE(big->find("the pixel mode's rendered frames ([formation] mode = pixel, "
                        "camera_width x camera_rows"),
              std::string::npos)
        << *big;
    // omnivision: a swarm of 1000 would hold its N^3 angle pairs (ran 479 s to bad_alloc at
    // 2.4 GB); tolerances of 30 degrees stop at the work meter in about 4 s (were 27 s)
    const std::string swarm = writeIniFrom(
        writeIniFrom(writeIniFrom(config("omnivision_swarm"), "work_swarm", "swarm = 30 ",
                                  "swarm = 1000 "),
                     "work_swarm", "swarm_area = 20 ", "swarm_area = 100 "),
        "work_swarm", "size = 40 40 3 ", "size = 120 120 3 ");
    const std::string loose =
        writeIniFrom(config("omnivision_swarm"), "work_loose", "refine = true",
                     "refine = true\nsum_tolerance = 30\nbearing_tolerance = 30");
    for (const auto& [ini, message] :
         {std::pair<std::string, std::string>{swarm,
                                              "[scenario] robots or [omnivision] swarm, cubed, x "
                                              "pairs: the identification of 1000 robots at 4 "
                                              "snapshots would hold about 56.0 GB at once"},
          {loose,
           "[omnivision] sum_tolerance, bearing_tolerance, bearing_sigma: the identification of "
           "30 robots examined over 405000000 angle pairs and images without settling"}}) {
        const std::string out = tmp("work_omni");
        fs::remove_all(out);
        const auto r = mrlocCmd("run " + ini + " --out " + out + " -q");
        EXPECT_EQ(r.code, 1) << r.output;
        EXPECT_NE(r.output.find(message), std::string::npos) << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
        EXPECT_FALSE(fs::exists(out));
    }
}
