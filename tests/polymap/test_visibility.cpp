// Visibility polygons against closed forms and against a ray-casting oracle at many angles,
// for points inside, on edges and on vertices.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/polymap/MapGenerators.h>
#include <mrloc/polymap/Visibility.h>

#include <cmath>

using namespace mrloc;
using common::Polygon;
using common::TPoint2D;
using common::TVector2D;
using polymap::visibilityPolygon;

namespace {

/** Distance a viewer at q sees along dir: 0 if dir leaves P at once. */
double oracle(const Polygon& P, const TPoint2D& q, const TVector2D& dir) {
    const double probe = 1e-7 * (P.max() - P.min()).norm();
    if (P.locate(q + dir * probe, 1e-13) != Polygon::Where::Inside) return 0;
    return P.rayCast(q, dir, 1e-12).value_or(0);
}

/** Largest radial disagreement of V(q) with the oracle over `rays` directions. */
double worstDisagreement(const Polygon& P, const TPoint2D& q, int rays = 2000) {
    const auto V = visibilityPolygon(P, q);
    double worst = 0;
    for (int i = 0; i < rays; ++i) {
        const double a = 2 * M_PI * (i + 0.318309886) / rays;  // never a round angle
        const TVector2D dir{std::cos(a), std::sin(a)};
        worst = std::max(worst, std::abs(V.radius(dir) - oracle(P, q, dir)));
    }
    return worst;
}

TPoint2D randomInside(const Polygon& P, mrpt::random::CRandomGenerator& rng) {
    for (;;) {
        const TPoint2D p{rng.drawUniform(P.min().x, P.max().x),
                         rng.drawUniform(P.min().y, P.max().y)};
        if (P.locate(p) == Polygon::Where::Inside) return p;
    }
}

}  // namespace

TEST(Visibility, ConvexPolygonSeesItself) {
    const auto P = Polygon::fromVertices({{0, 0}, {4, 0}, {4, 3}, {0, 3}}, "box");
    const auto V = visibilityPolygon(P, {1, 1});
    ASSERT_EQ(V.size(), 4u);
    const auto placed = V.placedAt({1, 1});
    for (const auto& p : P.vertices())
        EXPECT_NE(std::find(placed.begin(), placed.end(), p), placed.end()) << p.asString();
}

TEST(Visibility, LShapeWindowClosedForm) {
    // L: the viewer at (1, 3) in the vertical leg sees the leg and, past the reflex vertex
    // (2, 2), the horizontal leg up to where the window from (1,3) through (2,2) meets the
    // floor y = 0: (4, 0).
    const auto P = Polygon::fromVertices({{0, 0}, {6, 0}, {6, 2}, {2, 2}, {2, 5}, {0, 5}}, "L");
    auto V = visibilityPolygon(P, {1, 3});
    const auto placed = V.placedAt({1, 3});
    const std::vector<TPoint2D> expected{{0, 0}, {4, 0}, {2, 2}, {2, 5}, {0, 5}};
    ASSERT_EQ(placed.size(), expected.size());
    for (const auto& e : expected) {
        double nearest = 1e9;
        for (const auto& p : placed) nearest = std::min(nearest, (p - e).norm());
        EXPECT_LT(nearest, 1e-12) << e.asString();
    }
    // Exactly one window: (4,0)-(2,2).
    int windows = 0;
    for (size_t i = 0; i < V.size(); ++i) windows += V.isRadial(i);
    EXPECT_EQ(windows, 1);
}

TEST(Visibility, OutsideIsAnError) {
    const auto P = Polygon::fromVertices({{0, 0}, {4, 0}, {4, 3}, {0, 3}}, "box");
    EXPECT_THROW(visibilityPolygon(P, {5, 1}), Error);
}

TEST(Visibility, AgreesWithRayCastingOnRandomPolygons) {
    mrpt::random::CRandomGenerator rng(7);
    for (int poly = 0; poly < 25; ++poly) {
        const auto P = polymap::randomStarPolygon(8 + 2 * poly, 0.2, 1.0, rng);
        for (int k = 0; k < 6; ++k) {
            const auto q = randomInside(P, rng);
            EXPECT_LT(worstDisagreement(P, q), 1e-9)
                << "polygon " << poly << " at " << q.asString();
        }
        // On an edge, and on a vertex (reflex or convex).
        const size_t e = (size_t)rng.drawUniform32bit() % P.size();
        const TPoint2D onEdge = P[e] + (P[P.next(e)] - P[e]) * 0.37;
        EXPECT_LT(worstDisagreement(P, onEdge), 1e-9) << "polygon " << poly << " edge " << e;
        EXPECT_LT(worstDisagreement(P, P[e]), 1e-9) << "polygon " << poly << " vertex " << e;
    }
}

TEST(Visibility, AgreesWithRayCastingOnStepsMapWithCollinearities) {
    // Orthogonal, integer coordinates: many vertices share directions from a viewpoint.
    const auto map = polymap::stepsMap({});
    const auto& P = map.polygon;
    mrpt::random::CRandomGenerator rng(3);
    for (int k = 0; k < 10; ++k) {
        const TPoint2D q = randomInside(P, rng);
        const TPoint2D grid{std::round(q.x), std::round(q.y)};  // lines up with vertices
        EXPECT_LT(worstDisagreement(P, q), 1e-9) << q.asString();
        if (P.contains(grid)) {
            EXPECT_LT(worstDisagreement(P, grid), 1e-9) << grid.asString();
        }
    }
    for (size_t i = 0; i < P.size(); i += 7) {
        EXPECT_LT(worstDisagreement(P, P[i]), 1e-9) << "vertex " << i;
        EXPECT_LT(worstDisagreement(P, (P[i] + P[P.next(i)]) * 0.5), 1e-9) << "edge " << i;
    }
    for (const auto& s : map.sites) EXPECT_LT(worstDisagreement(P, s), 1e-9) << s.asString();
}

TEST(Visibility, CollinearVerticesOfTheMapDoNotMatter) {
    // The same rectangle with extra straight-through vertices sees the same polygon.
    const auto plain = Polygon::fromVertices({{0, 0}, {4, 0}, {4, 3}, {0, 3}}, "plain");
    const auto split = Polygon::fromVertices(
        {{0, 0}, {1, 0}, {2, 0}, {4, 0}, {4, 1.5}, {4, 3}, {2, 3}, {0, 3}}, "split");
    for (const TPoint2D q : {TPoint2D{1, 1}, TPoint2D{2, 0}, TPoint2D{4, 1.5}, TPoint2D{0, 0}}) {
        const auto a = visibilityPolygon(plain, q), b = visibilityPolygon(split, q);
        EXPECT_EQ(a.size(), b.size()) << q.asString();
        EXPECT_LT(polymap::boundaryDistance(a, b, 0.01), 1e-12) << q.asString();
    }
}
