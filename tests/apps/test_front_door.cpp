// Issue 27's front door: what a newcomer or an MRPT user meets first. Slips get one line that
// names what is wrong; MRPT's ground truth is picked up where MRPT's apps look for it; an MRPT
// INI for a task mrloc does not do is told so with what would fit its log; an impossible
// route is refused; the report opens with what ran, the headline beside the paper's and the
// provenance; the tour's index shows every run's headline.
#include <gtest/gtest.h>
#include <mrloc/common/Metrics.h>
#include <mrloc/common/Progress.h>

#include <nlohmann/json.hpp>
#include <regex>
#include <set>

#include "AllMethods.h"
#include "MrlocCli.h"
#include "PictureChecks.h"
#include "TestPaths.h"

namespace fs = std::filesystem;
using namespace mrloc;
using namespace mrloc::testing_cli;

namespace {

const std::string kMrptDatasets = "/usr/share/mrpt/datasets";
const std::string kMrptConfigs = "/usr/share/mrpt/config_files";

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

}  // namespace

TEST(FrontDoor, SlipsGetOneLineNamingWhatIsWrong) {
    const std::string rawlog = std::string(MRLOC_SOURCE_DIR) + "/rawlogs/quickstart.rawlog";
    // a rawlog where the INI goes
    auto r = mrlocCmd("simulate " + rawlog + " -q --out " + tmp("slip1"));
    EXPECT_EQ(r.code, 1);
    EXPECT_TRUE(contains(r.output, "this is a rawlog, not an INI")) << r.output;
    // an INI where the rawlog goes
    // (tmp() empties a folder: its name is kept, so that the check after the run can fail)
    const std::string slip2 = tmp("slip2");
    r = mrlocCmd("localize " + config("quickstart") + " " + config("quickstart") + " -q --out " +
                 slip2);
    EXPECT_EQ(r.code, 1);
    EXPECT_TRUE(contains(r.output, "this is an INI, not a rawlog")) << r.output;
    EXPECT_FALSE(fs::exists(slip2));
    // --out at a file
    const std::string file = testing::TempDir() + "/apps_a_file";
    std::ofstream(file) << "x";
    r = mrlocCmd("run " + config("quickstart") + " -q --out " + file);
    EXPECT_EQ(r.code, 1);
    EXPECT_TRUE(contains(r.output, "--out: '" + file + "' is a file, not a folder")) << r.output;
    EXPECT_EQ(slurp(file), "x");
    // the parser names what is missing
    r = mrlocCmd("localize " + config("quickstart"));
    EXPECT_EQ(r.code, 2);
    EXPECT_TRUE(contains(r.output, "missing <RAWLOG> (rawlog file)")) << r.output;
    EXPECT_FALSE(contains(r.output, "One or more required arguments missing")) << r.output;
    // a relative path that is not there shows where it was looked for
    r = mrlocCmd("run no/such/file.ini -q");
    EXPECT_EQ(r.code, 1);
    EXPECT_TRUE(contains(r.output, "no/such/file.ini (" + std::string(MRLOC_SOURCE_DIR) +
                                       "/no/such/file.ini): no such file"))
        << r.output;
}

TEST(FrontDoor, ARouteThroughAWallOrOutOfTheRoomIsRefused) {
    // quickstart's room is 3 x 3 m with a pillar box at 1.4-1.6 m; each edited INI is refused
    // with its line, and nothing is written
    const auto refused = [](const std::string& name, const std::string& from, const std::string& to,
                            const std::string& message) {
        SCOPED_TRACE(name);
        const std::string ini = writeIniFrom(config("quickstart"), name, from, to);
        const std::string out = tmp(name);
        const auto r = mrlocCmd("run " + ini + " -q --out " + out);
        EXPECT_EQ(r.code, 1);
        EXPECT_TRUE(contains(r.output, message)) << r.output;
        EXPECT_FALSE(fs::exists(out));
    };
    refused("route_outside", "waypoints = 2.5 0.5,", "waypoints = 12.5 0.5,",
            "[robot.r1] waypoints: waypoint 1 (12.5 0.5) is outside the room (3 x 3 m)");
    refused("route_through", "waypoints = 2.5 0.5, 2.5 2.5,",
            "waypoints = 2.5 0.5, 0.5 2.5, 2.5 2.5,",
            "the leg from (2.5 0.5) to (0.5 2.5) goes through obstacle_pillar");
}

