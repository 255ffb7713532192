// Triangle search and identification: seed 000 Fig. 6, the fast search against the
// brute-force oracle, and robustness to chance sums near 180 degrees.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/omnivision/TriangleSearch.h>

#include <tuple>

#include "Degrees.h"
#include "Swarm.h"

using namespace mrloc;
using namespace mrloc::omnivision;

namespace {

using mrloc::testing_angles::kDeg;

struct LabelScore {
    size_t right = 0, wrong = 0, images = 0;
};

LabelScore score(const Labels& got, const Labels& truth) {
    LabelScore s;
    for (size_t r = 0; r < truth.size(); ++r)
        for (size_t i = 0; i < truth[r].size(); ++i) {
            ++s.images;
            if (got[r][i] >= 0) (got[r][i] == truth[r][i] ? s.right : s.wrong)++;
        }
    return s;
}

/** Seed 000 Fig. 6: the angles each robot measured. A, B and C see three images, D four,
 *  E none; a view's bearings are rebuilt from its angles (0, then cumulative sums). */
Snapshot figure6() {
    const auto view = [](std::vector<double> deg) {
        for (auto& d : deg) d *= kDeg;
        return makeView(deg, "fig6");
    };
    Snapshot s;
    s.views = {view({0, 45.7, 72.3}),         // A: 45.7, 72.3, 26.6
               view({0, 49.7, 93.0}),         // B: 49.7, 43.3, 93.0
               view({0, 58.0, 123.8}),        // C: 58.0, 65.8, 123.8
               view({0, 29.6, 70.9, 167.8}),  // D: the six angles of Fig. 6
               view({})};                     // E: sees nothing
    return s;
}

}  // namespace

TEST(TriangleSearch, AnglesOfAViewAreAllPairs) {
    const auto v = makeView({0, 29.6 * kDeg, 70.9 * kDeg, 167.8 * kDeg}, "D");
    const auto a = anglesOf(v);
    ASSERT_EQ(a.size(), 6u);  // n(n-1)/2
    std::vector<double> deg;
    for (const auto& x : a) deg.push_back(std::round(x.angle / kDeg * 10) / 10);
    std::sort(deg.begin(), deg.end());
    EXPECT_EQ(deg, (std::vector<double>{29.6, 41.3, 70.9, 96.9, 138.2, 167.8}));
    EXPECT_NEAR(interiorAngle(makeView({-170 * kDeg, 170 * kDeg}, "wrap"), 0, 1), 20 * kDeg, 1e-12);
}

TEST(TriangleSearch, Figure6FindsTrianglesABCAndABDAndResolvesTheImages) {
    const auto s = figure6();
    const auto candidates = bruteForceTriangles(s, 0.06 * kDeg);
    const auto has = [&](std::array<int, 3> robots, std::array<double, 3> deg) {
        return std::any_of(candidates.begin(), candidates.end(), [&](const Triangle& t) {
            if (t.robot != robots) return false;
            for (size_t v = 0; v < 3; ++v)
                if (std::abs(t.angle[v] / kDeg - deg[v]) > 0.051) return false;
            return true;
        });
    };
    EXPECT_TRUE(has({0, 1, 2}, {72.3, 49.7, 58.0}));  // ABC
    EXPECT_TRUE(has({0, 1, 3}, {45.7, 93.0, 41.3}));  // ABD
    // The other two faces of the tetrahedron ABCD close too: ACD and BCD.
    EXPECT_TRUE(has({0, 2, 3}, {26.6, 123.8, 29.6}));
    EXPECT_TRUE(has({1, 2, 3}, {43.3, 65.8, 70.9}));
    EXPECT_EQ(candidates.size(), 4u);

    SearchOptions o;
    o.sumTolerance = 0.06 * kDeg;
    const auto id = identifyBruteForce(s, o);
    // At A (images at 0, 45.7, 72.3 deg): the image in both 72.3 and 45.7 is B, the one
    // only in 72.3 is C and the one only in 45.7 is D (seed 000 section 2).
    EXPECT_EQ(id.labels[0], (std::vector<int>{1, 3, 2}));
    EXPECT_EQ(id.labels[1], (std::vector<int>{0, 2, 3}));  // B: 49.7 is A-C, 93.0 is A-D
    EXPECT_EQ(id.labels[2], (std::vector<int>{0, 1, 3}));  // C: 58.0 is A-B, 65.8 is B-D
    // D's fourth image (E, seen by D alone) is in no triangle: it stays unidentified.
    EXPECT_EQ(id.labels[3], (std::vector<int>{2, 0, 1, -1}));
    EXPECT_EQ(id.triangles.size(), 4u);
    EXPECT_EQ(id.unresolved, (std::vector<int>{4}));  // E
}

