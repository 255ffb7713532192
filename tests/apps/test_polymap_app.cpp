// End-to-end polygon-map runs: the steps map from config/polymap_steps.ini, the map-file
// scenario, determinism, and bad [polymap] input.
#include <gtest/gtest.h>
#include <mrloc/common/Metrics.h>
#include <mrloc/common/Polygon.h>
#include <mrloc/polymap/PolymapFiles.h>
#include <mrloc/report/PictureLayout.h>
#include <mrpt/core/format.h>
#include <mrpt/img/CImage.h>

#include <cmath>
#include <sstream>

#include "MrlocCli.h"
#include "PictureChecks.h"
#include "TestPaths.h"

namespace fs = std::filesystem;
using namespace mrloc;
using namespace mrloc::testing_cli;

namespace {

/** The headline's "start error (worst robot)" (m): the start found against the truth there. */
double startErrorOf(const nlohmann::json& metrics) {
    for (const auto& f : metrics["headline"]["figures"])
        if (f["name"] == "start error (worst robot)" && f["value"].is_number())
            return f["value"].get<double>();
    ADD_FAILURE() << "no start error in the headline: " << metrics["headline"].dump();
    return NAN;
}

}  // namespace

TEST(MrlocPolymap, StepsMapRunFindsTwelveHypothesesWithTheTruthAmongThem) {
    const std::string out = tmp("polymap_steps");
    const auto r = mrlocCmd("run " + config("polymap_steps") + " -q --out " + out);
    ASSERT_EQ(r.code, 0) << r.output;
    expectPicturesReadAtAGlance(out, "polymap_steps");  // its pictures, once (test_pictures.cpp)
    const auto m = common::readJsonFile(out + "/metrics.json");
    // what ran, in the paper's terms (doc/polymap.md's table)
    EXPECT_EQ(m["headline"]
                  .value("mechanism", "")
                  .rfind("paper 002's hypotheses from the exact visibility polygon", 0),
              0u)
        << m["headline"];
    const auto& p = m["polymap"];
    EXPECT_EQ(p["map_vertices"], 148);
    EXPECT_EQ(p["robots"]["r1"]["hypotheses"], 12) << p.dump(2);
    EXPECT_TRUE(m["robots"]["r1"]["truth_in_hypotheses"].get<bool>()) << m.dump(2);
    EXPECT_LT(m["robots"]["r1"]["nearest_hypothesis_m"].get<double>(), 0.02);
    EXPECT_EQ(m["robots"]["r1"]["estimates"], 0);  // not localized yet: 12 candidates
    mrpt::img::CImage png;
    ASSERT_TRUE(png.loadFromFile(out + "/polymap.r1.png"));
    // the drawing 1200 px wide (the map is wider than high), framed by axes, the legend in
    // a panel right of it
    const auto layout = report::readLayout(out + "/polymap.r1.png");
    ASSERT_TRUE(layout && layout->legend);
    EXPECT_EQ(layout->data.width(), 1200);
    EXPECT_LT(layout->data.height(), 600);
    EXPECT_GE(layout->legend->x0, layout->data.x1);
    EXPECT_EQ(png.getWidth(), unsigned(layout->width));
    EXPECT_EQ(common::Polygon::load(out + "/map.poly").size(), 148u);
    EXPECT_EQ(polymap::HypothesesFile::read(out, "r1").hypotheses.size(), 12u);
    EXPECT_NE(slurp(out + "/report.html").find("12 hypotheses"), std::string::npos);
    // the headline: the truth's place among them, numbered as in the table (start_site = 4)
    EXPECT_NE(slurp(out + "/report.html")
                  .find("<b>12 hypotheses; the true start is hypothesis #4</b>, 0.000 m"),
              std::string::npos);
}

TEST(MrlocPolymap, MapFileRunWithTwoRoomsAndByteIdenticalRepeats) {
    std::string first;
    for (int i = 0; i < 2; ++i) {
        const std::string out = tmp("polymap_file" + std::to_string(i));
        const auto r = mrlocCmd("run " + config("polymap_file") + " -q --out " + out);
        ASSERT_EQ(r.code, 0) << r.output;
        if (i == 0)
            expectPicturesReadAtAGlance(out,
                                        "polymap_file");  // its pictures, once (test_pictures.cpp)
        const auto m = common::readJsonFile(out + "/metrics.json");
        EXPECT_EQ(m["polymap"]["robots"]["r1"]["hypotheses"], 2) << m.dump(2);
        EXPECT_TRUE(m["robots"]["r1"]["truth_in_hypotheses"].get<bool>());
        const std::string both =
            slurp(out + "/polymap_file.rawlog") + slurp(out + "/hypotheses.r1.txt");
        if (i == 0) {
            first = both;
        } else {
            EXPECT_TRUE(both == first) << "the same INI and seed gave different outputs";
        }
    }
}

