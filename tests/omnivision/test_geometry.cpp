// Seed 000 section 3 against hand layouts: eq. (3), (6), (8), footnote 1's special cases,
// the sine rule, the conventional and proposed methods, and the least-squares refinement.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/omnivision/Refinement.h>
#include <mrloc/omnivision/RelativeLocation.h>
#include <mrloc/omnivision/RestartSearch.h>
#include <mrpt/math/wrap2pi.h>

#include <Eigen/LU>
#include <iostream>

#include "Degrees.h"
#include "Swarm.h"

using namespace mrloc;
using namespace mrloc::omnivision;

namespace {
using mrloc::testing_angles::kDeg;

/** Interior angles at A and B of triangle ABC, and C's side of A->B. */
LineDirections directionsOf(Vec2 a, Vec2 b, Vec2 c) {
    const auto angle = [](Vec2 u, Vec2 v) {
        return std::acos(std::clamp(u.normalized().dot(v.normalized()), -1.0, 1.0));
    };
    const Vec2 ab = b - a, ac = c - a;
    const int side = ab.x() * ac.y() - ab.y() * ac.x() >= 0 ? 1 : -1;
    return lineDirections(angle(b - a, c - a), angle(a - b, c - b), side);
}

SearchOptions exact() {
    SearchOptions o;
    o.sumTolerance = 1e-6;
    o.bearingTolerance = 1e-6;
    return o;
}
}  // namespace

TEST(Geometry, Eq3PlacesCOnAUnitBaseline) {
    // A = (0,0), B = (4,0), C = (1,3): angle BAC = atan(3), ABC = 45 deg.
    const auto d = directionsOf({0, 0}, {4, 0}, {1, 3});
    EXPECT_NEAR(d.ac, std::atan2(3, 1), 1e-12);
    EXPECT_NEAR(d.bc, 135 * kDeg, 1e-12);
    const Vec2 c = unitBaselinePoint(d);
    EXPECT_NEAR(c.x(), 0.25, 1e-12);
    EXPECT_NEAR(c.y(), 0.75, 1e-12);
    // Below the axis, and beyond B.
    EXPECT_NEAR((4 * unitBaselinePoint(directionsOf({0, 0}, {4, 0}, {1, -3})) - Vec2(1, -3)).norm(),
                0, 1e-12);
    EXPECT_NEAR((4 * unitBaselinePoint(directionsOf({0, 0}, {4, 0}, {7, 2})) - Vec2(7, 2)).norm(),
                0, 1e-12);
    // With the interior angle ABC in eq. (2), as the text defines theta_BC, an isosceles
    // triangle has tan(theta_AC) = tan(theta_BC) and eq. (3) divides by zero.
    EXPECT_THROW(unitBaselinePoint({45 * kDeg, 45 * kDeg}), Error);
    EXPECT_NEAR(unitBaselinePoint(directionsOf({0, 0}, {2, 0}, {1, 1})).x(), 0.5, 1e-12);
}

TEST(Geometry, Footnote1SpecialCasesAt90Degrees) {
    // C above A: theta_AC = 90 deg, C = (0, -L tan theta_BC) (the footnote's sin is a typo:
    // -L sin theta_BC would put C at 2.4, not 3).
    const auto above = directionsOf({0, 0}, {4, 0}, {0, 3});
    EXPECT_NEAR(above.ac, 90 * kDeg, 1e-12);
    EXPECT_NEAR((4 * unitBaselinePoint(above) - Vec2(0, 3)).norm(), 0, 1e-12);
    EXPECT_NEAR(4 * unitBaselinePoint(above).y(), -4 * std::tan(above.bc), 1e-12);  // the tan
    // C above B: theta_BC = 90 deg, C = (L, L tan theta_AC).
    const auto overB = directionsOf({0, 0}, {4, 0}, {4, 3});
    EXPECT_NEAR(overB.bc, 90 * kDeg, 1e-12);
    EXPECT_NEAR((4 * unitBaselinePoint(overB) - Vec2(4, 3)).norm(), 0, 1e-12);
    // -90 degrees: below A and below B.
    EXPECT_NEAR((4 * unitBaselinePoint(directionsOf({0, 0}, {4, 0}, {0, -2})) - Vec2(0, -2)).norm(),
                0, 1e-12);
    EXPECT_NEAR((4 * unitBaselinePoint(directionsOf({0, 0}, {4, 0}, {4, -2})) - Vec2(4, -2)).norm(),
                0, 1e-12);
    // Both vertical, or parallel (C on the line AB): no intersection.
    EXPECT_THROW(unitBaselinePoint({90 * kDeg, 90 * kDeg}), Error);
    EXPECT_THROW(unitBaselinePoint({0, M_PI}), Error);
}

