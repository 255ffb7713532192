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

namespace {

/** Where the two walls' lines meet; nothing for lines closer to parallel than `minAngle`. */
std::optional<TPoint2D> corner(const Wall& p, const Wall& q, double minAngle) {
    const double angle = std::abs(mrpt::math::wrapToPi(p.normal - q.normal));
    if (angle < minAngle || angle > M_PI - minAngle) return std::nullopt;
    // n_p . X = n_p . a_p and n_q . X = n_q . a_q
    const TPoint2D np = p.unitNormal(), nq = q.unitNormal();
    const double cp = np.x * p.a.x + np.y * p.a.y, cq = nq.x * q.a.x + nq.y * q.a.y;
    const double det = np.x * nq.y - np.y * nq.x;
    return TPoint2D((cp * nq.y - cq * np.y) / det, (np.x * cq - nq.x * cp) / det);
}

/** Own walls T puts on some reference wall, and the summed misfit (for ties). */
std::pair<size_t, double> supportOf(const mrpt::poses::CPose2D& T,
                                    const std::vector<const Wall*>& own,
                                    const std::vector<const Wall*>& reference,
                                    const MatchOptions& o) {
    size_t n = 0;
    double misfit = 0;
    for (const Wall* w : own) {
        const Wall moved = w->transformed(T);
        const TPoint2D mid = (moved.a + moved.b) * 0.5;
        double best = INFINITY;
        for (const Wall* r : reference) {
            const double bearing = std::abs(mrpt::math::wrapToPi(r->normal - moved.normal));
            const double distance = std::abs(r->distanceFrom(mid));
            if (bearing > o.generalBearing || distance > o.generalDistance) continue;
            if (!(overlapAlong(*r, moved) > o.minOverlap)) continue;
            best = std::min(best, bearing / o.generalBearing + distance / o.generalDistance);
        }
        if (std::isfinite(best)) ++n, misfit += best;
    }
    return {n, misfit};
}

}  // namespace

std::optional<Redefinition> generalMatch(const std::vector<const Wall*>& own,
                                         const std::vector<const Wall*>& reference,
                                         const MatchOptions& options, size_t* ownWall,
                                         size_t* referenceWall) {
    std::optional<Redefinition> best;
    double bestMisfit = INFINITY;
    for (size_t i = 0; i < own.size(); ++i)
        for (size_t j = i + 1; j < own.size(); ++j) {
            const auto co = corner(*own[i], *own[j], options.cornerAngle);
            if (!co) continue;
            const double angleOwn = mrpt::math::wrapToPi(own[j]->normal - own[i]->normal);
            for (size_t k = 0; k < reference.size(); ++k)
                for (size_t l = 0; l < reference.size(); ++l) {
                    if (k == l) continue;
                    const double angleRef =
                        mrpt::math::wrapToPi(reference[l]->normal - reference[k]->normal);
                    if (std::abs(mrpt::math::wrapToPi(angleRef - angleOwn)) >
                        options.generalBearing)
                        continue;
                    const auto cr = corner(*reference[k], *reference[l], options.cornerAngle);
                    if (!cr) continue;
                    // seed 004 sec. 3: R_A = T R_B, the rotation the normals' difference (the
                    // mean of the corner's two), the shift taking one corner onto the other
                    const double theta =
                        mrpt::math::wrapToPi(reference[k]->normal - own[i]->normal +
                                             0.5 * mrpt::math::wrapToPi(angleRef - angleOwn));
                    const double c = std::cos(theta), s = std::sin(theta);
                    const mrpt::poses::CPose2D T(cr->x - (c * co->x - s * co->y),
                                                 cr->y - (s * co->x + c * co->y), theta);
                    const auto [support, misfit] = supportOf(T, own, reference, options);
                    if (support < options.generalSupport) continue;
                    if (best && (support < best->support ||
                                 (support == best->support && misfit >= bestMisfit)))
                        continue;
                    Redefinition r;
                    r.correction = T;
                    r.rotation = theta;
                    r.shift = std::hypot(T.x(), T.y());
                    r.support = support;
                    r.overlap = overlapAlong(*reference[k], own[i]->transformed(T));
                    best = r, bestMisfit = misfit;
                    if (ownWall) *ownWall = i;
                    if (referenceWall) *referenceWall = k;
                }
        }
    return best;
}

}  // namespace mrloc::framesync
