// End-to-end omni-directional camera runs (seed 000): the five robots A-E from rendered
// panoramas, the 30-robot swarm, the conventional method, determinism, bad [omnivision]
// input.
#include <gtest/gtest.h>
#include <mrloc/common/Metrics.h>
#include <mrloc/common/Trajectory.h>
#include <mrloc/omnivision/OmniFiles.h>
#include <mrpt/img/CImage.h>

#include <cmath>
#include <map>
#include <numeric>

#include "MrlocCli.h"
#include "PictureChecks.h"

namespace fs = std::filesystem;
using namespace mrloc;
using namespace mrloc::testing_cli;

TEST(MrlocOmnivision, FiveRobotsFromRenderedPanoramas) {
    const std::string out = tmp("omni5");
    const auto r = mrlocCmd("run " + config("omnivision_5robots") + " -q --out " + out);
    ASSERT_EQ(r.code, 0) << r.output;
    expectPicturesReadAtAGlance(out,
                                "omnivision_5robots");  // its pictures, once (test_pictures.cpp)
    const auto m = common::readJsonFile(out + "/metrics.json");
    const auto& o = m["omnivision"];
    EXPECT_EQ(o["camera"], "render");
    EXPECT_EQ(o["pair"], "A B") << o.dump(2);
    EXPECT_TRUE(o["restarts"].empty());
    for (const char* s : {"t_b", "t_e"}) {
        EXPECT_EQ(o["snapshots"][s]["triangles"], 10) << s;  // all C(5,3), from pixels
        EXPECT_TRUE(o["snapshots"][s]["unresolved"].empty());
    }
    // L from eq. (8): C moved 0.8 m against a 4.7 m baseline, so L is sensitive to the
    // detected bearings. Measured (seed 5): L 0.23 % short, paper median 0.28 %, refined
    // 0.26 %, layout RMSE 13.8 mm; each bound is about 1.5 times that (the run is
    // deterministic; the margin is for the renderer's driver). Over 20 seeds the medians are
    // 1.03 % and 0.37 % (doc/omnivision.md).
    EXPECT_NEAR(o["baseline_L_m"].get<double>() / o["true_L_m"].get<double>(), 1, 0.0035);
    EXPECT_LT(o["relative_distance_error_paper"]["median"].get<double>(), 0.0045);
    EXPECT_LT(o["relative_distance_error_refined"]["median"].get<double>(), 0.004);
    EXPECT_LT(m["rmse_m"].get<double>(), 0.021);  // layout error in the paper's frame
    // on the truth's timeline (0-23 s at 20 Hz, 461 stamps a robot): covered from the layout
    // at 12 s on, 221 stamps each; the layout carried by odometry measured 14.6 mm APE RMSE
    // pooled, bound 1.25 times that; the heading measured 0.20 deg RMSE, bound 0.3
    const auto& timeline = m["truth_timeline"];
    EXPECT_EQ(timeline["truth_stamps"], 5 * 461);
    EXPECT_EQ(timeline["covered"], 5 * 221);
    EXPECT_LT(timeline["ape"]["rmse_m"].get<double>(), 0.018);
    EXPECT_LT(timeline["ape_heading"]["rmse_deg"].get<double>(), 0.3);
    // Headings, beyond the paper: measured median (max) 0.043 (0.25) deg from the paper's
    // layout, 0.021 (0.034) deg refined; bounds 1.5 times the medians.
    EXPECT_EQ(o["heading_error_deg_refined"]["robots"], 5);
    EXPECT_LT(o["heading_error_deg_paper"]["median"].get<double>(), 0.065);
    EXPECT_LT(o["heading_error_deg_refined"]["median"].get<double>(), 0.032);
    // The files hold the five robots and the sweep's two axes.
    const auto layout = omnivision::LayoutFile::read(out);
    ASSERT_EQ(layout.points.size(), 5u);
    EXPECT_EQ(layout.a, "A");
    EXPECT_EQ(layout.b, "B");
    // each robot's covariance.<robot>.txt is the refinement's, at the estimate's time: A's
    // zero (the frame's origin), B's y zero (the x axis); the heading's variance and the
    // estimate's yaw are the layout's refined heading
    for (const auto& p : layout.points) {
        const auto cov = common::loadCovariances(out + "/covariance." + p.robot + ".txt");
        ASSERT_EQ(cov.size(), 1u) << p.robot;
        // the layout at t_e = 12 s, then carried by the robot's odometry at each of its
        // 20 Hz readings to the log's end at 23 s
        const auto estimate = common::loadTum(out + "/estimates." + p.robot + ".txt");
        ASSERT_EQ(estimate.size(), 221u) << p.robot;
        EXPECT_NEAR(estimate.back().t - estimate.front().t, 11.0, 1e-6) << p.robot;
        EXPECT_EQ(cov[0].t, estimate[0].t);
        EXPECT_DOUBLE_EQ(cov[0].cov(0, 0), p.cxx) << p.robot;
        EXPECT_DOUBLE_EQ(cov[0].cov(0, 1), p.cxy) << p.robot;
        EXPECT_DOUBLE_EQ(cov[0].cov(1, 1), p.cyy) << p.robot;
        EXPECT_DOUBLE_EQ(cov[0].cov(2, 2), p.cphiphi) << p.robot;
        EXPECT_GT(cov[0].cov(2, 2), 0.0) << p.robot;
        EXPECT_NEAR(estimate[0].pose.yaw(), p.refinedPhi, 1e-9) << p.robot;
        // within 4 sigma of the truth's heading (measured: at most 1.3 sigma)
        EXPECT_LT(std::abs(std::remainder(p.refinedPhi - p.truePhi, 2 * M_PI)),
                  4 * std::sqrt(p.cphiphi))
            << p.robot;
        if (p.robot == "A") {
            EXPECT_EQ(cov[0].cov(0, 0), 0.0);
        }
        if (p.robot == "B") {
            EXPECT_EQ(cov[0].cov(1, 1), 0.0);
        }
        if (p.robot != "A") {
            EXPECT_GT(cov[0].cov(0, 0), 0.0) << p.robot;
        }
    }
    // groundtruth.<robot>.txt is in the paper's frame (truthInEstimateFrame): at the
    // layout's time A is at the origin and B on the +x axis, true_L_m away.
    const auto truthAt = [&](const std::string& robot) {
        const auto p = common::interpolate(common::loadTum(out + "/groundtruth." + robot + ".txt"),
                                           layout.time);
        EXPECT_TRUE(p) << robot;
        return p.value_or(mrpt::poses::CPose3D());
    };
    const auto a = truthAt("A"), b = truthAt("B");
    EXPECT_NEAR(a.x(), 0, 1e-6);
    EXPECT_NEAR(a.y(), 0, 1e-6);
    EXPECT_NEAR(b.y(), 0, 1e-6);
    EXPECT_NEAR(b.x(), o["true_L_m"].get<double>(), 1e-6);
    const auto sweep = omnivision::AccuracyFile::read(out);
    EXPECT_EQ(sweep.distanceName, "odometer");
    EXPECT_EQ(sweep.points.size(), 7u);
    for (const auto& p : sweep.points) EXPECT_EQ(p.trials + p.failures, 100);  // per level
    for (const char* f : {"layout.png", "accuracy.png"}) {
        mrpt::img::CImage img;
        EXPECT_TRUE(img.loadFromFile(out + "/" + f)) << f;
        EXPECT_GT(img.getWidth(), 800u) << f;
    }
    const std::string page = slurp(out + "/report.html");
    EXPECT_NE(page.find("Relative layout"), std::string::npos);
    EXPECT_NE(page.find("Accuracy against noise"), std::string::npos);
    // the headline figures in the section, not only in metrics.json
    EXPECT_NE(page.find("<b>Relative distance error, median (max) over the 10 pairs: the "
                        "paper's solution 0.28 % (0.70 %), refined 0.26 % (0.31 %).</b>"),
              std::string::npos);
    EXPECT_NE(page.find("Snapshot t_b: 10 of the 10 triangles found."), std::string::npos);
}