TEST(TriangleSearch, FastFindsEveryLabelOfAMutuallyVisibleSwarm) {
    for (size_t n : {5, 10, 20, 30}) {
        const auto sw = testing_omni::randomSwarm(n, unsigned(n), 0.02);
        SearchOptions o;
        o.sumTolerance = 0.2 * kDeg;
        o.bearingTolerance = 0.1 * kDeg;
        const auto id = identify(sw.snapshot, o);
        const auto sc = score(id.labels, sw.truth);
        EXPECT_EQ(sc.wrong, 0u) << "N = " << n;
        // Images of two robots nearly in line from a camera stay unlabeled (ambiguous).
        EXPECT_GE(double(sc.right), 0.97 * double(sc.images)) << "N = " << n;
        EXPECT_TRUE(id.unresolved.empty()) << "N = " << n;
        // A missing label removes the N - 2 triangles through that pair.
        EXPECT_GE(id.triangles.size(), size_t(0.6 * double(n * (n - 1) * (n - 2) / 6)));
        for (const auto& t : id.triangles) EXPECT_LE(std::abs(t.sum() - M_PI), o.sumTolerance);
    }
}

/** Swarms at the density of 30 robots in a 20 m square (bench_triangles' BM_Identify). */
testing_omni::Swarm denseSwarm(size_t n, unsigned seed, double sigmaDeg, bool occluded) {
    return testing_omni::randomSwarm(n, seed, sigmaDeg, 20 * std::sqrt(double(n) / 30), 1.0,
                                     occluded ? 12 : 0, occluded ? 0.15 : 0.05);
}
SearchOptions tolerancesFor(double sigmaDeg) {
    SearchOptions o;
    o.sumTolerance = 6 * sigmaDeg * kDeg;
    o.bearingTolerance = 4 * sigmaDeg * kDeg;
    return o;
}

TEST(TriangleSearch, FiftyAndSeventyFiveRobotsAreLabelledWithNoWrongLabel) {
    // Before the hull seeds in a row, the mutual group and the significance test, 2 of 5
    // such scenes with 50 robots failed with 275-291 wrong labels. Measured since: every
    // image labelled at N = 50 (seeds 1-3), 99.9-100 % at N = 75; the bound is 97 % (the
    // issue's). N = 75, seed 6 placed robot a where robot b stood (16 wrong labels) until
    // the first group counted its degrees over every candidate.
    for (const auto& [n, seed] :
         std::vector<std::pair<size_t, unsigned>>{{50, 1}, {50, 2}, {50, 3}, {75, 1}, {75, 6}}) {
        const auto sw = denseSwarm(n, seed, 0.02, false);
        const auto id = identify(sw.snapshot, tolerancesFor(0.02));
        const auto sc = score(id.labels, sw.truth);
        EXPECT_EQ(sc.wrong, 0u) << "N = " << n << ", seed " << seed;
        EXPECT_GE(double(sc.right), 0.97 * double(sc.images)) << "N = " << n << ", seed " << seed;
        EXPECT_TRUE(id.unresolved.empty()) << "N = " << n << ", seed " << seed;
    }
}

TEST(TriangleSearch, SeventyFiveAtFiveHundredthsOfADegreeKeepNoWrongLabel) {
    // Two ways to a wrong label at 0.05 deg, one scene each (of the bench's 10, which had 30
    // wrong labels). Scene 6: a robot standing in line between placed pairs had its images
    // taken by their labels, stayed unplaced, and 14 images of it kept another's label,
    // until the finished layout was grown once more (growFreed). Scene 5: a robot placed
    // near its true place kept 4 wrong labels, until a robot that misses the placed robots
    // it should see was taken out (34 % of its checks against a 2.7 % median). Measured
    // since: none wrong, 92.4 % and 86.7 % labelled; bound 85 % (0.05 deg leaves images
    // that two robots share within the tolerance unlabelled). Broken once each: fails.
    for (const unsigned seed : {6u, 5u}) {
        const auto sw = denseSwarm(75, seed, 0.05, false);
        const auto id = identify(sw.snapshot, tolerancesFor(0.05));
        const auto sc = score(id.labels, sw.truth);
        EXPECT_EQ(sc.wrong, 0u) << "seed " << seed;
        EXPECT_GE(double(sc.right), 0.85 * double(sc.images)) << "seed " << seed;
    }
}

