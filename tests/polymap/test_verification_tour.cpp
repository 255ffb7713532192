// The travel bounds of elimination: the first-separation distance and the verification tour
// (Dudek, Romanik and Whitesides 1998), against a closed form and an exhaustive search.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/polymap/Elimination.h>
#include <mrloc/polymap/MapGenerators.h>
#include <mrloc/polymap/ShortestPath.h>
#include <mrloc/polymap/VerificationTour.h>

#include <cmath>

using namespace mrloc;
using common::TPoint2D;
using polymap::ProbeStrategy;

namespace {

/** A corridor 30 m x 1 m with two identical rooms 2 m x 6 m hanging below it (x 5-7 and
 *  20-22): from (6, -5) and (21, -5) the views are the same (the room and the corridor's
 *  ceiling above its opening). */
common::Polygon twoRooms() {
    return common::Polygon::fromVertices({{0, 0},
                                          {5, 0},
                                          {5, -6},
                                          {7, -6},
                                          {7, 0},
                                          {20, 0},
                                          {20, -6},
                                          {22, -6},
                                          {22, 0},
                                          {30, 0},
                                          {30, 1},
                                          {0, 1}},
                                         "two rooms");
}

}  // namespace

TEST(TravelBounds, TwoRoomsClosedForm) {
    // From (x, y) in room 1 the corridor's left end (0, 1) shows past the corner (5, 0) once
    // x - 5 >= 5 (-y): the critical chord. The nearest such point from (6, -5) with the
    // 0.1 m clearance from the room's right wall (x <= 6.9) is (6.9, -0.38). The twin's
    // right end (30, 1) shows past (22, 0) only from x - 6 <= 1 - 8 (-y), farther (4.84 m).
    const auto P = twoRooms();
    const std::vector<TPoint2D> H{{6, -5}, {21, -5}};
    polymap::EliminationOptions o;
    o.strategy = ProbeStrategy::VisibilityCells;
    const polymap::Eliminator eliminator(P, H, o);
    ASSERT_TRUE(polymap::Eliminator::sameView(eliminator.viewOf(0, {0, 0}),
                                              eliminator.viewOf(1, {0, 0}), 1e-9));
    const double exact = std::hypot(0.9, 4.62);  // 4.7068 m
    const auto bound = eliminator.firstSeparation({0, 1}, {0, 0});
    ASSERT_TRUE(bound);
    // From above, within the chord sampling (0.05 m) plus the clearance the candidates keep
    // from the chord (0.1 m).
    EXPECT_GE(*bound, exact - 1e-9);
    EXPECT_LE(*bound, exact + 0.15);
    std::cout << "first separation " << *bound << " m (exact " << exact << " m)\n";
    // k = 2: one separating point rules the twin out, so the tour is as long, whichever is
    // the truth, over the cells candidates sampled as finely.
    const auto [sites, oi] = eliminator.candidatesAndRegion({0, 1});
    for (size_t truth : {0u, 1u}) {
        const auto tour = polymap::verificationTour(eliminator, truth, sites);
        ASSERT_TRUE(tour);
        ASSERT_EQ(tour->probes.size(), 1u);
        EXPECT_GE(tour->length, exact - 1e-9) << truth;
        EXPECT_LE(tour->length, exact + 0.15) << truth;
        std::cout << "tour from " << truth << ": " << tour->length << " m\n";
        const auto out = eliminator.ruledOut(truth, tour->probes[0]);
        ASSERT_TRUE(out);
        EXPECT_EQ(*out, std::vector<size_t>{1 - truth});
    }
    // Sites that rule nothing out (the start itself) give no tour.
    EXPECT_FALSE(polymap::verificationTour(eliminator, 0, {{0, 0}, {0, -0.5}}));
}

namespace {

/** The shortest tour by brute force: every sequence of up to k - 1 <= 3 distinct sites (each
 *  site of a shortest tour rules out something new, so that is enough). */
double exhaustiveTour(const polymap::Eliminator& e, size_t truth,
                      const std::vector<TPoint2D>& sites) {
    const polymap::ShortestPaths paths(e.triangulation());
    const TPoint2D start = e.hypotheses()[truth];
    std::vector<TPoint2D> at;
    std::vector<unsigned> rules;
    for (const auto& p : sites)
        if (const auto out = e.ruledOut(truth, p); out && !out->empty()) {
            unsigned m = 0;
            for (size_t i : *out) m |= 1u << i;
            at.push_back(p);
            rules.push_back(m);
        }
    const size_t k = e.hypotheses().size();
    EXPECT_LE(k, 4u);
    const unsigned goal = ((1u << k) - 1) & ~(1u << truth);
    const size_t m = at.size();
    std::vector<std::vector<double>> d(m, std::vector<double>(m));
    std::vector<double> d0(m);
    for (size_t a = 0; a < m; ++a) {
        d0[a] = paths.distance(start, start + at[a]);
        for (size_t b = 0; b < m; ++b) d[a][b] = paths.distance(start + at[a], start + at[b]);
    }
    double best = INFINITY;
    for (size_t a = 0; a < m; ++a) {
        if ((rules[a] & goal) == goal) best = std::min(best, d0[a]);
        for (size_t b = 0; b < m; ++b) {
            if (b == a) continue;
            if (((rules[a] | rules[b]) & goal) == goal) best = std::min(best, d0[a] + d[a][b]);
            for (size_t c = 0; c < m && k > 3; ++c)
                if (c != a && c != b && ((rules[a] | rules[b] | rules[c]) & goal) == goal)
                    best = std::min(best, d0[a] + d[a][b] + d[b][c]);
        }
    }
    return best;
}

}  // namespace