TEST(MrlocPolymap, BadPolymapInputIsAClearErrorAndWritesNothing) {
    const std::string badPoly = (fs::path(testing::TempDir()) / "bowtie.poly").lexically_normal();
    std::ofstream(badPoly) << "0 0\n3 3\n3 0\n0 2\n";
    struct Case {
        std::string from, to, expected, base = "polymap_steps";
    };
    const std::vector<Case> cases = {
        {"steps             = 6", "stesp = 6", "[polymap] stesp: unknown key"},
        {"start_site        = 4", "start_site = 99", "start_site: 99, but the steps map"},
        {"start_site        = 4", "start = 500 500", "outside the floor plan"},
        {"map     = ../maps/two_rooms.poly", "map = /nonexistent/x.poly",
         "[polymap] map: no such file '/nonexistent/x.poly'", "polymap_file"},
        {"map     = ../maps/two_rooms.poly", "map = two_rooms.poly",
         "[polymap] map: no such file '" + testing::TempDir() +
             "two_rooms.poly' (a relative path is "
             "taken from the INI's folder)",
         "polymap_file"},
        {"map     = ../maps/two_rooms.poly", "map = /tmp", "[polymap] map: '/tmp' is a folder",
         "polymap_file"},
        {"map     = ../maps/two_rooms.poly", "map = " + badPoly, "intersects itself",
         "polymap_file"},
        {"map     = ../maps/two_rooms.poly",
         "map = " + std::string(MRLOC_SOURCE_DIR) + "/maps/two_rooms.poly\ngenerator = rooms",
         "either map = <file.poly> or a generator", "polymap_file"},
        {"scan_max_range    = 100", "scan_max_range = 1", "has no return"},
        {"heading           = 30", "heading = north", "[polymap] heading: expected a number"},
    };
    for (const auto& c : cases) {
        const std::string ini = writeIniFrom(config(c.base), "badpoly", c.from, c.to);
        const std::string out = tmp("badpoly");
        const auto r = mrlocCmd("run " + ini + " -q --out " + out);
        EXPECT_EQ(r.code, 1) << c.to << "\n" << r.output;
        EXPECT_NE(r.output.find(c.expected), std::string::npos) << c.to << "\n" << r.output;
        if (c.expected != "has no return") {
            EXPECT_FALSE(fs::exists(out)) << c.to;
        }
    }
}

TEST(MrlocPolymap, SimulateLocalizeAndRunWriteTheSameEffectiveIniWhichRunsAgain) {
    const std::string a = tmp("eff_sim"), b = tmp("eff_loc"), c = tmp("eff_run"),
                      d = tmp("eff_again");
    const std::string ini = config("polymap_steps");
    ASSERT_EQ(mrlocCmd("simulate " + ini + " -q --out " + a).code, 0);
    ASSERT_EQ(mrlocCmd("localize " + ini + " " + a + "/polymap_steps.rawlog -q --out " + b).code,
              0);
    ASSERT_EQ(mrlocCmd("run " + ini + " -q --out " + c).code, 0);
    const std::string effective = slurp(c + "/effective.ini");
    EXPECT_NE(effective.find("[polymap]"), std::string::npos);
    EXPECT_EQ(slurp(a + "/effective.ini"), effective);
    EXPECT_EQ(slurp(b + "/effective.ini"), effective);
    // effective.ini is a complete INI: it runs again to the same rawlog and result.
    ASSERT_EQ(mrlocCmd("run " + c + "/effective.ini -q --out " + d).code, 0);
    EXPECT_EQ(slurp(d + "/polymap_steps.rawlog"), slurp(c + "/polymap_steps.rawlog"));
    EXPECT_EQ(slurp(d + "/hypotheses.r1.txt"), slurp(c + "/hypotheses.r1.txt"));
}

