#pragma once
// Private to the elimination (Elimination.cpp, ProbeCandidates.cpp): the overlay region OI
// of the live hypotheses as a polygon, triangulated, with its shortest paths and its
// nearest-candidate search; and the cache of the map's own critical chords.
#include <mrloc/polymap/Elimination.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <optional>
#include <queue>
#include <utility>
#include <vector>

namespace mrloc::polymap {
namespace detail {

/** OI as a polygon (its holes too: pillars, or the walls of P's holes), for point location
 *  and shortest paths inside it. */
common::Polygon polygonOf(const OverlayRegion& oi);

/** p lies in T's polygon at least `radius` from its boundary: no edge of the polygon within
 *  `radius`, found by a walk over the triangles that the disk of that radius reaches (the
 *  segment to the nearest boundary point crosses only such triangles), so the cost is local. */
bool clearInside(const Triangulation& T, const TPoint2D& p, double radius);

}  // namespace detail

/** OI of the live hypotheses, as a polygon, triangulated, with its shortest paths. */
struct Eliminator::Region {
    OverlayRegion oi;
    common::Polygon polygon;
    Triangulation triangles;
    ShortestPaths paths;

    explicit Region(const common::Polygon& P, const std::vector<TPoint2D>& positions)
        : oi(overlayRegion(P, positions)),  // seed 002 steps 4-6
          polygon(detail::polygonOf(oi)),
          triangles(polygon),
          paths(triangles) {}
    Region(const Region&) = delete;  // triangles and paths refer to the members above
    Region& operator=(const Region&) = delete;

    /** p lies inside OI, `clearance` from its boundary (up to rounding: window probes sit
     *  at it). */
    bool clear(const TPoint2D& p, double clearance) const {
        return detail::clearInside(triangles, p,
                                   std::max(clearance * (1 - 1e-9), polygon.epsilon()));
    }

    /** The candidate nearest to `at` by travel inside OI, `clearance` from its boundary,
     *  that passes `test`, with that travel; candidates are tested nearest first (ties:
     *  lower index first), and `tested` counts them. The straight line bounds the travel from
     * below, so geodesics are computed only for the candidates whose straight distance is below the
     * answer's travel. */
    template <typename Test>
    std::optional<std::pair<double, size_t>> nearest(const TPoint2D& at,
                                                     const std::vector<TPoint2D>& found,
                                                     double clearance, Test test,
                                                     size_t* tested = nullptr) const {
        using Entry = std::pair<double, size_t>;
        std::vector<Entry> straight;  // a min-heap: only the near ones are ever taken off
        straight.reserve(found.size());
        for (size_t c = 0; c < found.size(); ++c) straight.push_back({(found[c] - at).norm(), c});
        std::make_heap(straight.begin(), straight.end(), std::greater<>());
        std::priority_queue<Entry, std::vector<Entry>, std::greater<>> byTravel;
        while (!straight.empty() || !byTravel.empty()) {
            if (!straight.empty() &&
                (byTravel.empty() || straight.front().first <= byTravel.top().first)) {
                const size_t c = straight.front().second;
                std::pop_heap(straight.begin(), straight.end(), std::greater<>());
                straight.pop_back();
                if (clear(found[c], clearance)) byTravel.push({paths.distance(at, found[c]), c});
                continue;
            }
            const auto [travel, c] = byTravel.top();
            byTravel.pop();
            if (tested) ++*tested;
            if (test(found[c])) return std::make_pair(travel, c);
        }
        return std::nullopt;
    }
};

struct Eliminator::ChordCache {
    std::once_flag once;
    std::vector<Chord> chords;
};

}  // namespace mrloc::polymap
