// The honest outcome's pieces: the headline as metrics.json holds it, the CLI's line, the
// trajectory figures with the odometry baseline kept apart, and the "did you mean" lookup.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/LocalizationRun.h>
#include <mrloc/common/Names.h>
#include <mrloc/common/Outcome.h>

#include <algorithm>
#include <cmath>

namespace {

using namespace mrloc;

TEST(Outcome, HeadlineRoundTripsThroughJson) {
    common::Headline h;
    h.reached = false;
    h.status = "not localized: 3 hypotheses left";
    h.figures.push_back({"travel", 12.5, "m", "0.978 of cells (paper 002)", "another map", false});
    h.figures.push_back({"dead reckoning", std::nullopt, "m", "", "", true});
    h.mechanism = "paper 002's elimination replayed with cells (elimination)";
    const auto back = common::headlineFromJson(common::toJson(h), "here");
    EXPECT_FALSE(back.reached);
    EXPECT_EQ(back.status, h.status);
    EXPECT_EQ(back.mechanism, h.mechanism);
    EXPECT_FALSE(common::toJson(common::Headline{}).contains("mechanism"));  // none to name
    ASSERT_EQ(back.figures.size(), 2u);
    EXPECT_DOUBLE_EQ(*back.figures[0].value, 12.5);
    EXPECT_EQ(back.figures[0].paper, "0.978 of cells (paper 002)");
    EXPECT_EQ(back.figures[0].differs, "another map");
    EXPECT_FALSE(back.figures[1].value.has_value());
    EXPECT_TRUE(back.figures[1].baseline);
    EXPECT_THROW(common::headlineFromJson(nlohmann::json::array(), "here"), Error);
}

TEST(Outcome, TheLineKeepsBaselinesApart) {
    common::Headline h;
    h.status = "tracked";
    h.figures.push_back({"RMSE", 0.0271, "m", "", "", false});
    h.figures.push_back({"odometry alone RMSE", 0.76, "m", "", "", true});
    h.mechanism = "mrloc's tracker";  // the report's and metrics.json's, not the line's
    EXPECT_EQ(common::headlineLine("beacons", h),
              "beacons: tracked: RMSE 0.0271 m; baseline: odometry alone RMSE 0.76 m");
}

TEST(Outcome, TrajectoryFiguresAreOnTheTruthsTimelineAndPoolTheBaselineByItsCounts) {
    // the headline's APE, coverage and RPE are metrics.json's truth_timeline (not rmse_m, the
    // errors at the estimates' stamps); two robots' odometry: APE RMSE 1 m over 3 stamps and
    // 2 m over 1, pooled sqrt((3 + 4) / 4)
    const auto metrics = nlohmann::json::parse(R"({"rmse_m": 0.05,
        "truth_timeline": {"share": 0.5, "ape": {"rmse_m": 0.25, "n": 4},
                           "rpe": [{"delta": 1.0, "unit": "m", "translation": {"rmse_m": 0.02}},
                                   {"delta": 1.0, "unit": "s", "translation": {"rmse_m": 0.03}}]},
        "robots": {
        "r1": {"odometry": {"rmse_m": 9.0, "n": 3, "truth_timeline": {"ape": {"rmse_m": 1.0, "n": 3}}}},
        "r2": {"odometry": {"rmse_m": 9.0, "n": 1, "truth_timeline": {"ape": {"rmse_m": 2.0, "n": 1}}}}}})");
    const auto f = common::trajectoryFigures(metrics);
    ASSERT_EQ(f.size(), 4u);
    EXPECT_EQ(f[0].name, "APE RMSE");
    EXPECT_DOUBLE_EQ(*f[0].value, 0.25);
    EXPECT_FALSE(f[0].baseline);
    EXPECT_DOUBLE_EQ(*f[1].value, 50.0);
    EXPECT_EQ(f[1].unit, "%");
    EXPECT_EQ(f[2].name, "RPE over 1 m RMSE");
    EXPECT_DOUBLE_EQ(*f[2].value, 0.02);
    EXPECT_NEAR(*f[3].value, std::sqrt(7.0 / 4.0), 1e-12);
    EXPECT_TRUE(f[3].baseline);
    EXPECT_EQ(f[3].name, "odometry alone APE RMSE");
    // robots standing on test points: an exact odometry is said to be so, not offered as a
    // baseline the method failed to beat
    const auto still = common::trajectoryFigures(nlohmann::json::parse(R"({"robots": {"p1":
        {"odometry": {"truth_timeline": {"ape": {"rmse_m": 0.0, "max_m": 0.0, "n": 801}}}}}})"));
    ASSERT_EQ(still.size(), 4u);
    EXPECT_EQ(still[3].name, "odometry alone APE RMSE (the robots stand still: nothing to drift)");
    EXPECT_DOUBLE_EQ(*still[3].value, 0.0);
    // no truth: every figure none, and no baseline invented
    const auto none = common::trajectoryFigures(nlohmann::json::parse(R"({"rmse_m": null})"));
    ASSERT_EQ(none.size(), 3u);
    for (const auto& fig : none) EXPECT_FALSE(fig.value.has_value()) << fig.name;
}

TEST(Outcome, NearMissFindsOneOrTwoEditsAndNothingFarther) {
    const std::vector<std::string> names = {"beacons", "polymap", "formation"};
    EXPECT_EQ(common::nearMiss("beacon", names).value_or(""), "beacons");
    EXPECT_EQ(common::nearMiss("Polymap", names).value_or(""), "polymap");
    EXPECT_EQ(common::nearMiss("fromation", names).value_or(""), "formation");  // a swap
    EXPECT_FALSE(common::nearMiss("lidar", names).has_value());
    EXPECT_EQ(common::editDistance("duraton", "duration"), 1u);
}

TEST(Outcome, EstimatesEndingEarlyAreAWarningOnlyWhileTheRobotGoesOnMoving) {
    // a 100 s log; three robots whose estimates stop at 40 s
    const auto path = [](double until, double speed) {
        common::Trajectory t;
        for (int i = 0; i <= 100; ++i) {
            const double s = std::min(double(i), until);
            t.push_back({double(i), mrpt::poses::CPose3D(speed * s, 0, 0, 0, 0, 0)});
        }
        return t;
    };
    common::Trajectories estimates, odometry;
    for (const char* r : {"lost", "arrived", "noOdometry"}) estimates[r] = path(40, 0.1);
    for (auto& [r, t] : estimates) t.resize(41);  // the last estimate at 40 s
    odometry["lost"] = path(100, 0.1);            // drives on: 6 m after its last estimate
    odometry["arrived"] = path(40.2, 0.1);        // 2 cm more: standing
    EXPECT_NEAR(common::odometryTravelAfter(odometry["lost"], 40), 6.0, 1e-9);
    EXPECT_NEAR(common::odometryTravelAfter(odometry["arrived"], 40), 0.02, 1e-9);
    const auto w = common::earlyEnds(estimates, odometry, 0, 100);
    ASSERT_EQ(w.size(), 2u);
    EXPECT_EQ(w[0], "robot 'lost': the estimates stop at 40.0 s of the log's 100.0 s");
    EXPECT_EQ(w[1], "robot 'noOdometry': the estimates stop at 40.0 s of the log's 100.0 s");
    // at 90 % of the span, no warning; a snapshot log (1 s or less), none
    for (auto& [r, t] : estimates) t = path(95, 0.1);
    EXPECT_TRUE(common::earlyEnds(estimates, {}, 0, 100).empty());
    EXPECT_TRUE(common::earlyEnds(estimates, {}, 0, 0.5).empty());
}

}  // namespace