TEST(MrlocPolymap, AFailedRunLeavesNothingBehind) {
    // Every beam beyond scan_max_range: the simulation succeeds, the localizer refuses a
    // scan with no return; the simulated rawlog must not stay behind.
    const std::string ini = writeIniFrom(config("polymap_steps"), "noreturn",
                                         "scan_max_range    = 100", "scan_max_range = 0.01");
    const std::string out = tmp("noreturn");
    const auto r = mrlocCmd("run " + ini + " -q --out " + out);
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_FALSE(fs::exists(out)) << r.output;
}

TEST(MrlocPolymap, PaperExperimentOnTheSteps76MapLocalizesFromEveryStart) {
    // config/polymap_steps76.ini: n = 76, k = 6, elimination = all (cells, randomized at
    // X = 100 and 500, triangulation, windows): every start ends with exactly its truth.
    std::string first;
    for (int i = 0; i < 2; ++i) {
        const std::string out = tmp("polymap_steps76_" + std::to_string(i));
        const auto r = mrlocCmd("run " + config("polymap_steps76") + " -q --out " + out);
        ASSERT_EQ(r.code, 0) << r.output;
        if (i == 0)
            expectPicturesReadAtAGlance(
                out, "polymap_steps76");  // its pictures, once (test_pictures.cpp)
        const auto file = polymap::EliminationFile::read(out);
        ASSERT_EQ(file.columns.size(), 5u);
        // The first-separation distance bounds every localization's travel (it is found from
        // above, to within the chord sampling of 5 cm and the 10 cm clearance).
        ASSERT_TRUE(std::isfinite(file.bound));
        EXPECT_GT(file.bound, 1.0);
        EXPECT_EQ(file.trueStart, 3u);  // start_site = 4
        const char* names[] = {"cells", "randomized:100", "randomized:500", "triangulation",
                               "windows"};
        for (size_t c = 0; c < 5; ++c) {
            const auto& col = file.columns[c];
            EXPECT_EQ(col.name, names[c]);
            ASSERT_EQ(col.travel.size(), 6u);
            for (size_t s = 0; s < 6; ++s) {
                EXPECT_EQ(col.survivors[s], 1) << col.name << " start " << s;
                EXPECT_EQ(col.fallbacks[s], 0) << col.name << " start " << s;  // the paper's map
                EXPECT_GE(col.probes[s], 1);
                EXPECT_LE(col.probes[s], 5);  // at most k - 1
                // Measured 4.9-27 m on this map (step width 16 m): a leg out of the branch
                // and a few metres of corridor; 60 m would be the whole staircase.
                EXPECT_GT(col.travel[s], 2.0);
                EXPECT_GE(col.travel[s], file.bound - 0.15) << col.name << " start " << s;
                EXPECT_LT(col.travel[s], 60.0);
            }
            ASSERT_FALSE(col.route.empty());
            EXPECT_EQ(col.stops.size(), (size_t)col.probes[file.trueStart]);
        }
        // The verification tour from every start (k = 6: searched exactly over the
        // algorithms' candidates and probes): no algorithm travels less, and it is never
        // shorter than the first separation (less its 0.15 m). Measured: 4.93-6.41 m, one
        // probe each; the algorithms' mean over it 1.01 (cells) to 1.16 (randomized, X = 100).
        ASSERT_EQ(file.tour.size(), 6u);
        ASSERT_EQ(file.tourProbes.size(), 6u);
        for (size_t s = 0; s < 6; ++s) {
            EXPECT_GE(file.tour[s], file.bound - 0.15) << "start " << s;
            EXPECT_GE(file.tourProbes[s], 1) << "start " << s;
            for (const auto& col : file.columns)
                EXPECT_LE(file.tour[s], col.travel[s] + 1e-9) << col.name << " start " << s;
        }
        // Each algorithm's mean path over the mean tour (the aim: under 1.5).
        // Measured 1.01, 1.16, 1.07, 1.05, 1.04 (windows as seed 002's reference [4] defines
        // them; the stretches of OI's boundary mrloc took for windows before gave 1.43);
        // limits about 5 % above, so that a worse probe choice shows.
        const double limits[] = {1.06, 1.22, 1.12, 1.10, 1.09};
        double meanTour = 0;
        for (double d : file.tour) meanTour += d / 6;
        for (size_t c = 0; c < 5; ++c) {
            double mean = 0;
            for (double d : file.columns[c].travel) mean += d / 6;
            EXPECT_LT(mean / meanTour, limits[c]) << file.columns[c].name;
        }
        ASSERT_EQ(file.trueTour.size(), (size_t)file.tourProbes[file.trueStart]);
        ASSERT_GE(file.trueTourRoute.size(), 2u);
        EXPECT_EQ(file.trueTourRoute.back(), file.trueTour.back());
        double along = 0;  // the drawn route is the tour
        for (size_t k = 1; k < file.trueTourRoute.size(); ++k)
            along += (file.trueTourRoute[k] - file.trueTourRoute[k - 1]).norm();
        EXPECT_NEAR(along, file.tour[file.trueStart], 1e-9);
        const auto times = polymap::EliminationTimes::read(out);
        ASSERT_EQ(times.seconds.size(), 5u);
        EXPECT_EQ(times.seconds[0].size(), 6u);
        const std::string html = slurp(out + "/report.html");
        EXPECT_NE(html.find("paper 002 Table 1"), std::string::npos);
        EXPECT_NE(html.find("mean d / mean tour"), std::string::npos);
        EXPECT_NE(html.find("polymap.r1.routes.png"), std::string::npos);
        mrpt::img::CImage png;
        ASSERT_TRUE(png.loadFromFile(out + "/polymap.r1.routes.png"));
        // Same INI, same seed: the same decisions, byte for byte (times are kept apart).
        const std::string text = slurp(polymap::EliminationFile::path(out));
        if (i == 0)
            first = text;
        else
            EXPECT_EQ(text, first);
    }
}

