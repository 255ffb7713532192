#pragma once
// The overlay intersection region OI (seed 002 steps 4-6): copies of P translated so that
// every live hypothesis sits at one origin, intersected; the connected component that holds
// the origin. A point x of OI is a place the robot can reach from where it stands, by the
// same displacement x, under every hypothesis at once; the probes that tell hypotheses
// apart are chosen in it.
//
// The polygon booleans are Boost.Geometry's (Boost Software License): translated copies of
// one map share whole edges and lie on each other's lines, the case where hand-written
// clipping breaks.
#include <mrloc/common/Polygon.h>

#include <vector>

namespace mrloc::polymap {

using common::TPoint2D;

struct OverlayRegion {
    /** Outer boundary, counter-clockwise, in the robot's frame (the origin is where it
     *  stands; axes along the map's). */
    std::vector<TPoint2D> outer;
    /** Holes, clockwise (translated copies can enclose one between them). */
    std::vector<std::vector<TPoint2D>> holes;
    double area = 0;  ///< m^2
    /** In OI, boundary included (within `tol`). */
    bool contains(const TPoint2D& p, double tol = 1e-9) const;
};

/** OI for hypotheses at `positions` (points of P, in the map frame). Throws mrloc::Error
 *  for no hypotheses or one outside P, or if the origin falls in no component. */
OverlayRegion overlayRegion(const common::Polygon& P, const std::vector<TPoint2D>& positions);

}  // namespace mrloc::polymap
