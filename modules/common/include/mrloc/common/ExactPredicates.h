#pragma once
// Exact geometric predicates on double coordinates (Shewchuk, "Adaptive precision
// floating-point arithmetic and fast robust geometric predicates", DCG 18, 1997): a
// floating-point evaluation with a proven error bound decides almost always; when it cannot,
// the determinant is evaluated exactly as a floating-point expansion. The answers are
// exact for every finite input whose products neither overflow nor underflow (coordinates
// within Polygon::kMaxCoordinate and not below 1e-100 in magnitude differences).
#include <mrpt/math/TPoint2D.h>

namespace mrloc::common {

/** Sign of the orientation of a, b, c: +1 if c lies left of the directed line a->b
 *  (a, b, c counter-clockwise), -1 if right, 0 if exactly collinear. */
int orientation(const mrpt::math::TPoint2D& a, const mrpt::math::TPoint2D& b,
                const mrpt::math::TPoint2D& c);

/** +1 if d lies strictly inside the circle through a, b, c (counter-clockwise), -1 if
 *  outside, 0 if exactly on it. */
int inCircle(const mrpt::math::TPoint2D& a, const mrpt::math::TPoint2D& b,
             const mrpt::math::TPoint2D& c, const mrpt::math::TPoint2D& d);

}  // namespace mrloc::common