TEST(Geometry, Eq8RecoversTheBaselineFromOneRobotsMotion) {
    const Vec2 a(0, 0), b(4, 0), c(1, 3), c2(2, 2.5);
    const double lC = (c2 - c).norm();
    EXPECT_NEAR(baselineFromMotion(directionsOf(a, b, c), directionsOf(a, b, c2), lC), 4, 1e-12);
    // Crossing the line AB between t_b and t_e (the sign of the bearings tells).
    EXPECT_NEAR(baselineFromMotion(directionsOf(a, b, c), directionsOf(a, b, {2, -1}),
                                   (Vec2(2, -1) - c).norm()),
                4, 1e-12);
    // Special case inside eq. (8): C' straight above B.
    EXPECT_NEAR(baselineFromMotion(directionsOf(a, b, c), directionsOf(a, b, {4, 2}),
                                   (Vec2(4, 2) - c).norm()),
                4, 1e-12);
    EXPECT_THROW(baselineFromMotion(directionsOf(a, b, c), directionsOf(a, b, c2), 0), Error);
    EXPECT_THROW(baselineFromMotion(directionsOf(a, b, c), directionsOf(a, b, c), 1.0), Error);
}

TEST(Geometry, SineRule) {
    // 3-4-5 triangle: i = (0,0), j = (4,0), k = (0,3).
    const double ai = 90 * kDeg, aj = std::atan2(3, 4), ak = std::atan2(4, 3);
    const auto [ik, jk] = sineRule(4, ai, aj, ak);
    EXPECT_NEAR(ik, 3, 1e-12);
    EXPECT_NEAR(jk, 5, 1e-12);
    EXPECT_THROW(sineRule(4, M_PI, 0, 0), Error);
}

namespace {
/** Five robots A-E; C and E move between t_b and t_e, A and B stand. */
struct TwoInstants {
    std::vector<mrpt::poses::CPose2D> before{
        {0, 0, 0.3}, {5, 0, 2.0}, {2, 3, -1}, {4, 4, 0.5}, {-1, 3, 1}};
    std::vector<mrpt::poses::CPose2D> after{
        {0, 0, 0.3}, {5, 0, 2.0}, {2.6, 2.2, -1.2}, {4, 4, 0.5}, {-0.5, 3.5, 1}};
    std::vector<double> travelled() const {
        std::vector<double> t;
        for (size_t i = 0; i < before.size(); ++i)
            t.push_back(std::hypot(after[i].x() - before[i].x(), after[i].y() - before[i].y()));
        return t;
    }
    std::vector<double> turned() const {
        std::vector<double> t;
        for (size_t i = 0; i < before.size(); ++i) t.push_back(after[i].phi() - before[i].phi());
        return t;
    }
};

double distance(const mrpt::poses::CPose2D& p, const mrpt::poses::CPose2D& q) {
    return std::hypot(p.x() - q.x(), p.y() - q.y());
}
}  // namespace

