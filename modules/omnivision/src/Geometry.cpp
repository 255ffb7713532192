#include <mrloc/common/Error.h>
#include <mrloc/omnivision/Geometry.h>
#include <mrpt/core/format.h>

#include <cmath>

namespace mrloc::omnivision {

namespace {
constexpr double kVertical = 1e-12;  ///< |cos| below which a line counts as vertical
bool vertical(double angle) { return std::abs(std::cos(angle)) < kVertical; }
}  // namespace

LineDirections lineDirections(double angleAtA, double angleAtB, int side) {
    const double s = side >= 0 ? 1.0 : -1.0;
    return {s * angleAtA, s * (M_PI - angleAtB)};
}

Vec2 unitBaselinePoint(const LineDirections& d) {
    const bool va = vertical(d.ac), vb = vertical(d.bc);
    if (va && vb) throw Error("omnivision: lines AC and BC are both vertical: no intersection");
    if (va) return {0.0, -std::tan(d.bc)};  // footnote 1: C = (0, -L tan theta_BC)
    if (vb) return {1.0, std::tan(d.ac)};   // footnote 1: C = (L, L tan theta_AC)
    const double ta = std::tan(d.ac), tb = std::tan(d.bc);
    const double den = tb - ta;
    if (std::abs(den) < 1e-12 * (1 + std::abs(ta) + std::abs(tb)))
        throw Error(mrpt::format(
            "omnivision: lines AC and BC are parallel (directions %.6f and %.6f deg): the "
            "robot is on the line AB",
            d.ac * 180 / M_PI, d.bc * 180 / M_PI));
    return {tb / den, ta * tb / den};  // eq. (3)
}

double baselineFromMotion(const LineDirections& before, const LineDirections& after, double lC) {
    if (!(lC > 0))
        throw Error(mrpt::format(
            "omnivision: the moving robot's distance l_C = %g: eq. (8) needs it to move "
            "(footnote 1)",
            lC));
    const Vec2 c = unitBaselinePoint(before), c2 = unitBaselinePoint(after);
    const double unitMotion = (c - c2).norm();  // the braces of eq. (8), square-rooted
    if (unitMotion < 1e-12)
        throw Error(
            "omnivision: the robot's angles did not change between t_b and t_e: its "
            "motion is not observable and eq. (8) has no solution");
    return lC / unitMotion;
}

std::pair<double, double> sineRule(double ij, double angleI, double angleJ, double angleK) {
    const double sk = std::sin(angleK);
    if (std::abs(sk) < 1e-12)
        throw Error("omnivision: a triangle's angle is 0 or 180 degrees: the sine rule fails");
    return {ij * std::sin(angleJ) / sk, ij * std::sin(angleI) / sk};
}

}  // namespace mrloc::omnivision