TEST(FrontDoor, MrptGroundTruthIsPickedUpWhereMrptsAppsLook) {
    if (!fs::exists(kMrptDatasets + "/uwb_ro-localization_demo_GT.txt"))
        GTEST_SKIP() << "MRPT's datasets (Debian mrpt-common) are not installed";
    // MRPT's UWB INI, unchanged: its groundTruthFile, offset by its [OdometryEstimation] start
    const std::string ini = kMrptConfigs + "/ro-localization/UWB_localization_demo.ini";
    const std::string out = tmp("mrpt_truth");
    auto r = mrlocCmd("localize " + ini + " " + kMrptDatasets +
                      "/uwb_ro-localization_demo.rawlog -q --out " + out);
    ASSERT_EQ(r.code, 0) << r.output;
    auto m = common::readJsonFile(out + "/metrics.json");
    EXPECT_TRUE(contains(m["ground_truth_from"].get<std::string>(),
                         "MRPT's [ro-localization] groundTruthFile"));
    // the same figures as with the hand-written [scenario] block of MrptData's test
    EXPECT_EQ(m["n"], 679);
    EXPECT_LT(m["rmse_m"].get<double>(), 0.32);
    // a copy of the log elsewhere: the INI's truth is not its; the _GT.txt beside it is
    const std::string folder = testing::TempDir() + "/apps_mrpt_copy";
    fs::remove_all(folder);
    fs::create_directories(folder);
    fs::copy_file(kMrptDatasets + "/uwb_ro-localization_demo.rawlog", folder + "/uwb.rawlog");
    const std::string out1 = tmp("mrpt_copy1");
    r = mrlocCmd("localize " + ini + " " + folder + "/uwb.rawlog -q --out " + out1);
    ASSERT_EQ(r.code, 0) << r.output;
    m = common::readJsonFile(testing::TempDir() + "/apps_mrpt_copy1/metrics.json");
    EXPECT_FALSE(m.contains("ground_truth_from")) << m.dump();
    EXPECT_FALSE(m["ground_truth"].get<bool>());
    fs::copy_file(kMrptDatasets + "/uwb_ro-localization_demo_GT.txt", folder + "/uwb_GT.txt");
    const std::string out2 = tmp("mrpt_copy2");
    r = mrlocCmd("localize " + ini + " " + folder + "/uwb.rawlog -q --out " + out2);
    ASSERT_EQ(r.code, 0) << r.output;
    m = common::readJsonFile(out2 + "/metrics.json");
    EXPECT_EQ(m["ground_truth_from"], "uwb_GT.txt beside the rawlog (MRPT's naming)");
    EXPECT_EQ(m["n"], 679);
    // the report says where the truth came from, and that the log was recorded elsewhere
    ASSERT_EQ(mrlocCmd("report " + out2).code, 0);
    const std::string page = slurp(out2 + "/report.html");
    EXPECT_TRUE(contains(page, "uwb_GT.txt beside the rawlog (MRPT&#39;s naming)") ||
                contains(page, "uwb_GT.txt beside the rawlog (MRPT's naming)"))
        << page.substr(0, 3000);
    EXPECT_TRUE(contains(page, "recorded elsewhere")) << page.substr(0, 3000);
    EXPECT_FALSE(contains(page, "simulated by mrloc")) << "a real log has no seed line";
}

TEST(FrontDoor, AnMrptIniForATaskMrlocDoesNotDoSaysWhatFits) {
    // icp-slam builds maps; mrloc localizes on known ones (pf-localization's INIs are
    // polymap's: tests/apps/test_real_polymap.cpp)
    const std::string ini = kMrptConfigs + "/icp-slam/icp-slam_demo_classic.ini";
    if (!fs::exists(ini)) GTEST_SKIP() << "MRPT's INIs (Debian mrpt-common) are not installed";
    const std::string out = tmp("icp_demo");
    const auto r = mrlocCmd("localize " + ini + " " + kMrptDatasets +
                            "/localization_demo.rawlog -q --out " + out);
    EXPECT_EQ(r.code, 1);
    EXPECT_TRUE(contains(r.output, "an INI of MRPT's SLAM apps")) << r.output;
    EXPECT_TRUE(contains(r.output, "CObservation2DRangeScan")) << r.output;
    EXPECT_TRUE(contains(r.output,
                         "method 'polymap' reads CObservation2DRangeScan: start from "
                         "config/polymap_file.ini"))
        << r.output;
    EXPECT_FALSE(contains(r.output, "beacon")) << r.output;
    EXPECT_FALSE(fs::exists(out));
    // simulate and run find the log the INI names itself
    const auto s = mrlocCmd("run " + ini + " -q --out " + tmp("icp_demo_run"));
    EXPECT_EQ(s.code, 1);
    EXPECT_TRUE(contains(s.output, "Faculty_one_loop_only.rawlog holds")) << s.output;
}