TEST(Methods, ConventionalAndProposedGiveEveryDistanceOfAHandLayout) {
    TwoInstants t;
    const auto sb = testing_omni::viewsOf(t.before, 0, 1);
    const auto se = testing_omni::viewsOf(t.after, 0, 2);
    const auto ib = identify(sb.snapshot, exact()), ie = identify(se.snapshot, exact());
    ASSERT_EQ(ie.triangles.size(), 10u);
    // Conventional: |AB| measured.
    const auto conv = conventionalMethod(se.snapshot, ie, 0, 1, 5.0);
    for (const auto& [e, d] : conv.distance)
        EXPECT_NEAR(d, distance(t.after[size_t(e.first)], t.after[size_t(e.second)]), 1e-9);
    EXPECT_EQ(conv.distance.size(), 10u);
    // Proposed: L from the motion of the witness that travelled farthest (C here).
    const auto prop = proposedMethod(sb.snapshot, ib, se.snapshot, ie, 0, 1, t.travelled());
    EXPECT_EQ(prop.moving, 2);
    EXPECT_NEAR(prop.after.baseline, 5, 1e-9);
    for (const auto& [e, d] : prop.after.distance)
        EXPECT_NEAR(d, distance(t.after[size_t(e.first)], t.after[size_t(e.second)]), 1e-9);
    // The layout: A at the origin, B on the x axis (here the world frame already), and
    // each robot's heading from where its images point.
    for (size_t r = 0; r < 5; ++r) {
        ASSERT_TRUE(prop.after.position[r]);
        EXPECT_NEAR(prop.after.position[r]->x(), t.after[r].x(), 1e-9);
        EXPECT_NEAR(prop.after.position[r]->y(), t.after[r].y(), 1e-9);
        ASSERT_TRUE(prop.after.heading[r]);
        EXPECT_NEAR(*prop.after.heading[r], t.after[r].phi(), 1e-9) << r;
        EXPECT_NEAR(*prop.before.heading[r], t.before[r].phi(), 1e-9) << r;
    }
}

TEST(Methods, LocalizedSearchAtTbFindsTheWitnessTriangleOfEq12) {
    TwoInstants t;
    const auto sb = testing_omni::viewsOf(t.before, 0, 1);
    const auto se = testing_omni::viewsOf(t.after, 0, 2);
    const auto ie = identify(se.snapshot, exact());
    const auto local = localizedRestartSearch(sb.snapshot, se.snapshot, ie, 0, 1, t.travelled(),
                                              t.turned(), exact(), false);
    // C travelled farthest (1 m against E's 0.71 m): the first witness tried, and found.
    EXPECT_EQ(local.witness, 2);
    EXPECT_EQ(local.witnessesTried, 1u);
    EXPECT_EQ(local.triangles, 1u);
    // Eq. (12): at most |NM_A^b| |NM_B^b| |NM_C^b| triples, less the stopped pair's images
    // (3 x 3 x 4), and half of A's and B's pairs put C on opposite sides of AB.
    EXPECT_LE(local.triples, 36u);
    EXPECT_GT(local.triples, 0u);
    // The six labels are the truth's, and nothing else is labelled.
    int labelled = 0;
    for (size_t r = 0; r < 5; ++r)
        for (size_t img = 0; img < local.before.labels[r].size(); ++img)
            if (const int who = local.before.labels[r][img]; who >= 0) {
                ++labelled;
                EXPECT_EQ(who, sb.truth[r][img]) << r << " " << img;
            }
    EXPECT_EQ(labelled, 6);
    ASSERT_EQ(local.before.triangles.size(), 1u);
    EXPECT_EQ(local.before.triangles[0].robot, (std::array<int, 3>{0, 1, 2}));
    // The proposed method on it gives the full search's L and t_e layout.
    const auto prop =
        proposedMethod(sb.snapshot, local.before, se.snapshot, ie, 0, 1, t.travelled());
    EXPECT_EQ(prop.moving, 2);
    EXPECT_NEAR(prop.after.baseline, 5, 1e-9);
    // Views of 500 images each (a hostile log) exceed the work bound: one line, no hang.
    auto huge = sb.snapshot;
    for (size_t r : {0u, 1u, 2u}) {
        std::vector<double> raw = huge.views[r].bearings;
        for (int i = 0; i < 500; ++i) raw.push_back(-3 + 0.0119 * i);
        huge.views[r] = makeView(raw, "huge");
    }
    try {
        localizedRestartSearch(huge, se.snapshot, ie, 0, 1, t.travelled(), t.turned(), exact(),
                               false);
        FAIL() << "expected the work bound";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("work bound"), std::string::npos) << e.what();
    }
    // No moving witness: nothing to search, and the caller searches t_b in full.
    const auto none = localizedRestartSearch(sb.snapshot, se.snapshot, ie, 0, 1,
                                             std::vector<double>(5, 0), t.turned(), exact(), false);
    EXPECT_EQ(none.witness, -1);
    EXPECT_EQ(none.witnessesTried, 0u);
    EXPECT_EQ(none.unconfirmed,
              "none of the 0 moving robots that A and B both see at t_e (0 tried) forms a "
              "triangle with them at t_b that the robots it saw confirm and no other robot could "
              "make (0 image triples searched, paper 000 eq. (12))");
}