TEST(TravelBounds, TourIsTheExhaustiveOptimumAndBelowEveryStrategy) {
    polymap::StepsMapOptions s;
    s.steps = 2;  // n = 52, k = 4
    const auto map = polymap::stepsMap(s);
    ASSERT_EQ(map.sites.size(), 4u);
    polymap::EliminationOptions o;
    o.strategy = ProbeStrategy::VisibilityCells;
    const polymap::Eliminator cells(map.polygon, map.sites, o);
    const std::vector<size_t> all{0, 1, 2, 3};
    const auto candidates = cells.candidatesAndRegion(all).first;
    std::vector<TPoint2D> sites;  // every 4th cells candidate: a brute force of ~10^6 tours
    for (size_t c = 0; c < candidates.size(); c += 4) sites.push_back(candidates[c]);
    const auto bound = cells.firstSeparation(all, {0, 0});
    ASSERT_TRUE(bound);
    for (size_t truth = 0; truth < 4; ++truth) {
        // Every strategy's own probes among the sites: the tour is at most its path.
        std::vector<TPoint2D> withProbes = sites;
        std::vector<double> travels;
        for (const auto strategy : {ProbeStrategy::VisibilityCells, ProbeStrategy::Randomized,
                                    ProbeStrategy::Triangulation, ProbeStrategy::Windows}) {
            o.strategy = strategy;
            const auto run =
                polymap::eliminateExactly(polymap::Eliminator(map.polygon, map.sites, o), truth);
            ASSERT_EQ(run.survivors, std::vector<size_t>{truth});
            for (const auto& p : run.probes) withProbes.push_back(p.at);
            travels.push_back(run.travel);
        }
        const auto tour = polymap::verificationTour(cells, truth, withProbes);
        ASSERT_TRUE(tour);
        for (double t : travels) EXPECT_LE(tour->length, t + 1e-9) << "start " << truth;
        // Never below the first-separation distance (less the clearance and the sampling it
        // is found within).
        EXPECT_GE(tour->length, *bound - 0.15) << "start " << truth;
        EXPECT_NEAR(tour->length, exhaustiveTour(cells, truth, withProbes), 1e-9)
            << "start " << truth;

        std::cout << "start " << truth << ": tour " << tour->length << " m over " << tour->sites
                  << " sites, " << tour->probes.size() << " probe(s); first separation " << *bound
                  << " m; strategies " << travels[0] << " " << travels[1] << " " << travels[2]
                  << " " << travels[3] << " m\n";
    }
}

TEST(TravelBounds, ThreeRoomsTheMiddleOneNeedsTwoProbes) {
    // Three identical rooms 2 m x 7 m below a corridor; the corridor ends 0.2 m past the
    // first room's left wall and the last room's right wall. From a room at (x, -t) (x from
    // its left wall) the left end shows past the left corner once x >= 0.2 t, the right end
    // once x <= 2 - 0.2 t; the start x = 1, t = 6 sees neither. With the middle room the
    // truth, the first room is ruled out on one side and the last on the other: two short
    // legs (about 0.2 m, 0.38 m and the clearance) beat the one point that sees both ends
    // (t <= 5, 1 m up).
    const auto P = common::Polygon::fromVertices({{0, 0},
                                                  {0.2, 0},
                                                  {0.2, -7},
                                                  {2.2, -7},
                                                  {2.2, 0},
                                                  {10, 0},
                                                  {10, -7},
                                                  {12, -7},
                                                  {12, 0},
                                                  {20, 0},
                                                  {20, -7},
                                                  {22, -7},
                                                  {22, 0},
                                                  {22.2, 0},
                                                  {22.2, 1},
                                                  {0, 1}},
                                                 "three rooms");
    const std::vector<TPoint2D> H{{1.2, -6}, {11, -6}, {21, -6}};
    polymap::EliminationOptions o;
    o.strategy = ProbeStrategy::VisibilityCells;
    const polymap::Eliminator cells(P, H, o);
    for (size_t i : {1u, 2u})
        ASSERT_TRUE(
            polymap::Eliminator::sameView(cells.viewOf(0, {0, 0}), cells.viewOf(i, {0, 0}), 1e-9));
    const auto sites = cells.candidatesAndRegion({0, 1, 2}).first;
    for (size_t truth = 0; truth < 3; ++truth) {
        const auto tour = polymap::verificationTour(cells, truth, sites);
        ASSERT_TRUE(tour) << truth;
        EXPECT_NEAR(tour->length, exhaustiveTour(cells, truth, sites), 1e-9) << truth;
        std::cout << "start " << truth << ": " << tour->length << " m, " << tour->probes.size()
                  << " probe(s), " << tour->expanded << " states expanded of " << tour->sites
                  << " sites\n";
        if (truth == 1) {
            EXPECT_EQ(tour->probes.size(), 2u);
            EXPECT_LT(tour->length, 1.0);  // the one point seeing both ends is 1 m away
        }
    }
}

TEST(TravelBounds, TooManyHypothesesForTheExactSearchIsAClearError) {
    mrpt::random::CRandomGenerator rng(5);
    polymap::RoomsMapOptions o;
    o.rooms = 17;
    const auto map = polymap::roomsMap(o, rng);
    const polymap::Eliminator eliminator(map.polygon, map.sites, {});
    try {
        polymap::verificationTour(eliminator, 0, {});
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("17 hypotheses"), std::string::npos) << e.what();
    }
}