// An INI for a log recorded elsewhere simulates nothing: run and simulate name the command
// that reads it (they said "[scenario] robots: required key is missing").
TEST(FrontDoor, RunningAnIniForALogRecordedElsewhereSaysToLocalizeIt) {
    for (const std::string command : {"run", "simulate"}) {
        const std::string out = tmp("librsf_" + command);
        const auto r = mrlocCmd(command + " " + config("beacons_librsf") + " --out " + out);
        EXPECT_EQ(r.code, 1) << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
        EXPECT_TRUE(contains(r.output, "beacons_librsf.ini: describes no simulation")) << r.output;
        EXPECT_TRUE(contains(r.output, "it localizes a log recorded elsewhere: mrloc localize " +
                                           config("beacons_librsf") + " <rawlog>"))
            << r.output;
        EXPECT_FALSE(contains(r.output, "required key")) << r.output;
        EXPECT_FALSE(fs::exists(out));
    }
}

TEST(FrontDoor, TheReportOpensWithWhatRanTheHeadlineAndProvenance) {
    const std::string out = tmp("report_top");
    const auto r = mrlocCmd("run " + config("quickstart") + " -q --out " + out);
    ASSERT_EQ(r.code, 0) << r.output;
    expectPicturesReadAtAGlance(out, "quickstart");  // its pictures, once (test_pictures.cpp)
    const std::string page = slurp(out + "/report.html");
    // title from the scenario, then the blocks in the issue's order
    EXPECT_TRUE(contains(page, "<title>quickstart: active ultrasonic beacons"))
        << page.substr(0, 400);
    const size_t what = page.find("What ran"), headline = page.find("Headline"),
                 provenance = page.find("Provenance"), errors = page.find("Position error");
    ASSERT_NE(what, std::string::npos);
    EXPECT_LT(what, headline);
    EXPECT_LT(headline, provenance);
    EXPECT_LT(provenance, errors);
    EXPECT_TRUE(contains(page, "simulated by mrloc, seed 1"));
    EXPECT_TRUE(contains(page, "odometry alone APE RMSE (baseline)"));
    const auto p = common::readJsonFile(out + "/provenance.json");
    for (const char* key : {"date_utc", "commit", "mrpt_version", "cpu", "cores"})
        EXPECT_TRUE(p.contains(key)) << key;
    EXPECT_EQ(p["date_utc"].get<std::string>().size(), 19u);  // 2026-12-02 15:22:35
    EXPECT_TRUE(contains(p["mrpt_version"].get<std::string>(), "2.")) << p.dump();
    EXPECT_TRUE(contains(page, "MRPT</th><td>" + p["mrpt_version"].get<std::string>()));
    // what ran, in the paper's terms (doc/beacons.md's table), under the outcome
    const auto m = common::readJsonFile(out + "/metrics.json");
    EXPECT_EQ(m["headline"].value("mechanism", ""),
              "mrloc's tracker between fixes (mode = tracker: odometry and gated ranges, beyond "
              "paper 001); one shared acoustic channel, one agent per slot (paper 001's firing "
              "of different beacons at different agents at once runs in [beacons_study] only)");
    EXPECT_TRUE(contains(page, "What ran: </b>")) << "the report names what ran";
    // the summary's first row is the RMSE
    const size_t table = page.find("<table", errors);
    EXPECT_LT(page.find("RMSE (m)", table), page.find("mean error (m)", table));
}