TEST(TriangleSearch, ImagesOfRobotsNearlyInLineAreMatchedOnceTheLayoutIsFinal) {
    // 30 robots at 0.1 deg, the bench's scenes 1-5: images that two placed robots' lines
    // share within the tolerance were left unlabelled (86.7-92.2 % labelled). The final
    // layout's predictions are far better than a tolerance, so each such group is matched
    // as a whole where the other matchings cost 9 squared sigmas more (assignNearLines).
    // Measured since: 92.6-95.6 %, none wrong; bound 92 %, under the lowest scene by 5 of
    // its 870 images. Without the matching: scenes 1, 2, 4 and 5 fail. (Over the bench's 10
    // scenes a configuration, wrong labels appear at a margin of 1 squared sigma, none at 4.)
    for (unsigned seed = 1; seed <= 5; ++seed) {
        const auto sw = denseSwarm(30, seed, 0.1, false);
        const auto id = identify(sw.snapshot, tolerancesFor(0.1));
        const auto sc = score(id.labels, sw.truth);
        EXPECT_EQ(sc.wrong, 0u) << "seed " << seed;
        EXPECT_GE(double(sc.right), 0.92 * double(sc.images)) << "seed " << seed;
    }
}

TEST(TriangleSearch, InRangeLimitedSwarmsARobotInLineTakesBackItsImages) {
    // Cameras that see 12 m through 0.15 m bands (the bench's occluded rows). Scene 6 at
    // N = 75, 0.02 deg: robot 7 stood where the sights 26-67 and 43-63 cross, those four
    // images of it kept the far robot's label (4 wrong), and 79.0 % was labelled. Scene 8
    // at N = 100, 0.05 deg: likewise robot 47 on six sights (12 wrong, 90.3 %). Three
    // causes: the growth stopped asking the placed robots in range after a few misses
    // (bands hide most of them), a robot placed in the same round on an image kept it from
    // the nearer robot whose band hides it, and the last growth tried 8 anchor pairs.
    // Measured since: none wrong, 100 % and 99.5 % labelled; bound 97 % (the issue's).
    // Each undone alone: 4 wrong and 80.4 % (scene 6); 12 wrong; 2 wrong and 78.2 %.
    for (const auto& [n, seed, sigma] :
         std::vector<std::tuple<size_t, unsigned, double>>{{75, 6, 0.02}, {100, 8, 0.05}}) {
        const auto sw = denseSwarm(n, seed, sigma, true);
        const auto id = identify(sw.snapshot, tolerancesFor(sigma));
        const auto sc = score(id.labels, sw.truth);
        EXPECT_EQ(sc.wrong, 0u) << "N = " << n << ", seed " << seed;
        EXPECT_GE(double(sc.right), 0.97 * double(sc.images)) << "N = " << n << ", seed " << seed;
    }
}

// Cameras that see 12 m: the hull's robots 10-17 m apart do not see each other, no hull
// triangle is true (all 45 of scene 9 at N = 75 false), and nothing was labelled in N = 75
// scene 9 nor in N = 100 scenes 1, 6 and 7. Two hull robots that are each other's extreme
// image grow from the robots both see; measured since: 100 % labelled, none wrong (N = 75
// scene 9 at seed 79, 0.35 s; N = 100 scene 1 at seed 99, 0.93 s). Bound 97 % (the
// issue's). Without the pair seeds: nothing labelled (fails); with them but a point's rays
// claimed by another point of the same pair (the anchor pairs' rule), nothing either.
void expectPairSeedsLabel(size_t n, unsigned seed) {
    const auto sw = denseSwarm(n, seed, 0.02, true);
    const auto id = identify(sw.snapshot, tolerancesFor(0.02));
    const auto sc = score(id.labels, sw.truth);
    EXPECT_EQ(sc.wrong, 0u) << "N = " << n << ", seed " << seed;
    EXPECT_GE(double(sc.right), 0.97 * double(sc.images)) << "N = " << n << ", seed " << seed;
}
TEST(TriangleSearch, WhereTheHullIsWiderThanTheRangeAPairOfHullRobotsSeedsTheLayout) {
    expectPairSeedsLabel(75, 9);
}
TEST(TriangleSearch, AHundredRobotsWithACameraRangeArePairSeeded) { expectPairSeedsLabel(100, 1); }

