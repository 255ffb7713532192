#include <mrloc/framesync/Matching.h>
#include <mrpt/math/wrap2pi.h>

#include <algorithm>
#include <cmath>

namespace mrloc::framesync {

mrpt::poses::CPose2D redefinitionTransform(const TPoint2D& centre, double rotation,
                                           const TPoint2D& normal, double shift) {
    using mrpt::poses::CPose2D;
    // seed 004 sec. 4.4: rotate about the robot's position, then move along the normal
    const CPose2D rotate = CPose2D(centre.x, centre.y, rotation) + CPose2D(-centre.x, -centre.y, 0);
    return CPose2D(normal.x * shift, normal.y * shift, 0) + rotate;
}

double overlapAlong(const Wall& reference, const Wall& other) {
    const TPoint2D d = (reference.b - reference.a) * (1.0 / std::max(reference.length(), 1e-12));
    auto along = [&](const TPoint2D& p) {
        return d.x * (p.x - reference.a.x) + d.y * (p.y - reference.a.y);
    };
    const double lo = std::min(along(other.a), along(other.b));
    const double hi = std::max(along(other.a), along(other.b));
    return std::min(hi, reference.length()) - std::max(lo, 0.0);
}

std::optional<Redefinition> matchWalls(const Wall& own, const Wall& reference,
                                       const TPoint2D& robot, const MatchOptions& options) {
    const double rotation = mrpt::math::wrapToPi(reference.normal - own.normal);
    if (std::abs(rotation) >= options.maxBearing) return std::nullopt;  // sec. 4.3, first test
    const double dOwn = own.distanceFrom(robot), dReference = reference.distanceFrom(robot);
    if (std::abs(dReference - dOwn) >= options.maxDistance) return std::nullopt;  // second
    Redefinition r;
    r.rotation = rotation;
    // the rotation about the robot keeps the own wall at dOwn; the shift brings it to
    // dReference along the reference's normal
    r.shift = dReference - dOwn;
    r.correction = redefinitionTransform(robot, rotation, reference.unitNormal(), r.shift);
    r.overlap = overlapAlong(reference, own.transformed(r.correction));
    if (!(r.overlap > options.minOverlap)) return std::nullopt;  // third test
    return r;
}

}  // namespace mrloc::framesync