// config/polymap_steps148_shafts.ini, the steps map closest to paper 002's text (issue 55):
// the simulated robot localizes, every start of every algorithm ends on its truth, the path
// grows from the end steps to the middle ones as in the paper's Table 1, and where the order
// of the algorithms is not the paper's the report says at which probe each parts from
// algorithm 1. Measured: the run 51.7 m of travel, start error 0.25 mm; Table 1 means cells
// 14.86, randomized 28.37 / 27.34, triangulation 17.83, windows 26.22 m; the windows
// algorithm parts from cells at probe 5 (3 hypotheses left against 1).
TEST(MrlocPolymap, StepsJoinedByShaftsRunsThePapersTablesAndSaysWhereTheOrderDiffers) {
    const std::string out = tmp("polymap_steps148_shafts");
    const auto r = mrlocCmd("run " + config("polymap_steps148_shafts") + " -q --out " + out);
    ASSERT_EQ(r.code, 0) << r.output;
    expectPicturesReadAtAGlance(
        out, "polymap_steps148_shafts");  // its pictures, once (test_pictures.cpp)
    const auto m = common::readJsonFile(out + "/metrics.json");
    EXPECT_TRUE(m["polymap"]["robots"]["r1"]["elimination"]["localized"].get<bool>());
    EXPECT_LT(startErrorOf(m), 0.005);
    const auto file = polymap::EliminationFile::read(out);
    ASSERT_EQ(file.columns.size(), 5u);
    for (const auto& col : file.columns) {
        ASSERT_EQ(col.travel.size(), 12u);
        for (size_t s = 0; s < 12; ++s) EXPECT_EQ(col.survivors[s], 1) << col.name << " " << s;
        // ends (starts 1-2, 11-12) against the middle (5-8): 4.9-7.6 m and 13.4-53.8 m
        for (const size_t end : {0, 1, 10, 11}) EXPECT_LT(col.travel[end], 8.0) << col.name;
        for (const size_t mid : {4, 5, 6, 7}) EXPECT_GT(col.travel[mid], 11.0) << col.name;
        ASSERT_EQ(col.stopsLeft.size(), col.stops.size());
        EXPECT_EQ(col.stopsLeft.back(), 1) << col.name;
    }
    const std::string html = slurp(out + "/report.html");
    EXPECT_NE(html.find("From the run's start (start 4) the algorithms first part from cells"),
              std::string::npos);
    EXPECT_NE(html.find("windows at probe 5: (32.50, 11.88) m, leaving 3 hypotheses, where "
                        "cells took (32.38, 10.10) m, leaving 1 hypothesis"),
              std::string::npos);
}

