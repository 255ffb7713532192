#include <mrloc/common/Error.h>
#include <mrloc/common/ExactPredicates.h>
#include <mrloc/polymap/ShortestPath.h>

#include <algorithm>

namespace mrloc::polymap {

using common::orientation;

ShortestPaths::ShortestPaths(const Triangulation& T) : T_(T) {
    const size_t count = T.triangles().size();
    parent_.assign(count, Triangulation::kNone);
    depth_.assign(count, -1);
    int root = Triangulation::kNone;
    for (size_t t = 0; t < count && root == Triangulation::kNone; ++t)
        if (T[(int)t].inside) root = (int)t;
    std::vector<int> stack{root};
    depth_[(size_t)root] = 0;
    while (!stack.empty()) {
        const int t = stack.back();
        stack.pop_back();
        for (int i = 0; i < 3; ++i) {
            const int u = T[t].neighbour[(size_t)i];
            if (T[t].constrained[(size_t)i] || depth_[(size_t)u] >= 0) continue;
            parent_[(size_t)u] = t;
            depth_[(size_t)u] = depth_[(size_t)t] + 1;
            stack.push_back(u);
        }
    }
}

std::vector<int> ShortestPaths::sleeve(int s, int t) const {
    std::vector<int> fromS, fromT;
    while (depth_[(size_t)s] > depth_[(size_t)t]) fromS.push_back(s), s = parent_[(size_t)s];
    while (depth_[(size_t)t] > depth_[(size_t)s]) fromT.push_back(t), t = parent_[(size_t)t];
    while (s != t) {
        fromS.push_back(s), s = parent_[(size_t)s];
        fromT.push_back(t), t = parent_[(size_t)t];
    }
    fromS.push_back(s);  // the common ancestor
    fromS.insert(fromS.end(), fromT.rbegin(), fromT.rend());
    return fromS;
}

GeodesicPath ShortestPaths::path(const TPoint2D& a, const TPoint2D& b) const {
    const auto la = T_.locateInside(a, "shortest path: the start");
    const auto lb = T_.locateInside(b, "shortest path: the goal");
    const std::vector<int> triangles = sleeve(la.triangle, lb.triangle);
    // The portals: the edges the sleeve crosses, as (left, right) seen walking along it.
    std::vector<std::pair<TPoint2D, TPoint2D>> portals{{a, a}};
    for (size_t k = 0; k + 1 < triangles.size(); ++k) {
        const int i = T_.edgeTowards(triangles[k], triangles[k + 1]);
        const auto& tri = T_[triangles[k]];
        portals.push_back({T_.point(tri.to(i)), T_.point(tri.from(i))});
    }
    portals.push_back({b, b});

    // The funnel: an apex and the left and right chains' last points; a portal end that
    // narrows the funnel moves its side, one that crosses the other side makes that side's
    // point a corner of the path and the new apex.
    GeodesicPath out;
    out.points.push_back(a);
    // A restart from a corner can meet it again (portals sharing that vertex): once is enough.
    const auto corner = [&out](const TPoint2D& p) {
        if (out.points.back() != p) out.points.push_back(p);
    };
    TPoint2D apex = a, left = a, right = a;
    size_t apexAt = 0, leftAt = 0, rightAt = 0;
    for (size_t i = 1; i < portals.size(); ++i) {
        const auto& [l, r] = portals[i];
        if (orientation(apex, right, r) >= 0) {
            if (apex == right || orientation(apex, left, r) < 0) {
                right = r, rightAt = i;
            } else {
                corner(left);
                apex = right = left, apexAt = rightAt = leftAt;
                i = apexAt;
                continue;
            }
        }
        if (orientation(apex, left, l) <= 0) {
            if (apex == left || orientation(apex, right, l) > 0) {
                left = l, leftAt = i;
            } else {
                corner(right);
                apex = left = right, apexAt = leftAt = rightAt;
                i = apexAt;
                continue;
            }
        }
    }
    if (out.points.back() != b) out.points.push_back(b);
    for (size_t k = 0; k + 1 < out.points.size(); ++k)
        out.length += (out.points[k + 1] - out.points[k]).norm();
    return out;
}

}  // namespace mrloc::polymap