TEST(TriangleSearch, AnUnresolvedRobotSaysWhy) {
    // An equilateral triangle 0-1-2 (every interior angle 60 degrees) and robot 3
    const auto view = [](std::vector<double> degrees) {
        for (double& d : degrees) d *= kDeg;
        return makeView(degrees, "test");
    };
    Snapshot s;
    s.views = {view({0, 60}), view({120, 180}), view({-120, -60}), view({45})};
    const Labels labels{{1, 2}, {2, 0}, {0, 1}, {-1}};
    auto id = consistentTriangles(s, labels, 0.5 * kDeg);
    EXPECT_EQ(id.unresolved, std::vector<int>{3});
    EXPECT_EQ(whyUnresolved(s, id, 3), UnresolvedReason::SeesTooFew);
    // two images, neither identified
    s.views[3] = view({45, 90});
    id = consistentTriangles(s, {{1, 2}, {2, 0}, {0, 1}, {-1, -1}}, 0.5 * kDeg);
    EXPECT_EQ(whyUnresolved(s, id, 3), UnresolvedReason::NotPlaced);
    // robot 3 labels 0 and 1, but only 0 labels it back: one robot both ways
    s.views[0] = view({0, 30, 60});
    id = consistentTriangles(s, {{1, 3, 2}, {2, 0}, {0, 1}, {0, 1}}, 0.5 * kDeg);
    EXPECT_EQ(whyUnresolved(s, id, 3), UnresolvedReason::NotPlaced);
    // robot 2's angle 5 degrees off: 0, 1 and 2 are identified both ways, in no triangle
    s.views = {view({0, 60}), view({120, 180}), view({-120, -55})};
    id = consistentTriangles(s, {{1, 2}, {2, 0}, {0, 1}}, 0.5 * kDeg);
    EXPECT_EQ(id.unresolved, (std::vector<int>{0, 1, 2}));
    for (int r = 0; r < 3; ++r) EXPECT_EQ(whyUnresolved(s, id, r), UnresolvedReason::NoTriangle);
    EXPECT_STREQ(textOf(UnresolvedReason::NoTriangle).words,
                 "identified, but in no triangle summing to 180 degrees within the tolerance");
}

TEST(TriangleSearch, AChanceLayoutOfAFewRobotsIsNotKept) {
    // 30 robots at 0.3 deg (three times the worst noise): a tolerance window then
    // holds a chance bearing 1 time in 5, no true layout grows, and the search kept the
    // best of its 200 chance layouts, 7 robots with 36 wrong labels. A layout no other
    // seed grew again must place a quarter of the robots: measured since, nothing labelled.
    const auto sw = denseSwarm(30, 1, 0.3, false);
    const auto id = identify(sw.snapshot, tolerancesFor(0.3));
    const auto sc = score(id.labels, sw.truth);
    EXPECT_EQ(sc.wrong, 0u);
    EXPECT_EQ(id.unresolved.size(), 30u);
}

TEST(TriangleSearch, AHundredRobotsAreLabelledWithNoWrongLabel) {
    // Seeds 3 and 9 of the bench. Before the group's degree over every candidate, the flat
    // seeds last and the one-sided sight, scene 3 took 9 seeds (2 s) and scene 9 had 26
    // wrong labels (still 26 with the one-sided sight check off, measured); since: 99.9 %
    // and 99.6 % labelled, none wrong (5 and 1 seeds).
    // The seeds tried count the work (deterministic): flat seeds first, scene 3 needed 9.
    for (const auto& [seed, seeds] : std::vector<std::pair<unsigned, size_t>>{{3, 5}, {9, 1}}) {
        const auto sw = denseSwarm(100, seed, 0.02, false);
        const auto id = identify(sw.snapshot, tolerancesFor(0.02));
        const auto sc = score(id.labels, sw.truth);
        EXPECT_LE(id.candidates, seeds) << "seed " << seed;
        EXPECT_EQ(sc.wrong, 0u) << "seed " << seed;
        EXPECT_GE(double(sc.right), 0.97 * double(sc.images)) << "seed " << seed;
        EXPECT_TRUE(id.unresolved.empty()) << "seed " << seed;
    }
}

