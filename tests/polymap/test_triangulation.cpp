// The constrained Delaunay triangulation of P: its invariants on the maps polymap meets
// (steps and rooms families, random stars up to n = 5000, star5000.poly, a regular polygon
// whose vertices are all nearly cocircular, orthogonal maps full of exactly cocircular
// corners and collinear vertices), and exact point location.
#include <gtest/gtest.h>
#include <mrloc/common/ExactPredicates.h>
#include <mrloc/polymap/MapGenerators.h>
#include <mrloc/polymap/Triangulation.h>

#include <cmath>
#include <map>
#include <set>

#include "TestPaths.h"

using namespace mrloc;
using common::orientation;
using common::Polygon;
using common::TPoint2D;
using polymap::Triangulation;

namespace {

std::vector<std::pair<std::string, Polygon>> testMaps() {
    std::vector<std::pair<std::string, Polygon>> maps;
    for (int steps : {3, 6, 41}) {
        polymap::StepsMapOptions o;
        o.steps = steps;
        maps.push_back({"steps" + std::to_string(steps), polymap::stepsMap(o).polygon});
    }
    mrpt::random::CRandomGenerator rng(11);
    maps.push_back({"rooms", polymap::roomsMap({}, rng).polygon});
    polymap::RoomsMapOptions longRooms;  // 1250 m by 9 m: P's edges cross the enclosing
    longRooms.rooms = 30;                // triangle's Delaunay edges
    longRooms.roomSteps = 80;
    longRooms.roomWidth = 40;
    maps.push_back({"rooms4984", polymap::roomsMap(longRooms, rng).polygon});
    for (int n : {12, 300, 5000})
        maps.push_back({"star" + std::to_string(n), polymap::randomStarPolygon(n, 0.1, 1.0, rng)});
    maps.push_back({"star5000.poly", Polygon::load(std::string(MRLOC_SOURCE_DIR) +
                                                   "/tests/data/bad-inputs/star5000.poly")});
    std::vector<TPoint2D> circle;
    for (int i = 0; i < 64; ++i)
        circle.push_back({std::cos(2 * M_PI * i / 64), std::sin(2 * M_PI * i / 64)});
    maps.push_back({"circle64", Polygon::fromVertices(circle, "circle64")});
    // A comb on the integer grid with straight-through vertices along its spine: squares
    // whose four corners are exactly cocircular.
    std::vector<TPoint2D> comb{{0, 0}};
    for (int x = 1; x <= 20; ++x) comb.push_back({(double)x, 0});
    for (int t = 19; t >= 0; t -= 2) {
        comb.push_back({(double)t + 1, 3});
        comb.push_back({(double)t, 3});
        comb.push_back({(double)t, 1});
        if (t > 0) comb.push_back({(double)t - 1, 1});
    }
    maps.push_back({"comb", Polygon::fromVertices(comb, "comb")});
    // holes: 100 pillars of 20 vertices (n = 2004), and rooms with a square pillar each
    maps.push_back({"hall100", polymap::pillarHall(10, 10, 20, 2.0, rng).polygon});
    polymap::RoomsMapOptions pillars;
    pillars.pillar = 0.5;
    for (const auto layout : polymap::kRoomsLayouts) {
        pillars.layout = layout;
        maps.push_back({"rooms with pillars, " + polymap::roomsLayoutName(layout),
                        polymap::roomsMap(pillars, rng).polygon});
    }
    return maps;
}

}  // namespace

