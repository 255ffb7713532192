#pragma once
// Seed 000 section 3: the frame with A at the origin and B = (L, 0) on the x axis.
//
// The paper names theta_AC the angle BAC and theta_BC the angle ABC, but eq. (1)-(3) use
// them as the directions of the lines AC and BC measured from the x axis (with the interior
// angle ABC in eq. (2) the denominator of eq. (3) vanishes for every isosceles triangle
// ABC). Here the directions are computed from the interior angles and the side of AB the
// robot is on (known from the sign of the bearings): dir(AC) = side * BAC and
// dir(BC) = side * (180 - ABC). Footnote 1 writes sin where tan is meant (C above A at
// height h gives tan(ABC) = h / L); the special cases below use tan.
#include <Eigen/Core>
#include <optional>

namespace mrloc::omnivision {

using Vec2 = Eigen::Vector2d;

/** Directions of lines AC and BC (rad, from the x axis) from the interior angles at A and
 *  B and the side of AB that C is on (+1: left of A->B). */
struct LineDirections {
    double ac = 0, bc = 0;
};
LineDirections lineDirections(double angleAtA, double angleAtB, int side);

/** C in units of L (A = (0,0), B = (1,0)): eq. (3) (eq. (6) for C'), with footnote 1's
 *  special cases when a line is vertical. Throws mrloc::Error if the lines are parallel
 *  (C on the line AB, or both lines vertical). */
Vec2 unitBaselinePoint(const LineDirections& d);

/** L = |AB| from C before and after it moved l_C (eq. (8)): l_C / |C - C'| with C and C'
 *  in units of L. Throws mrloc::Error if l_C <= 0 (footnote 1: C must move) or if C and
 *  C' coincide in the angles (the motion is not observable). */
double baselineFromMotion(const LineDirections& before, const LineDirections& after, double lC);

/** Sine rule: the sides |ik|, |jk| of triangle ijk from |ij| and its interior angles at
 *  i, j and k. Throws mrloc::Error if the angle at k is 0 or 180 degrees. */
std::pair<double, double> sineRule(double ij, double angleI, double angleJ, double angleK);

}  // namespace mrloc::omnivision