TEST(MrlocPolymap, SweepOverMapSizesDrawsFigsSixAndSeven) {
    // polymap_steps76.ini with a small sweep: steps maps of 1 and 2 steps (n = 28 and 52),
    // two starts each: every algorithm localizes, and both figures are drawn.
    const std::string ini = (fs::path(testing::TempDir()) / "sweep.ini").lexically_normal();
    {
        std::ofstream f(ini);
        f << slurp(config("polymap_steps76")) << "sweep_steps = 1 2\nsweep_starts = 2\n";
    }
    const std::string out = tmp("polymap_sweep");
    const auto r = mrlocCmd("run " + ini + " -q --out " + out);
    ASSERT_EQ(r.code, 0) << r.output;
    const auto sweep = polymap::EliminationSweepFile::read(out);
    ASSERT_EQ(sweep.rows.size(), 10u);  // 2 maps x 5 algorithms
    for (const auto& row : sweep.rows) {
        EXPECT_TRUE(row.n == 28 || row.n == 52) << row.n;
        EXPECT_EQ(row.k, row.n == 28 ? 2 : 4);
        EXPECT_EQ(row.starts, 2);
        EXPECT_EQ(row.notLocalized, 0) << row.column << " n = " << row.n;
        EXPECT_GT(row.meanTravel, 1.0);
    }
    for (const char* png : {"/elimination.fig6.png", "/elimination.fig7.png"}) {
        mrpt::img::CImage image;
        ASSERT_TRUE(image.loadFromFile(out + png)) << png;
        EXPECT_EQ(image.getWidth(), 900u);
    }
    EXPECT_NE(slurp(out + "/report.html").find("paper 002 Figs. 6-7"), std::string::npos);
}

TEST(MrlocPolymap, DrivingRobotEliminatesAndLocalizeReplaysIt) {
    // config/polymap_steps76.ini: the robot drives to probe after probe (algorithm 1) until
    // one hypothesis is left. Measured: 3 probes, 6.40 m, RMSE 0.28 mm over the 4 scans (the
    // start and the probes); bounds 2 mm and 20 m, margins for other noise draws (the worst
    // over 72 runs, 4 algorithms x every start of n = 76 and 148: 1.34 mm).
    const std::string out = tmp("polymap_drive76");
    const auto r = mrlocCmd("run " + config("polymap_steps76") + " -q --out " + out);
    ASSERT_EQ(r.code, 0) << r.output;
    const auto m = common::readJsonFile(out + "/metrics.json");
    const auto& e = m["polymap"]["robots"]["r1"]["elimination"];
    EXPECT_TRUE(e["localized"].get<bool>()) << e.dump();
    EXPECT_EQ(e["left"], 1);
    EXPECT_GE(e["probes"].get<int>(), 1);
    EXPECT_LE(e["probes"].get<int>(), 5);
    EXPECT_LT(e["travel_m"].get<double>(), 20.0);
    EXPECT_LT(startErrorOf(m), 0.002);
    // the start found, carried by odometry, covers every truth stamp (the first scan is the
    // log's first stamp); measured 7.7 mm APE RMSE over the 6.4 m drive (odometry's drift:
    // odometry alone from the true start 7.5 mm), bound 1.3 times that
    EXPECT_EQ(m["truth_timeline"]["covered"], m["truth_timeline"]["truth_stamps"]);
    EXPECT_LT(m["truth_timeline"]["ape"]["rmse_m"].get<double>(), 0.01);
    EXPECT_NE(slurp(out + "/report.html").find("The robot eliminated as it drove"),
              std::string::npos);
    // `mrloc localize` on the rawlog takes the same decisions: the same estimates, byte for byte.
    const std::string replay = tmp("polymap_drive76_replay");
    const auto l = mrlocCmd("localize " + config("polymap_steps76") + " " + out +
                            "/polymap_steps76.rawlog -q --out " + replay);
    ASSERT_EQ(l.code, 0) << l.output;
    EXPECT_EQ(slurp(replay + "/estimates.r1.txt"), slurp(out + "/estimates.r1.txt"));
}

TEST(MrlocPolymap, DrivingWithEveryAlgorithmFromTwoStarts) {
    for (const char* strategy : {"cells", "randomized", "triangulation", "windows"})
        for (const int site : {1, 6}) {
            const std::string ini = (fs::path(testing::TempDir()) / "drive.ini").lexically_normal();
            {
                std::ofstream f(ini);
                std::string text = slurp(config("polymap_steps76"));
                text.replace(text.find("drive             = cells"), 25,
                             std::string("drive = ") + strategy);
                text.replace(text.find("start_site        = 4"), 21,
                             "start_site = " + std::to_string(site));
                f << text;
            }
            const std::string out = tmp(std::string("polymap_drive_") + strategy);
            const auto r = mrlocCmd("run " + ini + " -q --out " + out);
            ASSERT_EQ(r.code, 0) << r.output;
            const auto m = common::readJsonFile(out + "/metrics.json");
            EXPECT_TRUE(m["polymap"]["robots"]["r1"]["elimination"]["localized"].get<bool>())
                << strategy << " start " << site;
            EXPECT_LT(startErrorOf(m), 0.002) << strategy << " start " << site;
        }
}