TEST(Triangulation, InvariantsOnEveryMap) {
    for (const auto& [name, P] : testMaps()) {
        SCOPED_TRACE(name);
        const Triangulation T(P);
        const int n = (int)P.size();
        const size_t holes = P.ringCount() - 1;
        EXPECT_EQ(T.insideCount(), P.size() + 2 * holes - 2);
        std::set<std::pair<int, int>> edges, constrainedEdges;
        double area = 0;
        size_t inside = 0, localDelaunayViolations = 0;
        for (int t = 0; t < (int)T.triangles().size(); ++t) {
            const auto& tri = T[t];
            for (int i = 0; i < 3; ++i) {  // neighbours agree and share the edge reversed
                const int u = tri.neighbour[(size_t)i];
                if (u == Triangulation::kNone) continue;
                const int j = T.edgeTowards(u, t);
                ASSERT_GE(j, 0);
                EXPECT_EQ(T[u].from(j), tri.to(i));
                EXPECT_EQ(T[u].to(j), tri.from(i));
                EXPECT_EQ(T[u].constrained[(size_t)j], tri.constrained[(size_t)i]);
                EXPECT_EQ(T[u].inside != tri.inside, tri.constrained[(size_t)i]);
            }
            if (!tri.inside) continue;
            ++inside;
            for (int k = 0; k < 3; ++k) ASSERT_LT(tri.v[(size_t)k], n);  // no Steiner point
            const TPoint2D &a = T.point(tri.v[0]), &b = T.point(tri.v[1]), &c = T.point(tri.v[2]);
            EXPECT_EQ(orientation(a, b, c), 1);
            area += 0.5 * common::cross(b - a, c - a);
            for (int i = 0; i < 3; ++i) {
                const int p = tri.from(i), q = tri.to(i);
                edges.insert({std::min(p, q), std::max(p, q)});
                if (tri.constrained[(size_t)i]) {
                    EXPECT_EQ(q, (int)P.next((size_t)p)) << "a constrained edge that is not P's";
                    constrainedEdges.insert({p, q});
                } else {
                    EXPECT_NE(q, (int)P.next((size_t)p)) << "P's edge " << p << " not constrained";
                    const int u = tri.neighbour[(size_t)i];
                    const int d = T[u].v[(size_t)T.edgeTowards(u, t)];
                    localDelaunayViolations += common::inCircle(a, b, c, T.point(d)) > 0;
                }
            }
        }
        EXPECT_EQ(inside, P.size() + 2 * holes - 2);
        EXPECT_EQ(constrainedEdges.size(), P.size());  // every edge of P, once
        // Euler: V - E + F = 1 - h for a disc with h holes
        EXPECT_EQ(edges.size(), 2 * P.size() + 3 * holes - 3);
        EXPECT_EQ(localDelaunayViolations, 0u);  // so constrained Delaunay
        EXPECT_NEAR(area, P.area(), 1e-12 * std::abs(P.area()));
    }
}

TEST(Triangulation, EveryInsideTriangleIsInsideP) {
    for (const auto& [name, P] : testMaps()) {
        if (P.size() > 1000) continue;  // Polygon::locate is O(n)
        SCOPED_TRACE(name);
        const Triangulation T(P);
        for (const auto& tri : T.triangles()) {
            const TPoint2D centroid =
                (T.point(tri.v[0]) + T.point(tri.v[1]) + T.point(tri.v[2])) * (1.0 / 3);
            EXPECT_EQ(P.locate(centroid, 0) == Polygon::Where::Inside, tri.inside)
                << centroid.asString();
        }
    }
}

TEST(Triangulation, LocatesExactly) {
    mrpt::random::CRandomGenerator rng(5);
    for (const auto& [name, P] : testMaps()) {
        SCOPED_TRACE(name);
        const Triangulation T(P);
        const int queries = P.size() > 1000 ? 200 : 1000;
        for (int k = 0; k < queries; ++k) {
            const TPoint2D p{rng.drawUniform(P.min().x - 1, P.max().x + 1),
                             rng.drawUniform(P.min().y - 1, P.max().y + 1)};
            const auto loc = T.locate(p);
            ASSERT_NE(loc.triangle, Triangulation::kNone);
            const auto& tri = T[loc.triangle];
            for (int i = 0; i < 3; ++i)
                ASSERT_GE(orientation(T.point(tri.from(i)), T.point(tri.to(i)), p), 0);
            const auto where = P.locate(p, 0);
            if (where != Polygon::Where::Boundary) {
                EXPECT_EQ(tri.inside, where == Polygon::Where::Inside) << p.asString();
            }
        }
        // Vertices and points exactly on P's edges (integer maps: exact midpoints).
        for (int v = 0; v < (int)P.size(); v += 7) {
            const auto loc = T.locate(P[(size_t)v]);
            ASSERT_GE(loc.vertex, 0);
            EXPECT_EQ(T[loc.triangle].v[(size_t)loc.vertex], v);
        }
    }
    const auto steps = polymap::stepsMap({}).polygon;
    const Triangulation T(steps);
    for (size_t e = 0; e < steps.size(); ++e) {
        const auto loc = T.locate((steps[e] + steps[steps.next(e)]) * 0.5);
        EXPECT_GE(loc.edge, 0) << "edge " << e;
    }
}

TEST(Triangulation, SameMapSameTriangles) {
    const auto P =
        Polygon::load(std::string(MRLOC_SOURCE_DIR) + "/tests/data/bad-inputs/star5000.poly");
    const Triangulation a(P), b(P);
    ASSERT_EQ(a.triangles().size(), b.triangles().size());
    for (size_t t = 0; t < a.triangles().size(); ++t)
        EXPECT_EQ(a.triangles()[t].v, b.triangles()[t].v);
}
