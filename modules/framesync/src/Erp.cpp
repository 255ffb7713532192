#include <mrloc/framesync/Erp.h>
#include <mrpt/math/wrap2pi.h>

#include <cmath>

namespace mrloc::framesync {

std::vector<double> wallNormalDirections(const TPoint2D& p1, double r1, const TPoint2D& p2,
                                         double r2) {
    const double dx = p2.x - p1.x, dy = p2.y - p1.y;
    const double length = std::hypot(dx, dy);
    if (!(length > 0)) return {};
    const double cosine = -(r2 - r1) / length;  // n.(P2 - P1) / |P1 P2|
    if (std::abs(cosine) > 1) return {};        // no wall: the ranges changed more than P moved
    const double alpha = std::atan2(dy, dx);
    const double spread = std::acos(cosine);
    if (spread == 0 || spread == M_PI) return {mrpt::math::wrapToPi(alpha + spread)};
    return {mrpt::math::wrapToPi(alpha + spread), mrpt::math::wrapToPi(alpha - spread)};
}

}  // namespace mrloc::framesync
