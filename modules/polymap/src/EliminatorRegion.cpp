#include "EliminatorRegion.h"

#include <mrloc/common/Error.h>
#include <mrloc/common/ExactPredicates.h>

namespace mrloc::polymap::detail {

namespace {

/** One ring of OI as Boost gives it, with the points it repeats (up to rounding) and the
 *  zero-width spikes it leaves dropped. */
std::vector<TPoint2D> cleanRing(std::vector<TPoint2D> ring, double tol) {
    for (bool changed = true; changed && ring.size() > 3;) {
        changed = false;
        for (size_t i = 0; i < ring.size() && ring.size() > 3; ++i) {
            const size_t n = ring.size();
            const TPoint2D &a = ring[(i + n - 1) % n], &b = ring[i], &c = ring[(i + 1) % n];
            const bool repeat = (b - a).norm() <= tol;
            const bool spike = std::abs(common::cross(a - b, c - b)) <= tol * (c - a).norm() &&
                               common::dot(a - b, c - b) > 0;
            if (repeat || spike) {
                ring.erase(ring.begin() + (long)i);
                changed = true;
            }
        }
    }
    return ring;
}

}  // namespace

common::Polygon polygonOf(const OverlayRegion& oi) {
    TPoint2D lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
    for (const auto& p : oi.outer) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    }
    const double tol = 1e-8 * (hi - lo).norm();
    std::vector<std::vector<TPoint2D>> rings{cleanRing(oi.outer, tol)};
    for (const auto& h : oi.holes) {
        auto ring = cleanRing(h, tol);
        // a sliver hole (rounding where two copies' walls meet) has no area to route round
        double twiceArea = 0;
        for (size_t i = 0; i < ring.size(); ++i)
            twiceArea += common::cross(ring[i], ring[(i + 1) % ring.size()]);
        if (ring.size() >= 3 && std::abs(twiceArea) > tol * (hi - lo).norm())
            rings.push_back(std::move(ring));
    }
    return common::Polygon::fromRings(std::move(rings), "elimination: the overlay region");
}

bool clearInside(const Triangulation& T, const TPoint2D& p, double radius) {
    const auto at = T.locate(p);
    if (at.triangle == Triangulation::kNone || !T[at.triangle].inside) return false;
    thread_local std::vector<int> reached;  // the disk is small: a few triangles
    reached.assign(1, at.triangle);
    for (size_t next = 0; next < reached.size(); ++next) {
        const auto& tri = T[reached[next]];
        for (int i = 0; i < 3; ++i) {
            if (common::distanceToSegment(p, T.point(tri.from(i)), T.point(tri.to(i))) >= radius)
                continue;
            if (tri.constrained[i]) return false;
            const int u = tri.neighbour[i];
            if (u != Triangulation::kNone && T[u].inside &&
                std::find(reached.begin(), reached.end(), u) == reached.end())
                reached.push_back(u);
        }
    }
    return true;
}

}  // namespace mrloc::polymap::detail
