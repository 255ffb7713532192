#pragma once
// A flat wall as one robot measured it: a segment in the robot's frame and the direction of
// its normal, pointing from the side the robot saw it from towards the wall. One wall gives
// two of the three degrees of freedom of a frame: its bearing and its distance along the
// normal (seed 004 sec. 4.1, last paragraph).
#include <mrpt/math/TPoint2D.h>
#include <mrpt/poses/CPose2D.h>

#include <cmath>

namespace mrloc::framesync {

using mrpt::math::TPoint2D;

/** p in the frame new = f (+) old. */
inline TPoint2D composePoint(const mrpt::poses::CPose2D& f, const TPoint2D& p) {
    double x, y;
    f.composePoint(p.x, p.y, x, y);
    return {x, y};
}

struct Wall {
    TPoint2D a, b;        ///< the segment's ends (m)
    double normal = 0;    ///< direction of the unit normal towards the wall (rad)
    double residual = 0;  ///< largest ERP distance to the fitted line (m)
    size_t erps = 0;      ///< ERPs it was fitted to

    TPoint2D unitNormal() const { return {std::cos(normal), std::sin(normal)}; }
    double length() const { return (b - a).norm(); }
    /** Distance from p to the wall's line along the normal (positive: the wall is ahead of
     *  p in the normal's direction, the side it was seen from). */
    double distanceFrom(const TPoint2D& p) const {
        const TPoint2D n = unitNormal();
        return n.x * (a.x - p.x) + n.y * (a.y - p.y);
    }
    /** The same wall in a frame redefined by `f` (new = f (+) old). */
    Wall transformed(const mrpt::poses::CPose2D& f) const {
        Wall w = *this;
        w.a = composePoint(f, a);
        w.b = composePoint(f, b);
        w.normal = normal + f.phi();
        return w;
    }
};

}  // namespace mrloc::framesync
