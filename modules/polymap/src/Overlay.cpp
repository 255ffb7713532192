#include <mrloc/common/Error.h>
#include <mrloc/polymap/Overlay.h>
#include <mrpt/core/format.h>

// Boost 1.74's rescaling policy trips GCC 12's -Wmaybe-uninitialized (a false positive in
// the header, not in our use).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <boost/geometry.hpp>
#include <boost/geometry/geometries/multi_polygon.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>
#include <limits>

namespace mrloc::polymap {

namespace bg = boost::geometry;
using BPoint = bg::model::d2::point_xy<double>;
using BPolygon = bg::model::polygon<BPoint, false /*counter-clockwise*/, false /*open*/>;
using BMulti = bg::model::multi_polygon<BPolygon>;

namespace {

/** P moved by -by; its holes (stored clockwise, as Boost wants a counter-clockwise
 *  polygon's inner rings) kept. */
BPolygon translated(const common::Polygon& P, const TPoint2D& by) {
    BPolygon out;
    for (size_t r = 0; r < P.ringCount(); ++r) {
        auto& ring = r == 0 ? out.outer() : (out.inners().emplace_back(), out.inners().back());
        ring.reserve(P.ringEnd(r) - P.ringBegin(r));
        for (size_t i = P.ringBegin(r); i < P.ringEnd(r); ++i)
            ring.push_back({P[i].x - by.x, P[i].y - by.y});
    }
    return out;
}

std::vector<TPoint2D> ring(const bg::model::ring<BPoint, false, false>& r) {
    std::vector<TPoint2D> out;
    out.reserve(r.size());
    for (const auto& p : r) out.push_back({p.x(), p.y()});
    return out;
}

/** Where p lies against a ring: -1 outside, 0 within tol of the boundary, 1 inside. */
int side(const std::vector<TPoint2D>& r, const TPoint2D& p, double tol) {
    bool inside = false;
    for (size_t i = 0, j = r.size() - 1; i < r.size(); j = i++) {
        if (common::distanceToSegment(p, r[j], r[i]) <= tol) return 0;
        if ((r[j].y > p.y) != (r[i].y > p.y) &&
            p.x < r[j].x + (p.y - r[j].y) * (r[i].x - r[j].x) / (r[i].y - r[j].y))
            inside = !inside;
    }
    return inside ? 1 : -1;
}

}  // namespace

bool OverlayRegion::contains(const TPoint2D& p, double tol) const {
    if (outer.empty() || side(outer, p, tol) < 0) return false;
    for (const auto& h : holes)
        if (side(h, p, tol) > 0) return false;
    return true;
}

OverlayRegion overlayRegion(const common::Polygon& P, const std::vector<TPoint2D>& positions) {
    if (positions.empty()) throw Error("overlay region: no hypotheses");
    for (const auto& p : positions)
        if (!P.contains(p))
            throw Error(mrpt::format("overlay region: hypothesis (%.9g %.9g) is outside the map",
                                     p.x, p.y));
    // seed 002 steps 4-6: P translated by -p_i puts hypothesis i at the origin.
    BMulti region;
    region.push_back(translated(P, positions[0]));
    for (size_t i = 1; i < positions.size() && !region.empty(); ++i) {
        BMulti next;
        bg::intersection(region, translated(P, positions[i]), next);
        region = std::move(next);
    }
    // The component holding the origin (on its boundary if a hypothesis is on P's).
    const BPoint origin{0, 0};
    const BPolygon* best = nullptr;
    double bestDistance = std::numeric_limits<double>::infinity();
    for (const auto& poly : region) {
        const double d = bg::distance(origin, poly);
        if (d < bestDistance) bestDistance = d, best = &poly;
    }
    const double tol = 1e3 * P.epsilon();
    if (!best || bestDistance > tol)
        throw Error(
            mrpt::format("overlay region: the origin lies in no component of the "
                         "intersection (%zu hypotheses, %zu components)",
                         positions.size(), region.size()));
    OverlayRegion out;
    out.outer = ring(best->outer());
    for (const auto& h : best->inners()) out.holes.push_back(ring(h));
    out.area = bg::area(*best);
    return out;
}

}  // namespace mrloc::polymap

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