TEST(TriangleSearch, NoisierOrOccludedBearingsLeaveImagesUnlabelledNeverWrong) {
    // 0.05 and 0.1 deg of noise (the tolerances 4 and 6 sigma), and swarms whose cameras see
    // 12 m through markers of the band's 0.15 m: fewer labels, none wrong. Over these nine
    // scenes 96.5 % of the images are labelled; the bound is 95 %. Breaking the significance
    // test (every candidate taken) gives wrong labels here and in the test above.
    size_t images = 0, right = 0;
    for (unsigned seed = 1; seed <= 3; ++seed) {
        for (const auto& [n, sigma, occluded] : std::vector<std::tuple<size_t, double, bool>>{
                 {30, 0.05, false}, {20, 0.1, false}, {20, 0.02, true}}) {
            const auto sw = denseSwarm(n, seed, sigma, occluded);
            const auto id = identify(sw.snapshot, tolerancesFor(sigma));
            const auto sc = score(id.labels, sw.truth);
            EXPECT_EQ(sc.wrong, 0u) << "N = " << n << ", " << sigma << " deg, seed " << seed;
            images += sc.images, right += sc.right;
        }
    }
    EXPECT_GE(double(right), 0.95 * double(images));  // measured 96.5 %
}

TEST(TriangleSearch, FastAgreesWithTheBruteForceOracle) {
    for (unsigned seed = 1; seed <= 6; ++seed) {
        const size_t n = 5 + seed % 4;  // 5..8 robots
        // Noise-free: the paper's search then has no chance sums and is exact.
        const auto sw = testing_omni::randomSwarm(n, seed * 31, 0.0, 10, 1.0);
        SearchOptions o;
        o.sumTolerance = 1e-6;
        o.bearingTolerance = 1e-6;
        const auto fast = identify(sw.snapshot, o);
        const auto brute = identifyBruteForce(sw.snapshot, o);
        EXPECT_EQ(score(brute.labels, sw.truth).wrong, 0u) << "seed " << seed;
        size_t visibleTriples = 0;  // markers may hide one another
        const auto sees = [&](size_t a, size_t b) {
            return std::count(sw.truth[a].begin(), sw.truth[a].end(), int(b)) > 0;
        };
        for (size_t i = 0; i < n; ++i)
            for (size_t j = i + 1; j < n; ++j)
                for (size_t k = j + 1; k < n; ++k)
                    visibleTriples += sees(i, j) && sees(j, i) && sees(i, k) && sees(k, i) &&
                                      sees(j, k) && sees(k, j);
        EXPECT_EQ(brute.triangles.size(), visibleTriples) << "seed " << seed;
        ASSERT_EQ(fast.triangles.size(), brute.triangles.size()) << "seed " << seed;
        for (size_t t = 0; t < fast.triangles.size(); ++t)
            EXPECT_EQ(fast.triangles[t].robot, brute.triangles[t].robot);
        EXPECT_EQ(fast.unresolved, brute.unresolved);
        // Labels agree wherever the oracle decided.
        for (size_t r = 0; r < n; ++r)
            for (size_t i = 0; i < sw.truth[r].size(); ++i)
                if (brute.labels[r][i] >= 0) {
                    EXPECT_EQ(fast.labels[r][i], brute.labels[r][i]);
                }
    }
}