TEST(Methods, LocalizedSearchPicksTheTrueTriangleAmongChanceSumsInASwarm) {
    // 30 and 60 robots, 0.02 deg noise; between t_b and t_e every robot but A and B drives
    // 0.3 m. Many triples sum to 180 degrees by chance; the robots the witness saw at t_e,
    // each within its odometer distance of where it stood, tell the true one (the paper's
    // setting: no heading), as does the witness's odometer turn (beyond the paper).
    size_t confirmed[2] = {0, 0};  // scenes with a triangle: heading-free, odometer turn
    for (const bool useOdometerTurn : {false, true})
        for (const size_t n : {30u, 60u})
            for (unsigned seed = 1; seed <= 3; ++seed) {
                const auto sg =
                    testing_omni::stopAndGo(n, seed, 0.02, 20 * std::sqrt(n / 30.0), 0.3);
                const auto &before = sg.before, &after = sg.after;
                SearchOptions o;
                o.sumTolerance = 6 * 0.02 * kDeg;
                o.bearingTolerance = 4 * 0.02 * kDeg;
                // t_e identified (the full search's job)
                const auto ie = consistentTriangles(after.snapshot, after.truth, o.sumTolerance);
                const std::string what = std::to_string(n) + " robots, seed " +
                                         std::to_string(seed) +
                                         (useOdometerTurn ? ", odometer turn" : ", no heading");
                const auto local =
                    localizedRestartSearch(before.snapshot, after.snapshot, ie, 0, 1, sg.travelled,
                                           sg.turned, o, useOdometerTurn);
                if (local.witness < 0) {
                    // every witness tried ambiguous: the caller's fall-back is the full search
                    EXPECT_EQ(local.witnessesTried, 10u) << what;
                    EXPECT_NE(local.unconfirmed.find("(10 tried)"), std::string::npos)
                        << what << ": " << local.unconfirmed;
                    EXPECT_TRUE(local.before.labels.empty()) << what;
                    continue;
                }
                ++confirmed[useOdometerTurn];
                EXPECT_GT(local.triangles, 1u) << what;  // chance sums exist
                EXPECT_EQ(local.before.triangles.size(), 1u) << what;
                for (size_t r = 0; r < n; ++r)
                    for (size_t img = 0; img < local.before.labels[r].size(); ++img)
                        if (const int who = local.before.labels[r][img]; who >= 0) {
                            EXPECT_EQ(who, before.truth[r][img]) << what;
                        }
            }
    // Measured: heading-free, a triangle in 2 of the six scenes (in the other four every one
    // of the ten witnesses tried is ambiguous); with the turn in all six.
    EXPECT_GE(confirmed[0], 2u);
    EXPECT_EQ(confirmed[1], 6u);
}

TEST(Methods, ProposedNeedsACommonMovingWitness) {
    TwoInstants t;
    auto moved = t.travelled();
    const auto sb = testing_omni::viewsOf(t.before, 0, 1);
    const auto se = testing_omni::viewsOf(t.after, 0, 2);
    const auto ib = identify(sb.snapshot, exact()), ie = identify(se.snapshot, exact());
    // Nobody moved: l_C = 0 (footnote 1).
    EXPECT_THROW(proposedMethod(sb.snapshot, ib, sb.snapshot, ib, 0, 1, std::vector<double>(5, 0)),
                 Error);
    // A and B share no witness when B sees nobody: the paper restarts with another pair.
    auto blind = se.snapshot;
    blind.views[1].bearings.clear();
    const auto iBlind = identify(blind, exact());
    try {
        proposedMethod(sb.snapshot, ib, blind, iBlind, 0, 1, moved);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("stop another pair"), std::string::npos);
    }
    // Another pair (D, E... here A and D) works.
    const auto other = proposedMethod(sb.snapshot, ib, se.snapshot, ie, 0, 3, moved);
    EXPECT_NEAR(other.after.baseline, distance(t.after[0], t.after[3]), 1e-9);
}