// The radius where the elimination looks for the robot at its probe is the simulator's own
// (sim::arrivalRadius + 1 cm), not a constant: a robot at 1 m/s with 50 ms steps may stop up
// to 5 cm short of its probe, beyond the 3 cm once assumed. The run localizes, and the replay
// of its rawlog (the same INI) takes the same decisions. (On this map the robot happened to
// stop within 3 cm, so the old constant passes too: this guards the scenario, the radius's
// formula is sim::arrivalRadius's.)
TEST(MrlocPolymap, AFastRobotWithLongStepsIsFoundAtItsProbes) {
    const std::string ini =
        writeIniFrom(config("polymap_steps76"), "fast_robot", "robots   = r1",
                     "robots   = r1\ndt       = 0.05\n\n[robot.r1]\nspeed = 1\n");
    const std::string out = tmp("polymap_fast");
    const auto r = mrlocCmd("run " + ini + " -q --out " + out);
    ASSERT_EQ(r.code, 0) << r.output;
    const auto m = common::readJsonFile(out + "/metrics.json");
    const auto& e = m["polymap"]["robots"]["r1"]["elimination"];
    EXPECT_TRUE(e["localized"].get<bool>()) << e.dump();
    EXPECT_EQ(e["left"], 1);
    const std::string replay = tmp("polymap_fast_replay");
    const auto l =
        mrlocCmd("localize " + ini + " " + out + "/polymap_steps76.rawlog -q --out " + replay);
    ASSERT_EQ(l.code, 0) << l.output;
    EXPECT_EQ(slurp(replay + "/estimates.r1.txt"), slurp(out + "/estimates.r1.txt"));
}

namespace {

/** config/polymap_rooms.ini (map seed 7, the robot at heading -60 deg) driving with
 *  `strategy` on `rooms` rooms laid out `layout`, the robot in room `site`, as
 *  <TempDir>/<name>.ini. */
std::string drivingRoomsIni(const std::string& name, const std::string& strategy, int rooms,
                            const std::string& layout, int site, const std::string& extra = "") {
    std::string text = slurp(config("polymap_rooms"));
    const auto replace = [&](const std::string& from, const std::string& to) {
        const auto pos = text.find(from);
        EXPECT_NE(pos, std::string::npos) << from;
        text.replace(pos, from.size(), to);
    };
    replace("duration = 0.1", "duration = 3000");
    replace("rooms      = 5 ", "room_layout = " + layout + "\nrooms = " + std::to_string(rooms));
    replace("start_site = 3", "start_site = " + std::to_string(site) + "\ndrive = " + strategy +
                                  "\nscan_rate = 0\n" + extra);
    const std::string path = testing::TempDir() + "/" + name + ".ini";
    std::ofstream(path) << text;
    return path;
}

/** `mrloc run` of drivingRoomsIni(name, ...) into the run folder tmp("polymap_" + name). */
struct RoomsRun {
    Result result;
    std::string out;
};
RoomsRun runDrivingRooms(const std::string& name, const std::string& strategy, int rooms,
                         const std::string& layout, int site, const std::string& extra = "") {
    const std::string ini = drivingRoomsIni(name, strategy, rooms, layout, site, extra);
    const std::string out = tmp("polymap_" + name);
    return {mrlocCmd("run " + ini + " -q --out " + out), out};
}

/** The run in `out` ended on one hypothesis after at most `travel` m, its start within
 *  `rmse` m of the truth. */
void expectLocalized(const std::string& out, const std::string& strategy, double travel,
                     double rmse) {
    const auto m = common::readJsonFile(out + "/metrics.json");
    const auto& e = m["polymap"]["robots"]["r1"]["elimination"];
    EXPECT_TRUE(e["localized"].get<bool>()) << strategy << " " << e.dump();
    EXPECT_LT(e["travel_m"].get<double>(), travel) << strategy;
    EXPECT_LT(startErrorOf(m), rmse) << strategy;
}

/** The robot's start as the run in `out` placed it: its ground truth's first pose (x, y). */
std::pair<double, double> firstTruePosition(const std::string& out) {
    std::istringstream gt(slurp(out + "/groundtruth.r1.txt"));
    std::string header;
    std::getline(gt, header);
    double t = 0, x = NAN, y = NAN;
    gt >> t >> x >> y;
    return {x, y};
}

}  // namespace

