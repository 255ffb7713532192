// common::orientation and common::inCircle against exact rational arithmetic
// (Boost.Multiprecision), on inputs where plain floating point decides wrongly.
#include <gtest/gtest.h>
#include <mrloc/common/ExactPredicates.h>

#include <boost/multiprecision/cpp_int.hpp>
#include <cmath>
#include <iostream>
#include <random>

using mrloc::common::inCircle;
using mrloc::common::orientation;
using mrpt::math::TPoint2D;
using Rational = boost::multiprecision::cpp_rational;

namespace {

int sign(const Rational& r) { return boost::multiprecision::sign(r); }

int orientationRational(const TPoint2D& a, const TPoint2D& b, const TPoint2D& c) {
    const Rational ax(a.x), ay(a.y), bx(b.x), by(b.y), cx(c.x), cy(c.y);
    return sign(Rational((ax - cx) * (by - cy) - (ay - cy) * (bx - cx)));
}

int inCircleRational(const TPoint2D& a, const TPoint2D& b, const TPoint2D& c, const TPoint2D& d) {
    const Rational adx = Rational(a.x) - d.x, ady = Rational(a.y) - d.y;
    const Rational bdx = Rational(b.x) - d.x, bdy = Rational(b.y) - d.y;
    const Rational cdx = Rational(c.x) - d.x, cdy = Rational(c.y) - d.y;
    return sign(Rational((adx * adx + ady * ady) * (bdx * cdy - bdy * cdx) +
                         (bdx * bdx + bdy * bdy) * (cdx * ady - cdy * adx) +
                         (cdx * cdx + cdy * cdy) * (adx * bdy - ady * bdx)));
}

}  // namespace

TEST(ExactPredicates, OrientationOnTheKettnerGrid) {
    // Kettner et al., "Classroom examples of robustness problems" (2008): p = (0.5 + x u,
    // 0.5 + y u) against the line (12, 12)-(24, 24), u = 2^-53. Naive evaluation gets a
    // large share of these 256 x 256 points wrong; the exact one none.
    const double u = std::ldexp(1.0, -53);
    const TPoint2D q{12, 12}, r{24, 24};
    int naiveWrong = 0, collinear = 0;
    for (int x = 0; x < 256; ++x)
        for (int y = 0; y < 256; ++y) {
            const TPoint2D p{0.5 + x * u, 0.5 + y * u};
            const int truth = orientationRational(p, q, r);
            ASSERT_EQ(orientation(p, q, r), truth) << x << " " << y;
            const double naive = (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x);
            naiveWrong += (naive > 0 ? 1 : naive < 0 ? -1 : 0) != truth;
            collinear += truth == 0;
        }
    std::cout << naiveWrong << " naive signs wrong, " << collinear << " collinear\n";
    EXPECT_GT(naiveWrong, 10000);  // the test means something: measured 11,972 wrong ...
    EXPECT_GT(collinear, 200);     // ... and 256 exactly collinear (x = y)
}

TEST(ExactPredicates, InCircleOnCocircularAndPerturbedPoints) {
    std::mt19937 rng(3);
    std::uniform_int_distribution<int> coord(-1000, 1000);
    int zeros = 0;
    for (int k = 0; k < 3000; ++k) {
        // A rectangle's corners are cocircular; nudge the fourth by a few ulps, or not.
        const double x0 = coord(rng) / 7.0, y0 = coord(rng) / 3.0;
        const double w = 1 + std::abs(coord(rng)) / 11.0, h = 1 + std::abs(coord(rng)) / 13.0;
        const TPoint2D a{x0, y0}, b{x0 + w, y0}, c{x0 + w, y0 + h};
        TPoint2D d{x0, y0 + h};
        const int nudge = (int)(rng() % 5) - 2;
        d.x = std::nextafter(d.x, nudge > 0 ? 1e9 : -1e9);
        if (nudge == 0) d.x = x0;
        const int truth = inCircleRational(a, b, c, d);
        ASSERT_EQ(inCircle(a, b, c, d), truth) << k;
        zeros += truth == 0;
    }
    EXPECT_GT(zeros, 100);
}

TEST(ExactPredicates, RandomNearDegenerateTriples) {
    std::mt19937_64 rng(8);
    std::uniform_real_distribution<double> uni(-1e3, 1e3);
    for (int k = 0; k < 20000; ++k) {
        const TPoint2D a{uni(rng), uni(rng)}, b{uni(rng), uni(rng)};
        const double t = uni(rng) / 1e3;
        TPoint2D c = a + (b - a) * t;  // on the line up to rounding
        if (k % 2) c.y = std::nextafter(c.y, 1e9);
        ASSERT_EQ(orientation(a, b, c), orientationRational(a, b, c)) << k;
        const TPoint2D d = a + (c - a) * 0.5;
        ASSERT_EQ(inCircle(a, b, c, d), inCircleRational(a, b, c, d)) << k;
    }
}
