// Every picture of every shipped INI (config/*.ini) reads at a glance (PictureChecks.h says
// what that is checked as). An INI that a test runs whole is checked there (kCheckedWhereRunWhole
// names the test); every other one runs here, one test each.
//
// A simulated INI runs here with its repetitions cut (experiments' trials and seeds, sweeps,
// the march's duration: kFewerRepetitions) so that all of them fit in CI; each still draws
// every kind of picture it draws whole. An INI for a log recorded elsewhere localizes its log
// as its header says (kLogs), skipped with a message when the log is not on the machine.
#include <gtest/gtest.h>
#include <mrloc/sim/Scenario.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <filesystem>
#include <fstream>
#include <map>

#include "MrlocCli.h"
#include "PictureChecks.h"

using namespace mrloc;
using namespace mrloc::testing_cli;
namespace fs = std::filesystem;

namespace {

/** Keys that repeat work, each at most this value wherever an INI sets it (the value a
 *  picture still needs: two runs for a table, a few trials for a curve). */
const std::map<std::string, std::string> kFewerRepetitions = {
    {"runs", "2"},                    // formation: Monte Carlo marches per route and speed
    {"pixel_runs", "0"},              // formation: Table 1 from pixels is a table, no picture
    {"camera_starts", "0"},           // formation: the grid of camera starts
    {"experiment_seeds", "2"},        // framesync
    {"experiment_sweep_seeds", "1"},  // framesync
    {"choice_trials", "10"},          // beacons' study
    {"trials", "3"},                  // beacons' study
    {"accuracy_trials", "5"},         // omnivision
    {"sweep_starts", "2"},            // polymap's sweep
    {"duration", "300"},              // s: formation's 3,200 s marches
};

/** polymap's sweep: two map sizes instead of five. */
const std::map<std::string, std::string> kFewerValues = {{"sweep_steps", "3 6"}};

/** The logs the INIs for logs recorded elsewhere localize (their headers' command lines). */
const std::map<std::string, std::string> kLogs = {
    {"beacons_librsf",
     std::string(MRLOC_SOURCE_DIR) + "/data/real/librsf-indoor-uwb/labyrinth.rawlog"},
    {"framesync_udacity",
     std::string(MRLOC_SOURCE_DIR) + "/data/real/udacity-sonar/udacity.rawlog"},
    {"polymap_localization_demo", "/usr/share/mrpt/datasets/localization_demo.rawlog"},
    {"polymap_sena",
     "/usr/share/mrpt/datasets/2006-01ENE-21-SENA_Telecom Faculty_one_loop_only.rawlog"},
    {"polymap_sena_malaga",
     "/usr/share/mrpt/datasets/2006-01ENE-21-SENA_Telecom Faculty_one_loop_only.rawlog"},
    // imported first (mrloc import mrclam, from ../shared/data): skipped here, and its
    // pictures are checked nowhere (RealLogs.BeaconTrackerOnMrclamDataset6 localizes it)
    {"beacons_mrclam", ""},
};

/** The shipped INIs that a test runs whole (as shipped), and checks the pictures of. */
const std::map<std::string, std::string> kCheckedWhereRunWhole = {
    {"beacons_bad_ranges", "MrlocRun.ThirtyPercentBadRangesNeverLoseTheTrack"},
    {"beacons_multi_robot",
     "MrlocCli.ARunIntoAUsedFolderLeavesNoStaleOutputsAndKeepsTheUsersFiles"},
    {"beacons_one_at_a_time", "FirstContact.OneBeaconAtATimeStartsBridgesAGapAndStaysRight"},
    {"formation_obstacles",
     "MrlocFormation.ObstacleRunKeepsEveryRobotOutOfTheSafetyZonesAndArrives"},
    {"formation_patrol",
     "MrlocFormation.PatrolRouteEndsWhereItStartsAndDeadReckoningDrivesAllOfIt"},
    {"formation_pixel",
     "MrlocFormation.PixelModeMarchIsSteeredByTheCamerasAndTheMidpointRuleBeatsThePapers"},
    {"omnivision_5robots", "MrlocOmnivision.FiveRobotsFromRenderedPanoramas"},
    {"omnivision_swarm", "MrlocOmnivision.SwarmOfThirty"},
    {"omnivision_swarm100", "MrlocOmnivision.SwarmOfAHundredBehindEachOthersBands"},
    {"omnivision_swarm100_rendered", "MrlocOmnivision.SwarmOfAHundredRenderedFromPixels"},
    {"polymap_file", "MrlocPolymap.MapFileRunWithTwoRoomsAndByteIdenticalRepeats"},
    {"polymap_localization_demo", "RealPolymap.LocalizationDemoBesidePfLocalization"},
    {"polymap_sena", "RealPolymap.SenaLogOnIcpSlamsMapBesideIcpSlam"},
    {"polymap_sena_malaga", "RealPolymap.SenaLogOnMrptsBuildingMapWithTheDefaults"},
    {"polymap_steps", "MrlocPolymap.StepsMapRunFindsTwelveHypothesesWithTheTruthAmongThem"},
    {"polymap_steps148_shafts",
     "MrlocPolymap.StepsJoinedByShaftsRunsThePapersTablesAndSaysWhereTheOrderDiffers"},
    {"polymap_steps76", "MrlocPolymap.PaperExperimentOnTheSteps76MapLocalizesFromEveryStart"},
    {"quickstart", "FrontDoor.TheReportOpensWithWhatRanTheHeadlineAndProvenance"},
};

std::vector<std::string> shippedInis() {
    std::vector<std::string> stems;
    for (const auto& e : fs::directory_iterator(std::string(MRLOC_SOURCE_DIR) + "/config"))
        if (e.path().extension() == ".ini") stems.push_back(e.path().stem().string());
    std::sort(stems.begin(), stems.end());
    return stems;
}

/** A copy of config/<stem>.ini with kFewerRepetitions applied, in <dir>/config/ beside links
 *  to the source's maps/ and data/ (an INI names its files from its own folder). Returns the
 *  keys it cut, as "key a -> b". */
std::vector<std::string> writeFewerRepetitions(const std::string& stem, const std::string& dir,
                                               std::string& iniPath) {
    mrpt::config::CConfigFile original(config(stem));
    mrpt::config::CConfigFileMemory ini;
    ini.setContent(slurp(config(stem)));
    std::vector<std::string> cuts;
    std::vector<std::string> sections;
    original.getAllSections(sections);
    for (const auto& section : sections) {
        std::vector<std::string> keys;
        original.getAllKeys(section, keys);
        for (const auto& key : keys) {
            const std::string value = original.read_string(section, key, "");
            if (const auto it = kFewerRepetitions.find(key); it != kFewerRepetitions.end()) {
                if (std::stod(value) > std::stod(it->second)) {
                    ini.write(section, key, it->second);
                    cuts.push_back(key + " " + value + " -> " + it->second);
                }
            } else if (const auto v = kFewerValues.find(key); v != kFewerValues.end()) {
                ini.write(section, key, v->second);
                cuts.push_back(key + " " + value + " -> " + v->second);
            }
        }
    }
    fs::create_directories(dir + "/config");
    for (const char* folder : {"maps", "data", "rawlogs"})
        fs::create_directory_symlink(std::string(MRLOC_SOURCE_DIR) + "/" + folder,
                                     dir + "/" + folder);
    iniPath = dir + "/config/" + stem + ".ini";
    std::ofstream(iniPath) << ini.getContent();
    return cuts;
}

}  // namespace