// The refinement's covariance against its errors (the report's 3-sigma ellipses): per robot,
// the error weighed by the covariance, per free coordinate, averaged over 20 seeds, must be
// near 1 (the issue: within 0.5 and 2). Measured: B 0.80, C 1.00, D 0.58, E 0.95; before
// the detector weighed columns by angle and the refinement knew the rendered bearings'
// noise, B 0.014, C 0.77, D 0.009, E 1.46 (the shipped seeds then differed only in odometry
// noise, so every seed saw the same layout: its one draw, twenty times).
TEST(MrlocOmnivision, ErrorsMatchTheCovarianceOverTwentySeeds) {
    std::map<std::string, std::vector<double>> nees;
    for (int seed = 1; seed <= 20; ++seed) {
        const std::string out = tmp("omni_nees_" + std::to_string(seed));
        // simulate and localize: the layout is localize's; the report's pictures are not needed
        // (1.0 s a seed instead of 1.7)
        ASSERT_EQ(mrlocCmd("simulate " + config("omnivision_5robots") + " -q --seed " +
                           std::to_string(seed) + " --out " + out + " && " + MRLOC_BINARY +
                           " localize " + config("omnivision_5robots") + " " + out +
                           "/omnivision_5robots.rawlog -q --out " + out)
                      .code,
                  0);
        for (const auto& p : omnivision::LayoutFile::read(out).points)
            if (const auto e = omnivision::normalisedSquaredError(p)) nees[p.robot].push_back(*e);
        fs::remove_all(out);
    }
    ASSERT_EQ(nees.size(), 4u);  // A is the frame's origin
    for (const auto& [robot, v] : nees) {
        ASSERT_EQ(v.size(), 20u) << robot;
        const double mean = std::accumulate(v.begin(), v.end(), 0.0) / double(v.size());
        EXPECT_GT(mean, 0.5) << robot;
        EXPECT_LT(mean, 2.0) << robot;
    }
}

