// Shortest paths inside P (funnel over the triangulation's sleeve) against a brute-force
// visibility-graph Dijkstra, on random star polygons and the steps map; closed forms.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/ExactPredicates.h>
#include <mrloc/polymap/MapGenerators.h>
#include <mrloc/polymap/ShortestPath.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <queue>

#include "RandomInside.h"

using namespace mrloc;
using common::orientation;
using common::Polygon;
using common::TPoint2D;
using test::randomInside;

namespace {

/** Segment p-q stays in P (boundary included): it crosses no edge properly (an edge that
 *  p or q lies on, up to rounding, does not count: edge midpoints are queried) and, between
 *  the vertices of P it passes through, its pieces' midpoints are in P. */
bool segmentInside(const Polygon& P, const TPoint2D& p, const TPoint2D& q) {
    std::vector<double> cuts{0, 1};
    const double len2 = common::dot(q - p, q - p);
    for (size_t i = 0; i < P.size(); ++i) {
        const TPoint2D &a = P[i], &b = P[P.next(i)];
        if (common::distanceToSegment(p, a, b) <= P.epsilon() ||
            common::distanceToSegment(q, a, b) <= P.epsilon())
            continue;
        const int o1 = orientation(p, q, a), o2 = orientation(p, q, b);
        const int o3 = orientation(a, b, p), o4 = orientation(a, b, q);
        if (o1 * o2 < 0 && o3 * o4 < 0) return false;
        if (o1 == 0 && len2 > 0) {
            const double s = common::dot(a - p, q - p) / len2;
            if (s > 0 && s < 1) cuts.push_back(s);
        }
    }
    std::sort(cuts.begin(), cuts.end());
    for (size_t k = 0; k + 1 < cuts.size(); ++k)
        if (P.locate(p + (q - p) * (0.5 * (cuts[k] + cuts[k + 1])), 1e-9) ==
            Polygon::Where::Outside)
            return false;
    return true;
}

/** Dijkstra over the visibility graph of P's vertices, a and b. */
double bruteForceDistance(const Polygon& P, const TPoint2D& a, const TPoint2D& b) {
    std::vector<TPoint2D> nodes = P.vertices();
    nodes.push_back(a);
    nodes.push_back(b);
    const size_t m = nodes.size(), src = m - 2, dst = m - 1;
    std::vector<double> dist(m, std::numeric_limits<double>::infinity());
    std::vector<char> done(m, 0);
    dist[src] = 0;
    for (size_t it = 0; it < m; ++it) {
        size_t u = m;
        for (size_t k = 0; k < m; ++k)
            if (!done[k] && (u == m || dist[k] < dist[u])) u = k;
        if (u == m || std::isinf(dist[u])) break;
        if (u == dst) break;
        done[u] = 1;
        for (size_t k = 0; k < m; ++k)
            if (!done[k] && dist[u] + (nodes[k] - nodes[u]).norm() < dist[k] &&
                segmentInside(P, nodes[u], nodes[k]))
                dist[k] = dist[u] + (nodes[k] - nodes[u]).norm();
    }
    return dist[dst];
}

/** Checks one query: the path stays in P, ends where asked, and is as long as the brute
 *  force's; returns the relative difference. */
double check(const Polygon& P, const polymap::ShortestPaths& paths, const TPoint2D& a,
             const TPoint2D& b) {
    const auto g = paths.path(a, b);
    EXPECT_EQ(g.points.front(), a);
    EXPECT_EQ(g.points.back(), b);
    for (size_t k = 0; k + 1 < g.points.size(); ++k) {
        EXPECT_TRUE(segmentInside(P, g.points[k], g.points[k + 1]))
            << "leg " << k << " of " << a.asString() << " -> " << b.asString();
        EXPECT_NE(g.points[k], g.points[k + 1])  // every corner once
            << "leg " << k << " of " << a.asString() << " -> " << b.asString();
    }
    const double truth = bruteForceDistance(P, a, b);
    return std::abs(g.length - truth) / std::max(truth, 1e-12);
}

}  // namespace

TEST(ShortestPath, AroundOneCornerClosedForm) {
    // L-shaped: from the bottom leg's far end to the top of the vertical leg, round the
    // reflex corner (2, 2).
    const auto P = Polygon::fromVertices({{0, 0}, {6, 0}, {6, 2}, {2, 2}, {2, 5}, {0, 5}}, "L");
    const polymap::Triangulation T(P);
    const polymap::ShortestPaths paths(T);
    const auto g = paths.path({5, 1}, {1, 4});
    ASSERT_EQ(g.points.size(), 3u);
    EXPECT_EQ(g.points[1], TPoint2D(2, 2));
    EXPECT_NEAR(g.length, std::hypot(3, 1) + std::hypot(1, 2), 1e-12);
    EXPECT_NEAR(paths.distance({1, 1}, {5, 1}), 4.0, 1e-12);  // in sight: straight
    EXPECT_NEAR(paths.distance({1, 1}, {1, 1}), 0.0, 0);
    EXPECT_THROW(paths.path({1, 1}, {4, 4}), Error);
}