class EveryShippedIni : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryShippedIni, DrawsPicturesThatReadAtAGlance) {
    if (std::getenv("MRLOC_SANITIZED"))  // set by scripts/sanitize.sh
        GTEST_SKIP() << "sanitized build: whole runs of every shipped INI; the pictures' code "
                        "runs sanitized in the report and TopView tests";
    const std::string stem = GetParam();
    const std::string out = tmp("pictures_" + stem);
    Result r{};
    if (const auto log = kLogs.find(stem); log != kLogs.end()) {
        if (log->second.empty()) GTEST_SKIP() << stem << ": its log is imported first";
        if (!fs::exists(log->second)) GTEST_SKIP() << log->second << " is absent";
        r = mrlocCmd("localize " + config(stem) + " '" + log->second + "' --out " + out + " -q");
        ASSERT_EQ(r.code, 0) << stem << ": " << r.output;
        r = mrlocCmd("report " + out);  // localize draws nothing: report draws
    } else {
        std::string ini;
        const auto cuts = writeFewerRepetitions(stem, tmp("pictures_ini_" + stem), ini);
        for (const auto& c : cuts) std::cout << stem << ": " << c << "\n";
        r = mrlocCmd("run " + ini + " --out " + out + " -q");
    }
    ASSERT_EQ(r.code, 0) << stem << ": " << r.output;
    expectPicturesReadAtAGlance(out, stem);
}

namespace {

/** The shipped INIs no other test runs whole. */
std::vector<std::string> checkedHere() {
    std::vector<std::string> here;
    for (const auto& stem : shippedInis())
        if (!kCheckedWhereRunWhole.count(stem)) here.push_back(stem);
    return here;
}

}  // namespace

INSTANTIATE_TEST_SUITE_P(Pictures, EveryShippedIni, ::testing::ValuesIn(checkedHere()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                             return info.param;
                         });

// Every INI shipped for a log recorded elsewhere names its log here, so that a new one is
// not left out of the pictures' check; the INIs checked elsewhere are shipped ones.
TEST(Pictures, EveryIniForALogNamesItsLog) {
    const auto shipped = shippedInis();
    for (const auto& [stem, test] : kCheckedWhereRunWhole)
        EXPECT_TRUE(std::count(shipped.begin(), shipped.end(), stem))
            << stem << " (" << test << ")";
    for (const auto& stem : shipped) {
        const mrpt::config::CConfigFile ini(config(stem));
        const bool simulates = sim::ScenarioOptions::describesSimulation(ini, "scenario");
        EXPECT_EQ(simulates, !kLogs.count(stem)) << stem;
    }
}