TEST(MrlocOmnivision, SwarmOfThirty) {
    const std::string out = tmp("omniswarm");
    const auto r = mrlocCmd("run " + config("omnivision_swarm") + " -q --out " + out);
    ASSERT_EQ(r.code, 0) << r.output;
    expectPicturesReadAtAGlance(out, "omnivision_swarm");  // its pictures, once (test_pictures.cpp)
    const auto m = common::readJsonFile(out + "/metrics.json");
    // what ran, in the paper's terms (doc/omnivision.md's table)
    EXPECT_EQ(m["headline"].value("mechanism", ""),
              "t_b: the full search, as at t_e (search_at_tb = full; paper 000's eq. (11)-(12) "
              "is search_at_tb = localized)");
    const auto& o = m["omnivision"];
    EXPECT_EQ(o["robots"], 30);
    EXPECT_TRUE(o["restarts"].empty()) << o.dump(2);
    EXPECT_EQ(o["pair"], "R01 R02");
    EXPECT_TRUE(o["snapshots"]["t_e"]["unresolved"].empty());
    // Measured 3068 of 4060 (the rest left unlabeled as ambiguous, none wrong): 5 % margin.
    EXPECT_GT(o["snapshots"]["t_e"]["triangles"].get<int>(), 2900);
    EXPECT_LT(o["relative_distance_error_refined"]["median"].get<double>(), 0.002);
    EXPECT_LT(o["relative_distance_error_refined"]["median"].get<double>(),
              o["relative_distance_error_paper"]["median"].get<double>());
    // Headings: measured median 0.073 deg from the paper's layout, 0.0057 deg refined.
    EXPECT_LT(o["heading_error_deg_refined"]["median"].get<double>(), 0.009);
    EXPECT_LT(o["heading_error_deg_refined"]["median"].get<double>(),
              o["heading_error_deg_paper"]["median"].get<double>());
}

// A hundred robots whose 0.15 m bands hide the robots behind them (issue 32). Measured: the
// t_e search places all but 8 robots and t_b all but 12 (hidden ones among them); the
// paper's median relative distance error 3.83 % over 2,761 pairs, refined 0.034 %; refined
// headings 0.0057 deg median. Bounds: 1.5 times the medians, and at least 90 of the robots.
TEST(MrlocOmnivision, SwarmOfAHundredBehindEachOthersBands) {
    const std::string out = tmp("omniswarm100");
    const auto r = mrlocCmd("run " + config("omnivision_swarm100") + " -q --out " + out);
    ASSERT_EQ(r.code, 0) << r.output;
    expectPicturesReadAtAGlance(out,
                                "omnivision_swarm100");  // its pictures, once (test_pictures.cpp)
    const auto m = common::readJsonFile(out + "/metrics.json");
    const auto& o = m["omnivision"];
    EXPECT_EQ(o["robots"], 100);
    EXPECT_LE(o["snapshots"]["t_e"]["unresolved"].size(), 10u);
    EXPECT_GE(o["heading_error_deg_refined"]["robots"].get<int>(), 90);
    EXPECT_LT(o["relative_distance_error_paper"]["median"].get<double>(), 0.058);
    EXPECT_LT(o["relative_distance_error_refined"]["median"].get<double>(), 0.0005);
    EXPECT_LT(o["heading_error_deg_refined"]["median"].get<double>(), 0.0086);
    // the robots it could not place are named, and the run says so and why (metrics.json
    // counts each reason): measured, of the 19 views (both instants), 18 not placed and 1
    // whose camera shows one robot
    const auto status = m["headline"]["status"].get<std::string>();
    EXPECT_NE(status.find("robot views unresolved ("), std::string::npos) << status;
    size_t unresolved = 0, explained = 0;
    for (const char* s : {"t_b", "t_e"}) {
        unresolved += o["snapshots"][s]["unresolved"].size();
        for (const auto& [reason, count] : o["snapshots"][s]["unresolved_why"].items())
            explained += count.get<size_t>();
    }
    EXPECT_GT(unresolved, 0u);
    EXPECT_EQ(explained, unresolved);
    EXPECT_NE(status.find(" not placed: identified both ways with fewer than 2 robots"),
              std::string::npos)
        << status;
    EXPECT_GT(o["snapshots"]["t_e"]["unresolved_why"].value("not_placed", 0), 0);
}