// Twenty identical rooms side by side, the robot in the tenth: each algorithm drives until the
// true start alone is left. Before a probe whose scan rules nothing out was avoided, the
// triangulation algorithm drove back to the same probe for ever (issue 29). Measured: travel
// 3.24 m (cells), 3.33 (randomized), 4.17 (triangulation), 3.39 (windows), start errors
// 1.1-1.8 mm; bounds 10 m and 5 mm.
TEST(MrlocPolymap, TwentyIdenticalRoomsEveryAlgorithmEnds) {
    for (const char* strategy : {"cells", "randomized", "triangulation", "windows"}) {
        const auto [r, out] =
            runDrivingRooms(std::string("rooms20_") + strategy, strategy, 20, "side", 10);
        ASSERT_EQ(r.code, 0) << strategy << "\n" << r.output;
        expectLocalized(out, strategy, 10.0, 0.005);
    }
}

// Two rooms in a row joined by a passage narrower than twice the clearance: the robot may
// enter no place where the rooms' views differ, so the run says so and exits 3 (a method
// that failed on its input), with the report written.
TEST(MrlocPolymap, IdenticalRoomsBehindNarrowPassagesSayWhy) {
    const auto [r, out] =
        runDrivingRooms("narrow", "cells", 2, "row", 1, "neck_width = 0.25\nclearance = 0.15\n");
    EXPECT_EQ(r.code, 3) << r.output;
    EXPECT_NE(r.output.find("no probe separates the 2 hypotheses left"), std::string::npos)
        << r.output;
    const auto m = common::readJsonFile(out + "/metrics.json");
    EXPECT_FALSE(m["polymap"]["robots"]["r1"]["elimination"]["localized"].get<bool>());
    EXPECT_EQ(m["polymap"]["robots"]["r1"]["elimination"]["left"], 2);
}

// The same rooms with 0.125 m passages, seen with 1 cm range noise: the passages are within
// the scan's tolerance (0.091 m here) of the walls beside them, so the sensed view's boundary
// is beyond the tolerance of every place's exact view (before issue 55: 0 hypotheses, the
// truth refused). The beams' second chance (99 % of them within the tolerance of V(p)) keeps
// both rooms, the truth among them; the passages are too narrow to enter, so no probe
// separates them and the run says so (exit 3).
TEST(MrlocPolymap, FeaturesBelowTheScansToleranceKeepTheTruthByTheBeams) {
    const auto [r, out] = runDrivingRooms("narrower", "cells", 2, "row", 1, "neck_width = 0.125\n");
    EXPECT_EQ(r.code, 3) << r.output;
    EXPECT_NE(r.output.find("no probe separates the 2 hypotheses left"), std::string::npos)
        << r.output;
    const auto m = common::readJsonFile(out + "/metrics.json");
    const auto& robot = m["polymap"]["robots"]["r1"];
    ASSERT_EQ(robot["hypotheses"], 2) << robot.dump();
    // the truth (the robot's first ground-truth pose) is one of them, within 5 mm
    const auto [x, y] = firstTruePosition(out);
    double nearest = INFINITY;
    for (const auto& p : robot["points"])
        nearest = std::min(nearest, std::hypot(p[0].get<double>() - x, p[1].get<double>() - y));
    EXPECT_LT(nearest, 0.005) << robot.dump();
}

