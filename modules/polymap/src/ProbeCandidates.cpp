// The probe candidates of each elimination algorithm (seed 002 sec. 2) and their
// completions (ProbeSource): where Eliminator::chooseProbe looks for a separating probe.
#include <mrloc/common/Error.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include "EliminatorRegion.h"

namespace mrloc::polymap {

namespace {

/** The critical chords of a polygon (Dudek-Romanik-Whitesides 1998): what a point sees
 *  changes only where its sight line to a vertex grazes a reflex vertex, i.e. across the
 *  chord that extends the line from vertex v through reflex vertex r into the polygon. */
template <class Chord>
std::vector<Chord> criticalChords(const common::Polygon& poly, const Triangulation& T) {
    std::vector<Chord> out;
    const auto& R = poly.vertices();
    const size_t m = R.size();
    const double eps = poly.epsilon();
    for (size_t r = 0; r < m; ++r) {
        if (!poly.isReflex(r)) continue;
        // What r sees: the vertices v it sees and, past r, where each chord ends.
        const VisibilityPolygon Vr = visibilityPolygon(T, R[r]);
        for (size_t v = 0; v < m; ++v) {
            if (v == r) continue;
            const TVector2D toV = R[v] - R[r];
            const bool adjacent = v == poly.next(r) || r == poly.next(v);
            if (!adjacent && Vr.radius(toV * (1 / toV.norm())) < toV.norm() - eps)
                continue;  // v hidden from r
            const TVector2D d = toV * (-1 / toV.norm());
            const double hit = Vr.radius(d);
            if (hit <= 1e3 * eps) continue;  // the extension leaves the polygon at once
            out.push_back({R[r], d, hit});
        }
    }
    return out;
}

/** Points along a chord (every `spacing`, at most perChord), both sides of it at the
 *  clearance, moved by `shift`. The nearest point of a cell lies on its boundary. */
void sampleSegment(const TPoint2D& from, const TVector2D& d, double length, double spacing,
                   int perChord, double clearance, const TVector2D& shift,
                   std::vector<TPoint2D>& out) {
    const TVector2D normal{-d.y, d.x};
    const int samples = std::clamp((int)std::ceil(length / spacing), 1, perChord);
    for (int k = 0; k < samples; ++k) {
        const TPoint2D on = from + d * (length * (k + 0.5) / samples) + shift;
        for (const double side : {-1.0, 1.0})
            out.push_back(on + normal * (side * std::max(clearance, 1e-6)));
    }
}

bool inBox(const TPoint2D& p, const common::Polygon& box) {
    return p.x >= box.min().x && p.y >= box.min().y && p.x <= box.max().x && p.y <= box.max().y;
}

}  // namespace

const std::vector<Eliminator::Chord>& Eliminator::mapChords() const {
    std::call_once(chords_->once, [this] { chords_->chords = criticalChords<Chord>(P_, T_); });
    return chords_->chords;
}

std::vector<TPoint2D> Eliminator::chordCandidates(const Region& region, double chordSpacing,
                                                  int perChord) const {
    // Algorithm 1 (Dudek-Romanik-Whitesides): the decomposition's cells are bounded by OI's
    // critical chords and OI's edges, and the nearest point of a cell lies on its boundary:
    // candidates are points along every chord, on both sides of it (cleared when reached:
    // see nearest()).
    std::vector<TPoint2D> out;
    for (const auto& c : criticalChords<Chord>(region.polygon, region.triangles))
        sampleSegment(c.from, c.d, c.length, chordSpacing, perChord, options_.clearance, {0, 0},
                      out);
    return out;
}

std::vector<TPoint2D> Eliminator::mapChordCandidates(const std::vector<size_t>& live,
                                                     const Region& region, double chordSpacing,
                                                     int perChord) const {
    std::vector<TPoint2D> out, chord;
    for (const auto& c : mapChords())
        for (size_t i : live) {
            chord.clear();
            sampleSegment(c.from, c.d, c.length, chordSpacing, perChord, options_.clearance,
                          hypotheses_[i] * -1.0, chord);
            for (const auto& p : chord)
                if (inBox(p, region.polygon)) out.push_back(p);
        }
    return out;
}

std::vector<TPoint2D> Eliminator::mapWindowCandidates(const std::vector<size_t>& live,
                                                      const Region& region,
                                                      const TPoint2D& from) const {
    // The windows of what the robot would see in the map under each live hypothesis, from
    // where it stands and from algorithm 4's middles, where the window itself may lie beyond
    // OI (a corridor seen from OI's edge): points along each window, and along the way from
    // the viewpoint towards its middle (walking up to a window shows what is behind it).
    std::vector<TPoint2D> viewpoints{from}, out;
    const auto middles = windowCandidates(region, from);
    viewpoints.insert(viewpoints.end(), middles.begin(), middles.end());
    const double spacing = std::max(options_.clearance, 1e-3);
    for (const auto& vp : viewpoints)
        for (size_t i : live) {
            VisibilityPolygon V;
            try {
                V = viewOf(i, vp);
            } catch (const Error&) {  // vp off the map under this hypothesis (by rounding)
                continue;
            }
            for (size_t e = 0; e < V.size(); ++e) {
                if (!V.isRadial(e)) continue;
                const TPoint2D a = V.vertices[e], b = V.vertices[(e + 1) % V.size()];
                const double length = (b - a).norm();
                if (!(length > 0)) continue;
                std::vector<TPoint2D> window;
                sampleSegment(a, (b - a) * (1 / length), length, spacing, 32, options_.clearance,
                              vp, window);
                const TVector2D toMiddle = (a + b) * 0.5;
                const double reach = toMiddle.norm();
                if (reach > 0)
                    sampleSegment({0, 0}, toMiddle * (1 / reach), reach, spacing, 32,
                                  options_.clearance, vp, window);
                for (const auto& p : window)
                    if (inBox(p, region.polygon)) out.push_back(p);
            }
        }
    return out;
}

std::vector<TPoint2D> Eliminator::windowCandidates(const Region& region,
                                                   const TPoint2D& from) const {
    // Algorithm 4, step 6: the middle points of windows [4] in OI. A window (Koenig, Mitchell,
    // Mudgal and Tovey 2009; Guibas, Motwani and Raghavan 1997) is an edge of a visibility
    // polygon that is not on the boundary: the robot would see more through it. The robot's
    // view inside OI from `from` gives the first windows; from a window's middle the robot
    // sees the windows behind it, and so on breadth first, until the candidates reach every
    // part of OI it can walk into (at most kWindowViews views). Middles closer than the
    // clearance are one.
    const double merge = std::max(options_.clearance, 1e-6 * (P_.max() - P_.min()).norm());
    std::vector<TPoint2D> out;
    std::set<std::pair<long, long>> taken;  // middles, by cells of the merge size
    std::vector<TPoint2D> viewpoints{from};
    for (size_t next = 0; next < viewpoints.size() && next < kWindowViews; ++next) {
        VisibilityPolygon V;
        try {
            V = visibilityPolygon(region.triangles, viewpoints[next]);
        } catch (const Error&) {  // the robot off OI (by rounding)
            continue;
        }
        for (size_t i = 0; i < V.size(); ++i) {
            if (!V.isRadial(i)) continue;  // a wall
            const TPoint2D m =
                viewpoints[next] + (V.vertices[i] + V.vertices[(i + 1) % V.size()]) * 0.5;
            // a wall seen edge-on lies on OI's boundary; a window in a gap narrower than the
            // clearance has no middle the robot may stand on
            if (!region.clear(m, options_.clearance)) continue;
            if (!taken.insert({std::lround(m.x / merge), std::lround(m.y / merge)}).second)
                continue;
            out.push_back(m);
            viewpoints.push_back(m);
        }
    }
    return out;
}

std::vector<TPoint2D> Eliminator::candidates(const std::vector<size_t>& live, const Region& region,
                                             const TPoint2D& from, size_t step,
                                             ProbeStrategy strategy, double chordSpacing,
                                             int perChord) const {
    std::vector<TPoint2D> out;
    const double clearance = options_.clearance;
    switch (strategy) {
        case ProbeStrategy::VisibilityCells:
            return chordCandidates(region, chordSpacing, perChord);
        case ProbeStrategy::Windows:
            return windowCandidates(region, from);
        case ProbeStrategy::Triangulation: {
            // seed 002 algorithm 3, step 7: edge midpoints and centroids of the map's
            // triangles, placed at the origin hypothesis.
            const TPoint2D origin = hypotheses_[live.front()];
            for (int t = 0; t < (int)T_.triangles().size(); ++t) {
                const auto& tri = T_[t];
                if (!tri.inside) continue;
                const TPoint2D &a = T_.point(tri.v[0]), &b = T_.point(tri.v[1]),
                               &c = T_.point(tri.v[2]);
                for (const TPoint2D p :
                     {(a + b + c) * (1.0 / 3), (a + b) * 0.5, (b + c) * 0.5, (c + a) * 0.5})
                    if (region.clear(p - origin, clearance)) out.push_back(p - origin);
            }
            std::sort(out.begin(), out.end(), [](const TPoint2D& a, const TPoint2D& b) {
                return a.x < b.x || (a.x == b.x && a.y < b.y);
            });
            out.erase(std::unique(out.begin(), out.end()), out.end());  // shared edges
            break;
        }
        case ProbeStrategy::Randomized: {
            // Algorithm 2 (Rao-Dudek-Whitesides): X uniform points of OI, seeded per step.
            std::mt19937 rng(options_.seed * 2654435761u + (uint32_t)step);
            std::uniform_real_distribution<double> ux(region.polygon.min().x,
                                                      region.polygon.max().x);
            std::uniform_real_distribution<double> uy(region.polygon.min().y,
                                                      region.polygon.max().y);
            const size_t want = (size_t)options_.randomPoints;
            for (size_t tries = 0; out.size() < want && tries < 1000 * want; ++tries) {
                const TPoint2D p{ux(rng), uy(rng)};
                if (region.clear(p, clearance)) out.push_back(p);
            }
            break;
        }
    }
    return out;
}

std::vector<TPoint2D> Eliminator::everyCandidate(const std::vector<size_t>& live,
                                                 const Region& region, const TPoint2D& at,
                                                 double spacing, int perChord) const {
    std::vector<TPoint2D> out;
    for (const auto strategy : {ProbeStrategy::VisibilityCells, ProbeStrategy::Randomized,
                                ProbeStrategy::Triangulation, ProbeStrategy::Windows}) {
        const auto more = candidates(live, region, at, 0, strategy, spacing, perChord);
        out.insert(out.end(), more.begin(), more.end());
    }
    for (const auto& more : {mapChordCandidates(live, region, spacing, perChord),
                             mapWindowCandidates(live, region, at)})
        out.insert(out.end(), more.begin(), more.end());
    return out;
}

}  // namespace mrloc::polymap