// A hundred robots from pixels (issue 32): 200 rendered panoramas of 8,192 px, the thin bands
// of overlapping robots split by their height. Measured: every robot identified at both
// instants (73,798 and 77,319 triangles), the paper's median relative distance error 2.86 %
// over 3,863 pairs, refined 0.0069 %, refined headings 0.0022 deg; 8.4 s for the run. With
// overlapping bands taken as one marker (the detector without the band's size), 3 robot
// views stay unresolved and 13 % fewer triangles are found (64,135 and 66,343). Bounds: 1.5
// times the medians, 5 % fewer triangles.
TEST(MrlocOmnivision, SwarmOfAHundredRenderedFromPixels) {
    const std::string out = tmp("omniswarm100r");
    const auto r = mrlocCmd("run " + config("omnivision_swarm100_rendered") + " -q --out " + out);
    ASSERT_EQ(r.code, 0) << r.output;
    expectPicturesReadAtAGlance(
        out, "omnivision_swarm100_rendered");  // its pictures, once (test_pictures.cpp)
    const auto m = common::readJsonFile(out + "/metrics.json");
    const auto& o = m["omnivision"];
    EXPECT_EQ(o["robots"], 100);
    EXPECT_EQ(m["headline"]["status"], "every robot identified") << m["headline"].dump(2);
    EXPECT_GT(o["snapshots"]["t_b"]["triangles"].get<int>(), 70000);
    EXPECT_GT(o["snapshots"]["t_e"]["triangles"].get<int>(), 73000);
    EXPECT_LT(o["relative_distance_error_paper"]["median"].get<double>(), 0.043);
    EXPECT_LT(o["relative_distance_error_refined"]["median"].get<double>(), 0.0001);
    EXPECT_LT(o["heading_error_deg_refined"]["median"].get<double>(), 0.0033);
}

// Seed 000 eq. (11)-(12): at t_b only the triangle of the stopped pair and one witness of
// t_e is searched. Confirmed by the witness's odometer turn (beyond the paper), the paper's
// solution is the full search's (the same triangle, the same L); the refinement has one
// odometer instead of 28, so it is less exact. Confirmed as the paper's setting allows (no
// heading), every one of the ten witnesses tried in this swarm is ambiguous: the full search
// runs, as the paper's fall-back, and the report says so.
TEST(MrlocOmnivision, LocalizedSearchAtTbGivesThePapersSolution) {
    const auto runWith = [](const std::string& search) {
        const std::string name = "omni_" + search;
        const std::string ini = writeIniFrom(config("omnivision_swarm"), name, "[omnivision]",
                                             "[omnivision]\nsearch_at_tb = " + search);
        const std::string out = tmp(name);
        const auto r = mrlocCmd("run " + ini + " -q --out " + out);
        EXPECT_EQ(r.code, 0) << r.output;
        return common::readJsonFile(out + "/metrics.json");
    };
    const auto m = runWith("localized_turn");
    const auto& o = m["omnivision"];
    EXPECT_EQ(o["search_at_tb"], "localized_turn");
    EXPECT_EQ(o["snapshots"]["t_b"]["search"], "localized");
    EXPECT_EQ(o["snapshots"]["t_b"]["triangles"], 1);
    ASSERT_EQ(o["localized_searches"].size(), 1u);
    const auto& l = o["localized_searches"][0];
    EXPECT_EQ(l["pair"], "R01 R02");
    EXPECT_EQ(l["witnesses_tried"], 1);
    EXPECT_FALSE(l.contains("full_search_instead"));
    // eq. (12) on 29 images each: at most 28 x 28 x 29 triples (measured 6,580)
    EXPECT_LE(l["image_triples"].get<int>(), 28 * 28 * 29);
    EXPECT_GT(l["triangles_summing_to_180"].get<int>(), 1);  // chance sums (measured 149)
    // Measured: the paper's median 2.64 % as with the full search, refined 0.18 % (0.082 %
    // with the full search); the run counts as every robot identified.
    EXPECT_NEAR(o["relative_distance_error_paper"]["median"].get<double>(), 0.0264, 0.0005);
    EXPECT_LT(o["relative_distance_error_refined"]["median"].get<double>(), 0.0025);
    EXPECT_EQ(m["headline"]["status"], "every robot identified") << m["headline"].dump(2);
    EXPECT_EQ(m["headline"]["mechanism"],
              "t_b: paper 000's eq. (11)-(12), a triangle of the stopped pair and one witness "
              "(search_at_tb = localized_turn), confirmed by the witness's odometer turn "
              "(beyond the paper, which rules out heading information)");

    const auto pm = runWith("localized");
    const auto& po = pm["omnivision"];
    EXPECT_EQ(po["search_at_tb"], "localized");
    EXPECT_EQ(po["snapshots"]["t_b"]["search"], "full");
    ASSERT_EQ(po["localized_searches"].size(), 1u);
    const std::string why = po["localized_searches"][0].value("full_search_instead", "");
    EXPECT_NE(why.find("(10 tried) forms a triangle with them at t_b that the robots it saw "
                       "confirm and no other robot could make"),
              std::string::npos)
        << why;
    EXPECT_EQ(pm["headline"]["mechanism"],
              "t_b: the full search, paper 000's fall-back: eq. (11)-(12) (search_at_tb = "
              "localized) confirmed no witness's triangle");
    // the full search's solution: the same as search_at_tb = full's
    EXPECT_NEAR(po["relative_distance_error_paper"]["median"].get<double>(), 0.0264, 0.0005);
    EXPECT_LT(po["relative_distance_error_refined"]["median"].get<double>(), 0.001);
}

