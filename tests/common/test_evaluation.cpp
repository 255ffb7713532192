// common::evaluate against closed forms: errors on the truth's timeline, coverage, gaps,
// alignment and evo's RPE (doc/evaluation.md).
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/Evaluation.h>
#include <mrpt/core/bits_math.h>

#include <cmath>

using namespace mrloc::common;

namespace {

StampedPose at(double t, double x, double y, double headingRad = 0) {
    return {t, mrpt::poses::CPose3D(x, y, 0, headingRad, 0, 0)};
}

/** A straight drive along x at 1 m/s, a stamp every `dt` s from t0 to t1. */
Trajectory straight(double t0, double t1, double dt) {
    Trajectory out;
    for (int k = 0; t0 + k * dt <= t1 + 1e-9; ++k) out.push_back(at(t0 + k * dt, t0 + k * dt, 0));
    return out;
}

}  // namespace

TEST(Evaluation, AConstantOffsetIsItsLengthAtEveryStampAndNoDrift) {
    const auto truth = straight(0, 10, 0.5);
    Trajectory estimate;
    for (const auto& p : truth) estimate.push_back(at(p.t, p.pose.x() + 0.3, p.pose.y() - 0.4));
    const auto e = evaluate(estimate, truth);
    EXPECT_EQ(e.coverage.truthStamps, 21u);
    EXPECT_EQ(e.coverage.covered, 21u);
    EXPECT_DOUBLE_EQ(e.coverage.share(), 1.0);
    EXPECT_DOUBLE_EQ(e.coverage.longestGap, 0.0);
    EXPECT_NEAR(e.translation.rmse, 0.5, 1e-12);
    EXPECT_NEAR(e.translation.max, 0.5, 1e-12);
    EXPECT_NEAR(e.heading.max, 0.0, 1e-12);
    // pairs 1 m of travel apart (two stamps), none over the end: 10
    EXPECT_EQ(e.rpeDistance.translation.n, 10u);
    EXPECT_NEAR(e.rpeDistance.translation.max, 0.0, 1e-12);
}

TEST(Evaluation, AConstantHeadingErrorIsItsAngleAndTurnsEachMetreByTwoSinHalfIt) {
    const auto truth = straight(0, 10, 0.5);
    Trajectory estimate;
    for (const auto& p : truth) estimate.push_back(at(p.t, p.pose.x(), p.pose.y(), 0.1));
    const auto e = evaluate(estimate, truth);
    EXPECT_NEAR(e.heading.rmse, 0.1, 1e-12);
    EXPECT_NEAR(e.translation.max, 0.0, 1e-12);
    // the estimate's 1 m step, seen in its own frame, is turned by -0.1 rad: |E| = 2 sin(0.05)
    EXPECT_NEAR(e.rpeDistance.translation.rmse, 2 * std::sin(0.05), 1e-12);
    EXPECT_NEAR(e.rpeDistance.heading.max, 0.0, 1e-12);
    // over 1 s (two stamps of 0.5 s), the same pairs
    EXPECT_EQ(e.rpeTime.translation.n, 10u);
    EXPECT_NEAR(e.rpeTime.translation.rmse, 2 * std::sin(0.05), 1e-12);
}

TEST(Evaluation, AGapLeavesTheTruthStampsInsideItNotCovered) {
    const auto truth = straight(0, 10, 0.1);  // 101 stamps
    Trajectory estimate;
    for (const auto& p : straight(0, 10, 0.1))
        if (p.t < 4 - 1e-9 || p.t > 6 + 1e-9) estimate.push_back(at(p.t, p.pose.x() + 0.1, 0));
    // estimates every 0.1 s: the limit is max(1 s, 5 x 0.1 s) = 1 s; the 2 s gap is over it
    const auto e = evaluate(estimate, truth);
    EXPECT_DOUBLE_EQ(e.coverage.maxGap, 1.0);
    EXPECT_EQ(e.coverage.covered, 101u - 21u);  // 4.0 .. 6.0 has no estimate
    EXPECT_NEAR(e.coverage.longestGap, 6.1 - 3.9, 1e-9);
    EXPECT_NEAR(e.translation.max, 0.1, 1e-9);
    // a gap of 2 s under a limit of 3 s is bridged: every stamp covered, interpolated
    EvaluationOptions wide;
    wide.maxGap = 3;
    const auto bridged = evaluate(estimate, truth, wide);
    EXPECT_EQ(bridged.coverage.covered, 101u);
    EXPECT_NEAR(bridged.translation.max, 0.1, 1e-9);
}

