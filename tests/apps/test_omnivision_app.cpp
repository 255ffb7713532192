// End-to-end omni-directional camera runs (seed 000): the five robots A-E from rendered
// panoramas, the 30-robot swarm, the conventional method, determinism, bad [omnivision]
// input.
#include <gtest/gtest.h>
#include <mrloc/common/Metrics.h>

#include "MrlocCli.h"

namespace fs = std::filesystem;
using namespace mrloc;
using namespace mrloc::testing_cli;

TEST(MrlocOmnivision, FiveRobotsFromRenderedPanoramas) {
    const std::string out = tmp("omni5");
    const auto r = mrlocCmd("run " + config("omnivision_5robots") + " -q --out " + out);
    ASSERT_EQ(r.code, 0) << r.output;
    const auto m = common::loadJson(out + "/metrics.json");
    const auto& o = m["omnivision"];
    EXPECT_EQ(o["camera"], "render");
    EXPECT_EQ(o["pair"], "A B") << o.dump(2);
    EXPECT_TRUE(o["restarts"].empty());
    for (const char* s : {"t_b", "t_e"}) {
        EXPECT_EQ(o["snapshots"][s]["triangles"], 10) << s;  // all C(5,3), from pixels
        EXPECT_TRUE(o["snapshots"][s]["unresolved"].empty());
    }
    // L from eq. (8): C moved 0.8 m against a 4.7 m baseline, so L is sensitive to the
    // detected bearings (0.65 px).
    EXPECT_NEAR(o["baseline_L_m"].get<double>() / o["true_L_m"].get<double>(), 1, 0.03);
    EXPECT_LT(o["relative_distance_error_paper"]["median"].get<double>(), 0.03);
    EXPECT_LT(o["relative_distance_error_refined"]["median"].get<double>(), 0.01);
    EXPECT_LT(m["rmse_m"].get<double>(), 0.05);  // layout error in the paper's frame
    for (const char* f : {"layout.png", "accuracy.png", "layout.txt", "accuracy.txt"})
        EXPECT_TRUE(fs::exists(out + "/" + f)) << f;
    const std::string page = slurp(out + "/report.html");
    EXPECT_NE(page.find("Relative layout"), std::string::npos);
    EXPECT_NE(page.find("Accuracy against noise"), std::string::npos);
}

TEST(MrlocOmnivision, SwarmOfThirty) {
    const std::string out = tmp("omniswarm");
    const auto r = mrlocCmd("run " + config("omnivision_swarm") + " -q --out " + out);
    ASSERT_EQ(r.code, 0) << r.output;
    const auto m = common::loadJson(out + "/metrics.json");
    const auto& o = m["omnivision"];
    EXPECT_EQ(o["robots"], 30);
    EXPECT_TRUE(o["restarts"].empty()) << o.dump(2);
    EXPECT_EQ(o["pair"], "R01 R02");
    EXPECT_TRUE(o["snapshots"]["t_e"]["unresolved"].empty());
    EXPECT_GT(o["snapshots"]["t_e"]["triangles"].get<int>(), 2400);  // of 4060
    EXPECT_LT(o["relative_distance_error_refined"]["median"].get<double>(), 0.002);
    EXPECT_LT(o["relative_distance_error_refined"]["median"].get<double>(),
              o["relative_distance_error_paper"]["median"].get<double>());
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
        const auto m = common::loadJson(out + "/metrics.json");
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