TEST(TriangleSearch, ChanceSumsDoNotSurviveConsistency) {
    // N = 10 with a loose tolerance: the paper's search finds far more angle triples than
    // the 120 true triangles (and its votes go astray); the fast search keeps only
    // triangles consistent with one layout.
    const auto sw = testing_omni::randomSwarm(10, 77, 0.05);
    SearchOptions o;
    o.sumTolerance = 0.5 * kDeg;
    o.bearingTolerance = 0.2 * kDeg;
    const auto raw = bruteForceTriangles(sw.snapshot, o.sumTolerance);
    EXPECT_GT(raw.size(), 500u);
    const auto fast = identify(sw.snapshot, o);
    EXPECT_EQ(score(fast.labels, sw.truth).wrong, 0u);
    EXPECT_LE(fast.triangles.size(), 120u);
    EXPECT_GE(fast.triangles.size(), 100u);
    // Every reported triangle is a true one.
    for (const auto& t : fast.triangles)
        for (size_t v = 0; v < 3; ++v)
            for (int img : t.images[v]) {
                const int who = sw.truth[size_t(t.robot[v])][size_t(img)];
                EXPECT_NE(std::find(t.robot.begin(), t.robot.end(), who), t.robot.end());
            }
}

TEST(TriangleSearch, PartialVisibilityLeavesRobotsUnresolved) {
    // A robot seen by one camera only is in no triangle: reported, not guessed.
    std::vector<mrpt::poses::CPose2D> poses = {
        {0, 0, 0.3}, {6, 0, -1}, {3, 5, 2}, {2, 2, 0.1}, {40, 40, 0}};
    auto sw = testing_omni::viewsOf(poses, 0.0, 3, /*maxRange=*/20);
    // Robot 4 stands beyond every camera's 20 m range: nobody sees it.
    SearchOptions o;
    o.sumTolerance = 0.05 * kDeg;
    o.bearingTolerance = 0.05 * kDeg;
    const auto id = identify(sw.snapshot, o);
    EXPECT_EQ(id.unresolved, (std::vector<int>{4}));
    EXPECT_EQ(score(id.labels, sw.truth).wrong, 0u);
    EXPECT_EQ(id.triangles.size(), 4u);  // the four robots 0..3 are mutually visible
}

TEST(TriangleSearch, ARobotHiddenBehindAnotherStillResolves) {
    // E stands on the segment A-C: A and C cannot see each other, and A's one image in that
    // direction is E (the nearer marker hides C). 7 of the 10 triangles exist.
    const std::vector<mrpt::poses::CPose2D> poses = {{3.788833, 2.894445, 0.3},
                                                     {8.258044, 4.356843, 1},
                                                     {9.693319, 8.936357, 2},
                                                     {2.992309, 9.932515, -1},
                                                     {8.853607, 8.084934, 0.5}};
    for (double sigma : {0.0, 0.05}) {
        const auto sw = testing_omni::viewsOf(poses, sigma, 14);
        SearchOptions o;
        o.sumTolerance = std::max(1e-6, 6 * sigma * kDeg);
        o.bearingTolerance = std::max(1e-6, 4 * sigma * kDeg);
        const auto id = identify(sw.snapshot, o);
        EXPECT_EQ(id.triangles.size(), 7u) << sigma;
        EXPECT_TRUE(id.unresolved.empty());
        EXPECT_EQ(score(id.labels, sw.truth).wrong, 0u);
    }
}

TEST(TriangleSearch, TheSearchIsBoundedAndTooLooseATolerancesIsOneLine) {
    // A swarm of 30 at 0.02 deg: the identification examines a few million angle pairs
    // (measured: 4.06 million here, 573,000 for omnivision_swarm.ini's first snapshot); with
    // 2-degree tolerances every pair is a candidate and the search once ran for hours. The
    // meter stops it at maxPairVisits with one line naming the keys.
    const auto sw = testing_omni::randomSwarm(30, 30u, 0.02);
    SearchOptions o;
    const auto id = identify(sw.snapshot, o);
    EXPECT_GT(id.pairVisits, 0u);
    EXPECT_LT(id.pairVisits, o.maxPairVisits(30) / 10);  // the budget is 13 times this
    o.sumTolerance = o.bearingTolerance = 2 * kDeg;
    // what the tight search needed: the loose one needs more
    o.maxPairVisitsPerRobotCubed = double(id.pairVisits) / (30.0 * 30 * 30);
    try {
        identify(sw.snapshot, o);
        ADD_FAILURE() << "the loose search finished within the tight one's pairs";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("[omnivision] sum_tolerance, bearing_tolerance"), std::string::npos)
            << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
}