// Three identical rooms with a pillar each (holes in the map, and in OI): a driving run
// localizes with every algorithm; the run's map.poly keeps the pillars as rings, and the
// same map read back from that file with `localizer = exact` localizes too. Measured: travel
// 2.83 (cells), 3.33 (randomized), 2.97 (triangulation), 2.90 m (windows), start errors
// 1.2-2.1 mm; bounds 10 m and 5 mm, as for the rooms above.
TEST(MrlocPolymap, RoomsWithPillarsLocalizeFromAGeneratedMapAndFromItsPolyFile) {
    std::string poly, lastRun;
    for (const char* strategy : {"cells", "randomized", "triangulation", "windows"}) {
        const auto [r, out] = runDrivingRooms(std::string("pillars_") + strategy, strategy, 3,
                                              "side", 2, "pillar = 0.5\n");
        lastRun = out;
        ASSERT_EQ(r.code, 0) << strategy << "\n" << r.output;
        expectLocalized(out, strategy, 10.0, 0.005);
        // normalised: "//" starts a comment in an MRPT INI, and TempDir() ends in '/'
        poly = fs::path(out + "/map.poly").lexically_normal().string();
    }
    const auto P = common::Polygon::load(poly);
    ASSERT_EQ(P.ringCount(), 4u);  // the floor and three pillars
    EXPECT_NEAR(P.area(), common::Polygon::fromVertices(P.ringVertices(0), "outer").area() - 0.75,
                1e-9);
    // the robot's start as the generator placed it: the run's ground truth, first pose
    const auto [x, y] = firstTruePosition(lastRun);
    ASSERT_TRUE(std::isfinite(x) && std::isfinite(y));
    // config/polymap_rooms.ini's scenario and scanner, the map from the file
    const std::string text = mrpt::format(
        "[scenario]\nname = pillars_file\nmethod = polymap\nseed = 2\nduration = 3000\n"
        "robots = r1\n[polymap]\nmap = %s\nlocalizer = exact\nstart = %.17g %.17g\n"
        "heading = -60\nscan_range_sigma = 0.01\ndrive = windows\nscan_rate = 0\n",
        poly.c_str(), x, y);
    const std::string ini = testing::TempDir() + "/pillars_file.ini";
    std::ofstream(ini) << text;
    const std::string fromFile = tmp("polymap_pillars_file");
    const auto r = mrlocCmd("run " + ini + " -q --out " + fromFile);
    ASSERT_EQ(r.code, 0) << r.output;
    const auto m = common::readJsonFile(fromFile + "/metrics.json");
    EXPECT_TRUE(m["polymap"]["robots"]["r1"]["elimination"]["localized"].get<bool>());
    EXPECT_EQ(m["polymap"]["robots"]["r1"]["hypotheses"].get<int>(), 3);
    EXPECT_LT(startErrorOf(m), 0.005);
}

// issue 52, one seed: the randomized algorithm's points drew from elimination_seed = 1
// whatever --seed was, so a batch over seeds repeated the same draws. Now --seed reaches
// them; elimination_seed, when given, fixes them and the report says so.
TEST(MrlocPolymap, TheRunsSeedReachesTheRandomizedDrawsUnlessTheIniFixesThem) {
    const auto experiment = [](long seed, const std::string& fixed) {
        const std::string out =
            tmp("polymap_seed_" + std::to_string(seed) + (fixed.empty() ? "" : "_fixed"));
        const std::string ini = writeIniFrom(
            config("polymap_steps"), "polymap_seed" + fixed, "angle_tolerance",
            "elimination = randomized\nrandom_points = 100\n" +
                (fixed.empty() ? "" : "elimination_seed = " + fixed + "\n") + "angle_tolerance");
        const auto r =
            mrlocCmd("run " + ini + " -q --seed " + std::to_string(seed) + " --out " + out);
        EXPECT_EQ(r.code, 0) << r.output;
        const auto file = polymap::EliminationFile::read(out);
        EXPECT_EQ(file.columns.size(), 1u);
        return std::make_pair(file.columns.at(0), slurp(out + "/report.html"));
    };
    const auto [one, reportOne] = experiment(1, "");
    const auto [two, reportTwo] = experiment(2, "");
    // the scan's noise moves the hypotheses by about 0.2 mm from one seed to the next; the
    // random points move the routes by metres
    const auto largestDifference = [](const std::vector<double>& a, const std::vector<double>& b) {
        EXPECT_EQ(a.size(), b.size());
        double d = 0;
        for (size_t i = 0; i < std::min(a.size(), b.size()); ++i)
            d = std::max(d, std::abs(a[i] - b[i]));
        return d;
    };
    // 12 starts, each localized from its own random points: two seeds' routes differ
    EXPECT_GT(largestDifference(one.travel, two.travel), 0.1);
    EXPECT_EQ(reportOne.find("fixed sub-seeds"), std::string::npos);

    const auto [fixedOne, reportFixed] = experiment(1, "5");
    const auto [fixedTwo, reportFixedTwo] = experiment(2, "5");
    EXPECT_LT(largestDifference(fixedOne.travel, fixedTwo.travel), 1e-3);
    EXPECT_EQ(fixedOne.probes, fixedTwo.probes);
    EXPECT_NE(reportFixed.find("fixed sub-seeds"), std::string::npos);
    EXPECT_NE(reportFixed.find("not from the run's seed: [polymap] elimination_seed = 5"),
              std::string::npos);
}