TEST(MrlocOmnivision, ConventionalMethodAndByteIdenticalRepeats) {
    const std::string ini =
        writeIniFrom(config("omnivision_5robots"), "omniconv", "method = proposed      #",
                     "measured_pair = A B\nsnapshot = 12\nmethod = conventional #");
    std::string first;
    for (int i = 0; i < 2; ++i) {
        const std::string out = tmp("omniconv" + std::to_string(i));
        const auto r = mrlocCmd("run " + ini + " -q --out " + out);
        ASSERT_EQ(r.code, 0) << r.output;
        const auto m = common::readJsonFile(out + "/metrics.json");
        EXPECT_EQ(m["omnivision"]["method"], "conventional");
        EXPECT_LT(m["omnivision"]["relative_distance_error_refined"]["median"].get<double>(), 0.01);
        const std::string both =
            slurp(out + "/omnivision_5robots.rawlog") + slurp(out + "/layout.txt");
        if (i == 0) {
            first = both;
        } else {
            EXPECT_TRUE(both == first) << "the same INI and seed gave different outputs";
        }
    }
}

TEST(MrlocOmnivision, BadOmnivisionInputIsAClearErrorAndWritesNothing) {
    struct Case {
        std::string from, to, expected;
    };
    const std::vector<Case> cases = {
        {"refine = true ", "refin = true ", "[omnivision] refin: unknown key"},
        {"pairs = A B, D E", "pairs = A Z", "[omnivision] pairs: robot 'Z' is not in the scenario"},
        {"pairs = A B, D E", "pairs = A A", "pairs of two different robots"},
        {"t_e = 12 ", "t_e = 9 ", "[omnivision] t_e: must be after t_b"},
        {"duration = 23", "duration = 11", "after [scenario] duration"},
        {"camera = render ", "camera = fisheye ", "[omnivision] camera"},
        {"view_width = 512 ", "view_width = wide ", "[omnivision] view_width"},
        // a width whose rows are not whole 4-byte words overran the rendered picture's memory
        {"view_width = 512 ", "view_width = 513 ", "[omnivision] view_width: a multiple of 4"},
    };
    for (const auto& c : cases) {
        const std::string ini = writeIniFrom(config("omnivision_5robots"), "badomni", c.from, c.to);
        const std::string out = tmp("badomni");
        const auto r = mrlocCmd("run " + ini + " -q --out " + out);
        EXPECT_EQ(r.code, 1) << c.to << "\n" << r.output;
        EXPECT_NE(r.output.find(c.expected), std::string::npos) << c.to << "\n" << r.output;
        EXPECT_FALSE(fs::exists(out)) << c.to;
    }
}
