// mrloc::common::Polygon: validation, orientation, .poly I/O and the predicates.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/ExactPredicates.h>
#include <mrloc/common/Polygon.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>

#include "TestPaths.h"

using mrloc::Error;
using mrloc::common::Polygon;
using mrloc::common::TPoint2D;

namespace {

std::string errorOf(const std::vector<TPoint2D>& v) {
    try {
        Polygon::fromVertices(v, "test.poly");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

std::string writeTemp(const std::string& name, const std::string& text) {
    const auto path = std::filesystem::temp_directory_path() / name;
    std::ofstream(path) << text;
    return path.string();
}

}  // namespace

TEST(Polygon, ClockwiseInputIsReoriented) {
    const auto P = Polygon::fromVertices({{0, 0}, {0, 2}, {3, 2}, {3, 0}}, "cw");
    EXPECT_DOUBLE_EQ(P.area(), 6.0);
    EXPECT_EQ(P[0], TPoint2D(3, 0));  // reversed order
}

TEST(Polygon, InvalidInputIsAClearError) {
    EXPECT_NE(errorOf({{0, 0}, {1, 0}}).find("at least 3 vertices"), std::string::npos);
    EXPECT_NE(errorOf({{0, 0}, {1, 0}, {1, 1}, {1, 0}, {0, 1}}).find("repeats"), std::string::npos);
    // (2,0) goes back along the edge it came on: a zero-width spike.
    EXPECT_NE(errorOf({{0, 0}, {2, 0}, {1, 0}, {1, 1}}).find("collinear duplicate"),
              std::string::npos);
    // A bow tie crosses itself.
    EXPECT_NE(errorOf({{0, 0}, {3, 3}, {3, 0}, {0, 2}}).find("intersects itself"),
              std::string::npos);
    // A vertex touching a non-adjacent edge.
    EXPECT_NE(errorOf({{0, 0}, {4, 0}, {4, 4}, {2, 0}, {0, 4}}).find("intersects itself"),
              std::string::npos);
    EXPECT_NE(errorOf({{0, 0}, {1, 1}, {2, 2}}).find("no area"), std::string::npos);
    EXPECT_NE(errorOf({{0, 0}, {1, 0}, {NAN, 1}}).find("finite"), std::string::npos);
    // A straight-through collinear vertex is allowed.
    EXPECT_EQ(errorOf({{0, 0}, {1, 0}, {2, 0}, {2, 1}}), "");
}

TEST(Polygon, PolyFileRoundTripAndErrors) {
    // comments anywhere; a blank line before the first vertex or after the last is no ring
    const auto path =
        writeTemp("mrloc_square.poly", "# a square\n\n0 0\n# here\n2 0 # corner\n2 2\n0 2\n\n");
    const auto P = Polygon::load(path);
    EXPECT_EQ(P.size(), 4u);
    const auto copy = path + ".copy";
    P.save(copy, "copied");
    const auto Q = Polygon::load(copy);
    ASSERT_EQ(Q.size(), 4u);
    for (size_t i = 0; i < 4; ++i) EXPECT_EQ(P[i], Q[i]);
    const auto bad = writeTemp("mrloc_bad.poly", "0 0\n1 0\n1 x\n");
    try {
        Polygon::load(bad);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("mrloc_bad.poly:3"), std::string::npos) << e.what();
    }
    EXPECT_THROW(Polygon::load("/nonexistent/x.poly"), Error);
    // a blank line between vertices ends the ring: a second ring is a hole
    const auto holes = writeTemp("mrloc_holes.poly", "0 0\n4 0\n4 4\n0 4\n\n1 1\n2 1\n2 2\n");
    const auto H = Polygon::load(holes);
    ASSERT_EQ(H.ringCount(), 2u);
    EXPECT_NEAR(H.area(), 16 - 0.5, 1e-12);                    // the hole's area taken off
    EXPECT_EQ(H.locate({1.2, 1.8}), Polygon::Where::Inside);   // above the hole's hypotenuse
    EXPECT_EQ(H.locate({1.8, 1.2}), Polygon::Where::Outside);  // in the hole
    EXPECT_EQ(H.locate({1.5, 1}), Polygon::Where::Boundary);
    EXPECT_EQ(H.next(6), 4u);  // the hole's ring closes on itself
    EXPECT_EQ(H.prev(4), 6u);
    EXPECT_FALSE(H.isReflex(0));
    EXPECT_TRUE(H.isReflex(5));  // a hole's corners are reflex seen from the free space
    // saved and read back ring by ring, in the same order
    const auto again = writeTemp("mrloc_holes_again.poly", "");
    H.save(again);
    const auto H2 = Polygon::load(again);
    ASSERT_EQ(H2.size(), H.size());
    for (size_t i = 0; i < H.size(); ++i) EXPECT_EQ(H[i], H2[i]);
    EXPECT_EQ(H2.ringOf(5), 1u);
}

TEST(Polygon, SizeAndCoordinateBounds) {
    // More vertices than kMaxVertices: the file reader stops at the first one too many.
    std::string text;
    for (size_t i = 0; i <= Polygon::kMaxVertices; ++i) {
        const double a = 2 * M_PI * double(i) / double(Polygon::kMaxVertices + 1);
        text += std::to_string(100 * std::cos(a)) + " " + std::to_string(100 * std::sin(a)) + "\n";
    }
    try {
        Polygon::load(writeTemp("mrloc_huge.poly", text));
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("mrloc_huge.poly:20001: more than the 20000 vertices"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_NE(errorOf({{0, 0}, {2e6, 0}, {0, 1}}).find("vertex 2 lies beyond 1000000 m"),
              std::string::npos);
    // star5000.poly (tests/data/bad-inputs): a valid map of 5000 vertices on a 2^-16 grid.
    const auto star =
        Polygon::load(std::string(MRLOC_SOURCE_DIR) + "/tests/data/bad-inputs/star5000.poly");
    EXPECT_EQ(star.size(), 5000u);
    EXPECT_GT(star.area(), 0);
}

TEST(Polygon, LocateAndRayCast) {
    const auto P = Polygon::fromVertices({{0, 0}, {4, 0}, {4, 4}, {2, 2}, {0, 4}}, "notch");
    EXPECT_EQ(P.locate({1, 1}), Polygon::Where::Inside);
    EXPECT_EQ(P.locate({2, 3}), Polygon::Where::Outside);
    EXPECT_EQ(P.locate({2, 0}), Polygon::Where::Boundary);
    EXPECT_EQ(P.locate({2, 2}), Polygon::Where::Boundary);
    EXPECT_TRUE(P.isReflex(3));
    EXPECT_FALSE(P.isReflex(0));
    EXPECT_NEAR(*P.rayCast({1, 1}, {1, 0}), 3.0, 1e-12);
    EXPECT_NEAR(*P.rayCast({1, 1}, {0, 1}), 2.0, 1e-12);  // the notch's edge (0,4)-(2,2) at y=3
}

namespace {

/** Closed segments a-b and c-d share a point (exact). */
bool closedSegmentsMeet(const TPoint2D& a, const TPoint2D& b, const TPoint2D& c,
                        const TPoint2D& d) {
    using mrloc::common::orientation;
    const int o1 = orientation(a, b, c), o2 = orientation(a, b, d);
    const int o3 = orientation(c, d, a), o4 = orientation(c, d, b);
    const auto within = [](const TPoint2D& p, const TPoint2D& q, const TPoint2D& x) {
        return std::min(p.x, q.x) <= x.x && x.x <= std::max(p.x, q.x) &&
               std::min(p.y, q.y) <= x.y && x.y <= std::max(p.y, q.y);
    };
    if (o1 * o2 < 0 && o3 * o4 < 0) return true;
    return (o1 == 0 && within(a, b, c)) || (o2 == 0 && within(a, b, d)) ||
           (o3 == 0 && within(c, d, a)) || (o4 == 0 && within(c, d, b));
}

/** The validation rules, every pair tested: what the sweep must agree with. */
bool validByBruteForce(const std::vector<TPoint2D>& v) {
    const size_t n = v.size();
    for (size_t i = 0; i < n; ++i)
        for (size_t j = i + 1; j < n; ++j)
            if (v[i] == v[j]) return false;
    double area = 0;
    for (size_t i = 0; i < n; ++i) area += mrloc::common::cross(v[i], v[(i + 1) % n]);
    if (area == 0) return false;
    for (size_t i = 0; i < n; ++i) {  // a zero-width spike
        const TPoint2D &a = v[(i + n - 1) % n], &b = v[i], &c = v[(i + 1) % n];
        if (mrloc::common::orientation(a, b, c) == 0 && mrloc::common::dot(a - b, c - b) > 0)
            return false;
    }
    for (size_t i = 0; i < n; ++i)
        for (size_t j = i + 2; j < n; ++j) {
            if (i == 0 && j == n - 1) continue;
            if (closedSegmentsMeet(v[i], v[i + 1], v[j], v[(j + 1) % n])) return false;
        }
    return true;
}

}  // namespace

TEST(Polygon, SweepValidationAgreesWithEveryPairOnDegenerateGrids) {
    // Random vertex lists on a 6 x 6 integer grid: full of collinear edges, vertices on
    // other edges, edges touching end to end, overlapping, crossing; and some simple ones.
    std::mt19937 rng(17);
    size_t valid = 0, invalid = 0;
    for (int k = 0; k < 40000; ++k) {
        const int n = 3 + (int)(rng() % 8);
        std::vector<TPoint2D> v;
        for (int i = 0; i < n; ++i) v.push_back({(double)(rng() % 6), (double)(rng() % 6)});
        const bool expected = validByBruteForce(v);
        const bool accepted = errorOf(v).empty();
        ASSERT_EQ(accepted, expected) << ::testing::PrintToString(v);
        (expected ? valid : invalid)++;
    }
    std::cout << valid << " simple, " << invalid << " not\n";
    EXPECT_GT(valid, 1000u);
}

TEST(Polygon, RingsAreValidatedTogether) {
    // A 10 x 8 room: each hostile hole named, with the ring and where
    const std::vector<TPoint2D> room{{0, 0}, {10, 0}, {10, 8}, {0, 8}};
    const auto square = [](double x, double y, double s) {
        return std::vector<TPoint2D>{{x, y}, {x + s, y}, {x + s, y + s}, {x, y + s}};
    };
    const auto fails = [&](std::vector<std::vector<TPoint2D>> rings) {
        try {
            Polygon::fromRings(std::move(rings), "m.poly");
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(fails({room, square(12, 4, 1)})
                  .find("m.poly: ring 2, a hole, is not inside the "
                        "outer ring (ring 1) at its vertex (12 4)"),
              std::string::npos);
    EXPECT_NE(fails({room, square(2, 2, 4), square(3, 3, 1)})
                  .find("m.poly: ring 3, a hole, lies inside ring 2, another hole"),
              std::string::npos);
    EXPECT_NE(fails({room, square(2, 2, 2), square(3, 1, 2)}).find("m.poly: two rings cross"),
              std::string::npos)
        << fails({room, square(2, 2, 2), square(3, 1, 2)});
    EXPECT_NE(fails({room, square(2, 2, 2), square(4, 2, 2)}).find("two rings cross or touch"),
              std::string::npos);  // a shared wall: touching
    EXPECT_NE(fails({room, square(9, 2, 1)}).find("two rings cross or touch"),
              std::string::npos)  // a hole touching the outer wall
        << fails({room, square(9, 2, 1)});
    EXPECT_NE(fails({room, {{2, 2}, {6, 2}, {6, 4}, {4, 1}, {2, 4}}})
                  .find("m.poly (ring 2): the polygon intersects itself"),
              std::string::npos)
        << fails({room, {{2, 2}, {6, 2}, {6, 4}, {4, 1}, {2, 4}}});
    // two holes meeting at one vertex, one ending there and one beginning there in the
    // sweep's order (a pinch between pillars, as a traced grid map gives): the sweep never
    // holds their edges side by side, so the rings' vertices are compared together too
    // (fuzz_poly found it: the triangulation met the vertex twice)
    EXPECT_NE(
        fails({room, {{3, 4}, {5, 5}, {3, 6}}, {{5, 5}, {7, 4}, {7, 6}}})
            .find("m.poly: two rings cross or touch: ring 3 and ring 2 share the vertex (5 5)"),
        std::string::npos)
        << fails({room, {{3, 4}, {5, 5}, {3, 6}}, {{5, 5}, {7, 4}, {7, 6}}});
    EXPECT_NE(fails({room, {{2, 1}, {1, 2}, {0, 0}}}).find("touch"), std::string::npos)
        << fails({room, {{2, 1}, {1, 2}, {0, 0}}});  // a hole's corner on the outer corner
    // a good one: holes reoriented clockwise whatever their input order, the area net
    const auto P = Polygon::fromRings({room, square(2, 2, 1), {{5, 5}, {5, 6}, {6, 6}}}, "ok");
    EXPECT_EQ(P.ringCount(), 3u);
    EXPECT_NEAR(P.area(), 80 - 1 - 0.5, 1e-12);
    for (size_t r = 1; r < P.ringCount(); ++r) {
        double twice = 0;
        for (size_t i = P.ringBegin(r); i < P.ringEnd(r); ++i)
            twice += mrloc::common::cross(P[i], P[P.next(i)]);
        EXPECT_LT(twice, 0) << "ring " << r;
    }
    // the edges' sweep sees every ring: a pillar crossing the outer wall is refused even
    // though its first vertex is inside
    EXPECT_NE(fails({room, {{9, 4}, {11, 4}, {11, 5}, {9, 5}}}).find("two rings cross"),
              std::string::npos);
}