TEST(ShortestPath, AgreesWithVisibilityGraphDijkstra) {
    // Measured: no difference on random stars, 1.4e-16 on the steps map (the same corners
    // summed in another order); tolerance 1e-12, far below any wrong corner.
    mrpt::random::CRandomGenerator rng(4);
    double worst = 0;
    for (int poly = 0; poly < 30; ++poly) {
        const int n = 10 + 5 * poly;
        const auto P = polymap::randomStarPolygon(n, 0.1, 1.0, rng);
        const polymap::Triangulation T(P);
        const polymap::ShortestPaths paths(T);
        for (int k = 0; k < 10; ++k) {
            const TPoint2D a = randomInside(P, rng), b = randomInside(P, rng);
            worst = std::max(worst, check(P, paths, a, b));
        }
        // From a vertex, to an edge's midpoint, and vertex to vertex.
        const size_t i = (size_t)rng.drawUniform32bit() % P.size();
        const size_t j = (size_t)rng.drawUniform32bit() % P.size();
        worst = std::max(worst, check(P, paths, P[i], (P[j] + P[P.next(j)]) * 0.5));
        worst = std::max(worst, check(P, paths, P[i], P[j]));
    }
    std::cout << "random stars: largest relative difference " << worst << "\n";
    EXPECT_LT(worst, 1e-12);
}

TEST(ShortestPath, StepsMapWithCollinearVertices) {
    const auto P = polymap::stepsMap({}).polygon;
    const polymap::Triangulation T(P);
    const polymap::ShortestPaths paths(T);
    mrpt::random::CRandomGenerator rng(6);
    double worst = 0;
    for (int k = 0; k < 40; ++k)
        worst = std::max(worst, check(P, paths, randomInside(P, rng), randomInside(P, rng)));
    for (size_t i = 0; i < P.size(); i += 9)
        worst = std::max(worst, check(P, paths, P[i], P[(i * 7 + 3) % P.size()]));
    std::cout << "steps: largest relative difference " << worst << "\n";
    EXPECT_LT(worst, 1e-12);
}

TEST(ShortestPath, AroundAPillarClosedForm) {
    // A 10 x 8 room with a pillar [4, 5] x [4, 5]: from (2, 4.5) to (8, 4.5) round two of the
    // pillar's corners (either side: the same length).
    const auto P = Polygon::fromRings(
        {{{0, 0}, {10, 0}, {10, 8}, {0, 8}}, {{4, 4}, {5, 4}, {5, 5}, {4, 5}}}, "pillar room");
    const polymap::Triangulation T(P);
    const polymap::ShortestPaths paths(T);
    const auto g = paths.path({2, 4.5}, {8, 4.5});
    ASSERT_EQ(g.points.size(), 4u);
    EXPECT_NEAR(g.length, std::hypot(2, 0.5) + 1 + std::hypot(3, 0.5), 1e-12);
    EXPECT_NEAR(std::abs(g.points[1].y - 4.5), 0.5, 0);
    EXPECT_NEAR(paths.distance({2, 1}, {8, 1}), 6.0, 1e-12);  // below the pillar: straight
    EXPECT_THROW(paths.path({2, 1}, {4.5, 4.5}), Error);      // in the pillar
}

TEST(ShortestPath, WithHolesAgreesWithVisibilityGraphDijkstra) {
    // Pillar halls (holes of 4 to 9 vertices) and rooms with pillars: the reduced visibility
    // graph's Dijkstra against the brute force over every vertex pair. Measured: largest
    // relative difference 2e-16 (sums in another order); tolerance 1e-12.
    mrpt::random::CRandomGenerator rng(21);
    double worst = 0;
    for (int hall = 0; hall < 5; ++hall) {
        const auto P = polymap::pillarHall(2 + hall, 3, 4 + hall, 1.5, rng).polygon;
        const polymap::Triangulation T(P);
        const polymap::ShortestPaths paths(T);
        const TPoint2D from = randomInside(P, rng);
        for (int k = 0; k < 8; ++k) {  // one source, many goals (the source's cache)
            worst = std::max(worst, check(P, paths, from, randomInside(P, rng)));
            worst = std::max(worst, check(P, paths, randomInside(P, rng), randomInside(P, rng)));
        }
        const size_t i = 4 + (size_t)rng.drawUniform32bit() % (P.size() - 4);
        worst = std::max(worst, check(P, paths, P[i], P[0]));                         // hole vertex
        worst = std::max(worst, check(P, paths, (P[i] + P[P.next(i)]) * 0.5, from));  // its edge
    }
    polymap::RoomsMapOptions o;
    o.pillar = 0.75;
    const auto rooms = polymap::roomsMap(o, rng);
    const polymap::Triangulation T(rooms.polygon);
    const polymap::ShortestPaths paths(T);
    for (size_t a = 0; a < rooms.sites.size(); ++a)
        for (size_t b = 0; b < rooms.sites.size(); ++b)
            worst = std::max(worst, check(rooms.polygon, paths, rooms.sites[a], rooms.sites[b]));
    std::cout << "holes: largest relative difference " << worst << "\n";
    EXPECT_LT(worst, 1e-12);
}