TEST(Evaluation, AnEstimateThatStartsLateCoversOnlyWhatFollowsItsStart) {
    const auto truth = straight(0, 10, 0.1);
    Trajectory estimate;
    for (const auto& p : straight(3, 10, 0.1)) estimate.push_back(at(p.t, p.pose.x(), 0.2));
    const auto e = evaluate(estimate, truth);
    EXPECT_EQ(e.coverage.covered, 71u);
    EXPECT_NEAR(e.coverage.share(), 71.0 / 101.0, 1e-12);
    EXPECT_NEAR(e.coverage.start, 3.0, 1e-9);
    EXPECT_NEAR(e.coverage.end, 10.0, 1e-9);
    EXPECT_NEAR(e.coverage.longestGap, 3.0, 1e-9);
    EXPECT_NEAR(e.translation.rmse, 0.2, 1e-12);
    // nothing covered: every count 0, the gap the whole truth
    const auto none = evaluate(Trajectory{at(20, 0, 0), at(21, 0, 0)}, truth);
    EXPECT_EQ(none.coverage.covered, 0u);
    EXPECT_EQ(none.translation.n, 0u);
    EXPECT_NEAR(none.coverage.longestGap, 10.0, 1e-9);
}

TEST(Evaluation, ARigidMotionVanishesUnderSE2AndOriginAlignment) {
    Trajectory truth;
    for (int k = 0; k <= 40; ++k) {
        const double t = 0.25 * k;
        truth.push_back(at(t, 3 * std::cos(0.3 * t), 2 * std::sin(0.3 * t), 0.3 * t));
    }
    const mrpt::poses::CPose2D moved(1.0, 2.0, mrpt::DEG2RAD(30.0));
    Trajectory estimate;
    for (const auto& p : truth) {
        const auto q = moved + mrpt::poses::CPose2D(p.pose.x(), p.pose.y(), p.pose.yaw());
        estimate.push_back(at(p.t, q.x(), q.y(), q.phi()));
    }
    EXPECT_GT(evaluate(estimate, truth).translation.max, 1.0);
    for (const auto align : {Alignment::SE2, Alignment::Origin}) {
        EvaluationOptions o;
        o.align = align;
        const auto e = evaluate(estimate, truth, o);
        EXPECT_LT(e.translation.max, 1e-9) << alignmentName(align);
        EXPECT_LT(e.heading.max, 1e-9) << alignmentName(align);
        // the alignment undoes the motion
        const auto back = e.alignment + moved;
        EXPECT_NEAR(back.x(), 0, 1e-9);
        EXPECT_NEAR(back.y(), 0, 1e-9);
        EXPECT_NEAR(back.phi(), 0, 1e-9);
    }
    EvaluationOptions se2;
    se2.align = Alignment::SE2;
    EXPECT_THROW(evaluate(Trajectory{at(0, 0, 0)}, Trajectory{at(0, 1, 1)}, se2), mrloc::Error);
}

// evo's definitions by hand (evo_ape: |trans(Q_i^-1 P_i)|; evo_rpe with delta 1 m:
// |trans((Q_i^-1 Q_j)^-1 (P_i^-1 P_j))|) on three poses
TEST(Evaluation, AgreesWithEvosDefinitionsOnAHandMadePair) {
    const Trajectory truth{at(0, 0, 0), at(1, 1, 0), at(2, 2, 0)};
    const Trajectory estimate{at(0, 0, 0), at(1, 1, 0.1), at(2, 2, 0.3)};
    const auto e = evaluate(estimate, truth);
    EXPECT_NEAR(e.translation.rmse, std::sqrt((0.01 + 0.09) / 3), 1e-12);
    EXPECT_NEAR(e.translation.mean, 0.4 / 3, 1e-12);
    EXPECT_NEAR(e.translation.median, 0.1, 1e-12);
    EXPECT_NEAR(e.translation.max, 0.3, 1e-12);
    EXPECT_EQ(e.rpeDistance.translation.n, 2u);
    EXPECT_NEAR(e.rpeDistance.translation.rmse, std::sqrt((0.01 + 0.04) / 2), 1e-12);
    EXPECT_NEAR(e.rpeDistance.translation.max, 0.2, 1e-12);
}

