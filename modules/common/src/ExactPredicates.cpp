#include <mrloc/common/ExactPredicates.h>

#include <cmath>
#include <vector>

namespace mrloc::common {
namespace {

constexpr double kEps = 1.1102230246251565e-16;  // 2^-53, half an ulp of 1
// Shewchuk's first-stage error bounds (ccwerrboundA, iccerrboundA).
constexpr double kOrientBound = (3.0 + 16.0 * kEps) * kEps;
constexpr double kInCircleBound = (10.0 + 96.0 * kEps) * kEps;

/** A nonoverlapping floating-point expansion: the exact value is the sum of its terms,
 *  ordered by increasing magnitude (Shewchuk sec. 2). */
using Expansion = std::vector<double>;

/** a + b = x + err exactly (Knuth's Two-Sum). */
inline void twoSum(double a, double b, double& x, double& err) {
    x = a + b;
    const double bv = x - a, av = x - bv;
    err = (a - av) + (b - bv);
}

/** d, computed as a - b, is exactly a - b (Two-Sum's error is zero). */
inline bool exactDifference(double a, double b, double d) {
    double x, err;
    twoSum(a, -b, x, err);
    return x == d && err == 0;
}

/** Adds b to the m terms of e exactly (Grow-Expansion with zero elimination); e has room
 *  for m + 1 terms. Returns the new number of terms. */
size_t grow(double* e, size_t m, double b) {
    double q = b;
    size_t out = 0;
    for (size_t i = 0; i < m; ++i) {
        double sum, err;
        twoSum(q, e[i], sum, err);
        q = sum;
        if (err != 0) e[out++] = err;
    }
    if (q != 0) e[out++] = q;
    return out;
}

void grow(Expansion& e, double b) {
    e.push_back(0);
    e.resize(grow(e.data(), e.size() - 1, b));
}

Expansion fromDifference(double a, double b) {
    Expansion e;
    grow(e, a);
    grow(e, -b);
    return e;
}

/** The exact product of two expansions (each term product split exactly with fma). */
Expansion times(const Expansion& a, const Expansion& b) {
    Expansion out;
    for (double x : a)
        for (double y : b) {
            const double p = x * y;
            grow(out, std::fma(x, y, -p));
            grow(out, p);
        }
    return out;
}

Expansion plus(Expansion a, const Expansion& b) {
    for (double y : b) grow(a, y);
    return a;
}

Expansion minus(Expansion a, const Expansion& b) {
    for (double y : b) grow(a, -y);
    return a;
}

/** The sign of an expansion is the sign of its largest term. */
int sign(const Expansion& e) { return e.empty() ? 0 : (e.back() > 0 ? 1 : -1); }

using mrpt::math::TPoint2D;

int orientationExact(const TPoint2D& a, const TPoint2D& b, const TPoint2D& c) {
    const Expansion acx = fromDifference(a.x, c.x), acy = fromDifference(a.y, c.y);
    const Expansion bcx = fromDifference(b.x, c.x), bcy = fromDifference(b.y, c.y);
    return sign(minus(times(acx, bcy), times(acy, bcx)));
}

int inCircleExact(const TPoint2D& a, const TPoint2D& b, const TPoint2D& c, const TPoint2D& d) {
    const Expansion adx = fromDifference(a.x, d.x), ady = fromDifference(a.y, d.y);
    const Expansion bdx = fromDifference(b.x, d.x), bdy = fromDifference(b.y, d.y);
    const Expansion cdx = fromDifference(c.x, d.x), cdy = fromDifference(c.y, d.y);
    const Expansion alift = plus(times(adx, adx), times(ady, ady));
    const Expansion blift = plus(times(bdx, bdx), times(bdy, bdy));
    const Expansion clift = plus(times(cdx, cdx), times(cdy, cdy));
    const Expansion bc = minus(times(bdx, cdy), times(bdy, cdx));
    const Expansion ca = minus(times(cdx, ady), times(cdy, adx));
    const Expansion ab = minus(times(adx, bdy), times(ady, bdx));
    return sign(plus(plus(times(alift, bc), times(blift, ca)), times(clift, ab)));
}

}  // namespace

int orientation(const TPoint2D& a, const TPoint2D& b, const TPoint2D& c) {
    const double acx = a.x - c.x, bcy = b.y - c.y, acy = a.y - c.y, bcx = b.x - c.x;
    const double left = acx * bcy, right = acy * bcx;
    const double det = left - right;
    const double bound = kOrientBound * (std::abs(left) + std::abs(right));
    if (det > bound) return 1;
    if (-det > bound) return -1;
    if (left == 0 && right == 0) return 0;  // both products exactly zero
    // Differences without rounding (grid and integer maps, nearby points): the two products
    // split exactly with fma make a four-term sum, summed exactly on the stack.
    if (exactDifference(a.x, c.x, acx) && exactDifference(b.y, c.y, bcy) &&
        exactDifference(a.y, c.y, acy) && exactDifference(b.x, c.x, bcx)) {
        const double terms[4] = {std::fma(acx, bcy, -left), left, -std::fma(acy, bcx, -right),
                                 -right};
        double e[4];
        size_t m = 0;
        for (const double t : terms) m = grow(e, m, t);
        return m == 0 ? 0 : (e[m - 1] > 0 ? 1 : -1);
    }
    return orientationExact(a, b, c);
}

int inCircle(const TPoint2D& a, const TPoint2D& b, const TPoint2D& c, const TPoint2D& d) {
    const double adx = a.x - d.x, bdx = b.x - d.x, cdx = c.x - d.x;
    const double ady = a.y - d.y, bdy = b.y - d.y, cdy = c.y - d.y;
    const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy, alift = adx * adx + ady * ady;
    const double cdxady = cdx * ady, adxcdy = adx * cdy, blift = bdx * bdx + bdy * bdy;
    const double adxbdy = adx * bdy, bdxady = bdx * ady, clift = cdx * cdx + cdy * cdy;
    const double det =
        alift * (bdxcdy - cdxbdy) + blift * (cdxady - adxcdy) + clift * (adxbdy - bdxady);
    const double permanent = (std::abs(bdxcdy) + std::abs(cdxbdy)) * alift +
                             (std::abs(cdxady) + std::abs(adxcdy)) * blift +
                             (std::abs(adxbdy) + std::abs(bdxady)) * clift;
    const double bound = kInCircleBound * permanent;
    if (det > bound) return 1;
    if (-det > bound) return -1;
    return inCircleExact(a, b, c, d);
}

}  // namespace mrloc::common