TEST(FrontDoor, TheIndexShowsEveryRunsHeadlineAndLinksItsReport) {
    const std::string tour = tmp("tour");
    ASSERT_EQ(mrlocCmd("run " + config("quickstart") + " -q --out " + tour + "/beacons").code, 0);
    ASSERT_EQ(mrlocCmd("run " + config("polymap_steps") + " -q --out " + tour + "/polymap").code,
              0);
    const auto r = mrlocCmd("index " + tour);
    ASSERT_EQ(r.code, 0) << r.output;
    const std::string page = slurp(tour + "/index.html");
    EXPECT_TRUE(contains(page, "<a href='beacons/report.html'>beacons</a>")) << page;
    EXPECT_TRUE(contains(page, "<a href='polymap/report.html'>polymap</a>")) << page;
    // titled by what the folder holds (issue 57), unless the title is given (./run.sh's tour)
    EXPECT_TRUE(contains(page, "<title>mrloc: 2 runs in apps_tour (beacons, polymap)</title>"))
        << page;
    EXPECT_FALSE(contains(page, "five methods"));
    // the beacons run's APE RMSE on the truth's timeline as metrics.json has it, to 3 digits
    const auto m = common::readJsonFile(tour + "/beacons/metrics.json");
    char rmse[32];
    std::snprintf(rmse, sizeof rmse, "%.3g\u00a0m",  // no-break space
                  m["truth_timeline"]["ape"]["rmse_m"].get<double>());
    EXPECT_TRUE(contains(page, rmse)) << rmse;
    EXPECT_TRUE(contains(page, "odometry alone APE RMSE (baseline)"));
    // polymap_steps drives nothing: its goal is not reached, and the index says so
    EXPECT_TRUE(contains(page, "not reached: not localized")) << page;
    // a run folder from a stranger: its words are text, never markup; a folder that is a
    // link is not followed
    fs::create_directories(tour + "/zz");
    std::ofstream(tour + "/zz/metrics.json")
        << R"({"method": "<b>m", "robots": {}, "headline": {"reached": false,
              "status": "<script>alert(1)</script>", "figures": []}})";
    fs::create_directory_symlink(tour + "/beacons", tour + "/link");
    ASSERT_EQ(mrlocCmd("index " + tour + " --title 'the <i>tour</i>'").code, 0);
    const std::string again = slurp(tour + "/index.html");
    EXPECT_TRUE(contains(again, "<h1>the &lt;i&gt;tour&lt;/i&gt;</h1>")) << again;
    EXPECT_TRUE(contains(again, "&lt;script&gt;alert(1)&lt;/script&gt;")) << again;
    EXPECT_FALSE(contains(again, "<script>"));
    EXPECT_TRUE(contains(again, "zz (no report) (&lt;b&gt;m)")) << again;
    EXPECT_FALSE(contains(again, "link/report.html")) << again;
    // an empty folder has no index
    const std::string empty = tmp("tour_empty");
    fs::create_directories(empty);
    const auto e = mrlocCmd("index " + empty);
    EXPECT_EQ(e.code, 1);
    EXPECT_TRUE(contains(e.output, "no run folder in it")) << e.output;
}

TEST(FrontDoor, EveryTourLineNamesAShippedIniOfThatMethod) {
    std::ifstream list(std::string(MRLOC_SOURCE_DIR) + "/config/tour.txt");
    std::set<std::string> methods;
    for (std::string line; std::getline(list, line);) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream words(line);
        std::string name, ini;
        words >> name >> ini;
        const std::string text = slurp(std::string(MRLOC_SOURCE_DIR) + "/" + ini);
        ASSERT_FALSE(text.empty()) << ini;
        EXPECT_TRUE(std::regex_search(text, std::regex("\\nmethod *= *" + name + "\\b")))
            << ini << " is not an INI of " << name;
        methods.insert(name);
    }
    // every registered method is on the tour (the recipe's step 7)
    method::Registry registry;
    app::registerAllMethods(registry);
    const auto names = registry.names();
    EXPECT_EQ(methods, std::set<std::string>(names.begin(), names.end()));
}

TEST(FrontDoor, ProgressSaysHowFarAndHowLongIsLeft) {
    EXPECT_EQ(common::progressText("localizing", 0.25, 250, 1000, 10.0),
              "localizing: 25 % (250 of 1000), 10 s so far, about 30 s left");
    // too early for a rate: no estimate
    EXPECT_EQ(common::progressText("simulating", 0.01, 1, 100, 2.0),
              "simulating: 1 % (1 of 100), 2 s so far");
    // an unknown total: the count
    EXPECT_EQ(common::progressText("reading", -1, 4711, 0, 75.0),
              "reading: 4711 so far, 1 min 15 s so far");
    EXPECT_EQ(common::durationText(3725), "1 h 02 min");
}