TEST(Evaluation, HeadingsInterpolateAlongTheShorterArc) {
    // estimates at 170 and -170 degrees: half way, 180 degrees, not 0
    const Trajectory estimate{at(0, 0, 0, mrpt::DEG2RAD(170.0)),
                              at(1, 1, 0, mrpt::DEG2RAD(-170.0))};
    const Trajectory truth{at(0.5, 0.5, 0, M_PI)};
    const auto e = evaluate(estimate, truth);
    ASSERT_EQ(e.coverage.covered, 1u);
    EXPECT_NEAR(e.heading.max, 0.0, 1e-9);
    EXPECT_NEAR(e.translation.max, 0.0, 1e-12);
    const auto j = toJson(e);
    EXPECT_EQ(j["alignment"], "none");
    EXPECT_EQ(j["coverage"]["covered"], 1);
    EXPECT_NEAR(j["ape_heading"]["max_deg"].get<double>(), 0.0, 1e-6);
    EXPECT_EQ(j["rpe"].size(), 2u);
    EXPECT_TRUE(j["rpe"][0]["translation"]["rmse_m"].is_null());  // no pair: null, never 0
}

TEST(Evaluation, TheUncoveredStretchesAreTheGapTheLateStartAndTheEarlyEnd) {
    // the pictures shade these: from the covered stamp before to the covered stamp after
    const auto truth = straight(0, 10, 0.1);
    Trajectory estimate;
    for (const auto& p : truth)
        if (p.t > 1 + 1e-9 && p.t < 9 - 1e-9 && (p.t < 4 - 1e-9 || p.t > 6 + 1e-9))
            estimate.push_back(at(p.t, p.pose.x(), 0));
    const auto e = evaluate(estimate, truth);
    ASSERT_EQ(e.coverage.uncovered.size(), 3u);
    EXPECT_NEAR(e.coverage.uncovered[0].first, 0.0, 1e-9);  // the truth's start
    EXPECT_NEAR(e.coverage.uncovered[0].second, 1.1, 1e-9);
    EXPECT_NEAR(e.coverage.uncovered[1].first, 3.9, 1e-9);
    EXPECT_NEAR(e.coverage.uncovered[1].second, 6.1, 1e-9);
    EXPECT_NEAR(e.coverage.uncovered[2].first, 8.9, 1e-9);
    EXPECT_NEAR(e.coverage.uncovered[2].second, 10.0, 1e-9);  // the truth's end
    EXPECT_NEAR(e.coverage.longestGap, 2.2, 1e-9);
    // every covered stamp carries the poses the pictures draw
    ASSERT_FALSE(e.errors.empty());
    EXPECT_NEAR(e.errors.front().truth.x(), 1.1, 1e-9);
    EXPECT_NEAR(e.errors.front().estimate.x(), 1.1, 1e-9);
    // nothing covered: the whole truth is one stretch
    const auto none = evaluate({at(100, 0, 0), at(101, 1, 0)}, truth);
    ASSERT_EQ(none.coverage.uncovered.size(), 1u);
    EXPECT_NEAR(none.coverage.uncovered[0].second - none.coverage.uncovered[0].first, 10, 1e-9);
}

TEST(Evaluation, PooledRpeIsOverEveryRobotsPairs) {
    // robot a drifts 2 sin(0.05) per metre (a 0.1 rad heading error), robot b not at all:
    // 10 pairs each, so the pooled RMSE is sqrt(10 (2 sin 0.05)^2 / 20)
    const auto truth = straight(0, 10, 0.5);
    Trajectory turned;
    for (const auto& p : truth) turned.push_back(at(p.t, p.pose.x(), p.pose.y(), 0.1));
    const auto j = pooledJson({evaluate(turned, truth), evaluate(truth, truth)});
    ASSERT_TRUE(j.contains("rpe"));
    ASSERT_EQ(j["rpe"].size(), 2u);
    EXPECT_EQ(j["rpe"][0]["unit"], "m");
    EXPECT_EQ(j["rpe"][0]["translation"]["n"], 20u);
    EXPECT_NEAR(j["rpe"][0]["translation"]["rmse_m"].get<double>(),
                std::sqrt(0.5) * 2 * std::sin(0.05), 1e-12);
    EXPECT_EQ(j["rpe"][1]["unit"], "s");
    EXPECT_EQ(j["truth_stamps"], 42u);
}