TEST(Refinement, ExactDataIsAFixedPointAndNoiseIsReduced) {
    TwoInstants t;
    RefinementProblem p;
    const auto build = [&](double sigmaDeg, unsigned seed, ProposedSolution& paper) {
        const auto sb = testing_omni::viewsOf(t.before, sigmaDeg, seed);
        const auto se = testing_omni::viewsOf(t.after, sigmaDeg, seed + 1);
        SearchOptions o;
        o.sumTolerance = std::max(1e-6, 6 * sigmaDeg * kDeg);
        o.bearingTolerance = std::max(1e-6, 4 * sigmaDeg * kDeg);
        const auto ib = identify(sb.snapshot, o), ie = identify(se.snapshot, o);
        paper = proposedMethod(sb.snapshot, ib, se.snapshot, ie, 0, 1, t.travelled());
        p = {};
        p.snapshots = {sb.snapshot, se.snapshot};
        p.labels = {ib.labels, ie.labels};
        p.initial = {paper.before.position, paper.after.position};
        p.stationary = {0, 1};
        for (int r : {2, 4}) p.distances.push_back({0, r, 1, r, t.travelled()[size_t(r)], 0.01});
        p.bearingSigma = std::max(1e-6, sigmaDeg) * kDeg;
        p.a = 0, p.b = 1;
    };
    ProposedSolution paper;
    build(0, 1, paper);
    const auto exactFit = refineLayout(p);
    for (size_t r = 0; r < 5; ++r) {
        EXPECT_NEAR(exactFit.position[1][r]->x(), t.after[r].x(), 1e-6);
        EXPECT_NEAR(exactFit.position[1][r]->y(), t.after[r].y(), 1e-6);
        EXPECT_NEAR(*exactFit.heading[1][r], t.after[r].phi(), 1e-7);
    }
    // Noisy angles (0.1 deg) and exact odometry: over 30 trials the refined layout is
    // closer to the truth than the paper's, and its covariance is honest (the mean
    // normalised squared error of a 2-D position is about 2).
    double paperSq = 0, refinedSq = 0, nees = 0, headingNees = 0;
    int n = 0;
    for (unsigned trial = 0; trial < 30; ++trial) {
        build(0.1, 100 + 2 * trial, paper);
        p.distances.clear();
        for (int r : {2, 4}) p.distances.push_back({0, r, 1, r, t.travelled()[size_t(r)], 1e-4});
        const auto fit = refineLayout(p);
        for (size_t r = 2; r < 5; ++r) {
            const Vec2 truth(t.after[r].x(), t.after[r].y());
            paperSq += (*paper.after.position[r] - truth).squaredNorm();
            const Vec2 e = *fit.position[1][r] - truth;
            refinedSq += e.squaredNorm();
            nees += e.dot(fit.covariance[1][r].topLeftCorner<2, 2>().inverse() * e);
            headingNees +=
                std::pow(mrpt::math::wrapToPi(*fit.heading[1][r] - t.after[r].phi()), 2) /
                fit.covariance[1][r](2, 2);
            ++n;
        }
    }
    EXPECT_LT(refinedSq, paperSq);
    EXPECT_GT(nees / n, 1.0);
    EXPECT_LT(nees / n, 3.5);
    // The heading's variance is as honest (1 expected).
    EXPECT_GT(headingNees / n, 0.5);
    EXPECT_LT(headingNees / n, 1.8);
    std::cout << "position NEES " << nees / n << ", heading NEES " << headingNees / n << "\n";
}
