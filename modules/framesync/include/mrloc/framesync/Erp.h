#pragma once
// Estimated reflection points (ERP), seed 004 sec. 4.1, eqs. (1)-(6). A sonar reports the
// distance to the nearest echo in its cone; off a flat wall (a specular reflector) that is
// the perpendicular distance. Two readings r1 at P1 and r2 at P2 of one sonar that came
// from the same wall fix the wall's normal direction and the two reflection points.
//
// The paper's eq. (4) is garbled in the text (its square root reads (y2 - x2)^2); derived
// again (doc/framesync.md): a wall n.X = c with unit normal n pointing from the sensor to
// the wall gives r_i = c - n.P_i, so n.(P2 - P1) = -(r2 - r1), and with alpha the
// direction of P1 -> P2 the normal's direction is
//     phi = alpha +- arccos(-(r2 - r1) / |P1 P2|),
// which is eq. (4) once the paper's alpha (measured from the y axis, eqs. (5)-(6)) is
// turned into ours (pi/2 - alpha_paper). |r2 - r1| > |P1 P2| admits no wall.
#include <mrpt/math/TPoint2D.h>

#include <vector>

namespace mrloc::framesync {

using mrpt::math::TPoint2D;

/** Both roots of the normal's direction (rad, wrapped to (-pi, pi]), equal when
 *  |r2 - r1| = |P1 P2|; empty when |r2 - r1| > |P1 P2| (no flat wall gives both ranges)
 *  or when P1 = P2. Seed 004 eq. (4), re-derived. */
std::vector<double> wallNormalDirections(const TPoint2D& p1, double r1, const TPoint2D& p2,
                                         double r2);

/** One estimated reflection point: where the sonar's echo came from if the wall is flat. */
struct Erp {
    TPoint2D sensor;   ///< P_i, the sensor's position
    TPoint2D point;    ///< R_i = P_i + r_i (cos phi, sin phi), eqs. (2)-(3)
    double direction;  ///< phi: the direction of P_i -> R_i, the wall's normal (rad)
};

inline Erp makeErp(const TPoint2D& sensor, double range, double direction) {
    return {sensor, sensor + TPoint2D(range * std::cos(direction), range * std::sin(direction)),
            direction};
}

}  // namespace mrloc::framesync
