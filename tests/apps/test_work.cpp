// A run's work as a whole (method/Work.h, doc/errors.md "Work"): the budget's arithmetic, and
// runs whose keys are each allowed but whose product is not, refused with one line before
// anything is written, or announced with their estimate.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/method/Work.h>
#include <mrloc/sim/Scenario.h>
#include <mrpt/config/CConfigFile.h>

#include <filesystem>
#include <optional>

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
    // of rawlog (the 10 Hz wrote 381 MB in 55 s)
    const std::string ini = writeIniFrom(
        writeIniFrom(config("polymap_steps"), "work_scans", "duration = 0.1", "duration = 120"),
        "work_scans", "scan_rays         = 1440", "scan_rays = 100000\nscan_rate = 1000");
    const std::string out = tmp("work_scans");
    for (const std::string verb : {"simulate", "run"}) {
        const auto r = mrlocCmd(verb + " " + ini + " --out " + out);
        EXPECT_EQ(r.code, 1) << r.output;
        EXPECT_EQ(r.output.rfind("mrloc " + verb + ": error: ", 0), 0u) << r.output;
        EXPECT_NE(r.output.find("[polymap] scan_rate x scan_rays x [scenario] duration: "),
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
