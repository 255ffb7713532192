// The overlay intersection region OI (seed 002 steps 4-6) against point sampling: a point
// is in OI iff it is inside every translated copy of P and connected to the origin.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/polymap/Hypotheses.h>
#include <mrloc/polymap/MapGenerators.h>
#include <mrloc/polymap/Overlay.h>

#include <cmath>
#include <iostream>
#include <queue>

using namespace mrloc;
using common::Polygon;
using common::TPoint2D;

namespace {

/** Inside every copy (P - p_i), with the distance to the nearest copy boundary. */
std::pair<bool, double> inAllCopies(const Polygon& P, const std::vector<TPoint2D>& hyps,
                                    const TPoint2D& x) {
    bool all = true;
    double nearest = INFINITY;
    for (const auto& h : hyps) {
        const TPoint2D y = x + h;  // x in the robot's frame is h + x in the map
        all = all && P.locate(y, 0) != Polygon::Where::Outside;
        for (size_t i = 0; i < P.size(); ++i)
            nearest = std::min(nearest, common::distanceToSegment(y, P[i], P[P.next(i)]));
    }
    return {all, nearest};
}

/** Compares OI with sampling on a grid of spacing h: grid cells whose centres are in every
 *  copy, flood-filled from the origin's cell, are the oracle's OI; samples nearer than 2 h
 *  to a copy's boundary (where a grid cannot tell) are skipped. Returns the samples checked. */
int compareWithSampling(const Polygon& P, const std::vector<TPoint2D>& hyps, double h) {
    const auto OI = polymap::overlayRegion(P, hyps);
    TPoint2D min{-INFINITY, -INFINITY}, max{INFINITY, INFINITY};
    for (const auto& q : hyps) {  // OI lies in every copy's bounding box
        min = {std::max(min.x, P.min().x - q.x), std::max(min.y, P.min().y - q.y)};
        max = {std::min(max.x, P.max().x - q.x), std::min(max.y, P.max().y - q.y)};
    }
    const int nx = (int)std::ceil((max.x - min.x) / h), ny = (int)std::ceil((max.y - min.y) / h);
    std::vector<char> in((size_t)nx * ny), far((size_t)nx * ny), reached((size_t)nx * ny);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const TPoint2D c{min.x + (i + 0.5) * h, min.y + (j + 0.5) * h};
            const auto [all, nearest] = inAllCopies(P, hyps, c);
            in[(size_t)(j * nx + i)] = all;
            far[(size_t)(j * nx + i)] = nearest > 2 * h;
        }
    const int oi = (int)std::floor((0 - min.x) / h), oj = (int)std::floor((0 - min.y) / h);
    std::queue<std::pair<int, int>> frontier;
    if (in[(size_t)(oj * nx + oi)]) frontier.push({oi, oj}), reached[(size_t)(oj * nx + oi)] = 1;
    while (!frontier.empty()) {
        const auto [i, j] = frontier.front();
        frontier.pop();
        for (const auto& [di, dj] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
            const int a = i + di, b = j + dj;
            if (a < 0 || b < 0 || a >= nx || b >= ny) continue;
            const size_t k = (size_t)(b * nx + a);
            if (in[k] && !reached[k]) reached[k] = 1, frontier.push({a, b});
        }
    }
    int checked = 0;
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const size_t k = (size_t)(j * nx + i);
            if (!far[k]) continue;
            const TPoint2D c{min.x + (i + 0.5) * h, min.y + (j + 0.5) * h};
            EXPECT_EQ(OI.contains(c), in[k] && reached[k]) << c.asString();
            ++checked;
        }
    EXPECT_TRUE(OI.contains({0, 0}));
    return checked;
}

}  // namespace

TEST(Overlay, TwoCopiesOfABoxClosedForm) {
    // A 4 x 3 box, hypotheses at (1, 1) and (2, 1): OI = [-1, 2] x [-1, 2].
    const auto P = Polygon::fromVertices({{0, 0}, {4, 0}, {4, 3}, {0, 3}}, "box");
    const auto OI = polymap::overlayRegion(P, {{1, 1}, {2, 1}});
    EXPECT_NEAR(OI.area, 9.0, 1e-12);
    EXPECT_TRUE(OI.contains({-1, -1}));
    EXPECT_TRUE(OI.contains({1.5, 1.5}));
    EXPECT_FALSE(OI.contains({2.5, 0}));
    EXPECT_TRUE(OI.holes.empty());
}

TEST(Overlay, StepsMapTwelveHypothesesAgainstSampling) {
    // The paper's n = 148, k = 12: all copies share whole walls (integer translations).
    const auto map = polymap::stepsMap({});
    const int checked = compareWithSampling(map.polygon, map.sites, 0.05);
    EXPECT_GT(checked, 100);
    const auto OI = polymap::overlayRegion(map.polygon, map.sites);
    std::cout << "steps k = 12: OI area " << OI.area << " m^2, " << OI.outer.size() << " vertices, "
              << checked << " samples checked\n";
}

TEST(Overlay, RoomsMapsAgainstSampling) {
    mrpt::random::CRandomGenerator rng(12);
    for (int rooms : {2, 3, 5}) {
        polymap::RoomsMapOptions o;
        o.rooms = rooms;
        const auto map = polymap::roomsMap(o, rng);
        const int checked = compareWithSampling(map.polygon, map.sites, 0.1);
        EXPECT_GT(checked, 100) << rooms;
    }
}

TEST(Overlay, OneHypothesisIsTheMapItself) {
    const auto map = polymap::stepsMap({});
    const auto OI = polymap::overlayRegion(map.polygon, {map.sites[0]});
    EXPECT_NEAR(OI.area, map.polygon.area(), 1e-9 * map.polygon.area());
    EXPECT_THROW(polymap::overlayRegion(map.polygon, {}), Error);
    EXPECT_THROW(polymap::overlayRegion(map.polygon, {{-100, -100}}), Error);
}
