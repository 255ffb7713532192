// Seed and grow: placing a seed triangle and growing the layout where rays meet.
#include "LayoutGrowth.h"

#include <map>
#include <set>
#include <tuple>

namespace mrloc::omnivision::seedgrow {

/** Tolerance of a bearing predicted to a point `dist` away: the layout's positions err
 *  by about a bearing tolerance times its scale, which matters more for near points. */
double LayoutGrower::tolAt(const Layout& layout, double dist) const {
    return o_.bearingTolerance * std::min(2.0, 1 + 0.5 * layout.scale / std::max(dist, 1e-9));
}

/** Places a seed triangle with |r0 r1| = 1; false if it is degenerate. */
bool LayoutGrower::placeSeed(const Seed& seed, Layout& layout) const {
    std::array<double, 3> theta{};
    for (size_t v = 0; v < 3; ++v) {
        theta[v] = signedAngle(table_.view(seed.r[v]), seed.image[v][0], seed.image[v][1]);
        if (theta[v] <= 1e-6 || theta[v] >= M_PI) return false;
    }
    const double third = M_PI - theta[0] - theta[1];
    if (third < 1e-6) return false;
    layout = Layout{};
    layout.placed.assign(size_t(n_), 0);
    layout.p.assign(size_t(n_), Vec2::Zero());
    layout.heading.assign(size_t(n_), 0);
    layout.labels.resize(size_t(n_));
    for (int r = 0; r < n_; ++r) layout.labels[size_t(r)].assign(table_.view(r).size(), -1);
    layout.p[size_t(seed.r[1])] = {1, 0};
    layout.p[size_t(seed.r[2])] = std::sin(theta[1]) / std::sin(third) * unit(theta[0]);
    for (size_t v = 0; v < 3; ++v) {
        const int r = seed.r[v];
        layout.placed[size_t(r)] = 1;
        layout.order.push_back(r);
        layout.labels[size_t(r)][size_t(seed.image[v][0])] = seed.r[(v + 1) % 3];
        layout.labels[size_t(r)][size_t(seed.image[v][1])] = seed.r[(v + 2) % 3];
    }
    for (int r : seed.r) layout.heading[size_t(r)] = fitHeading(layout, r);
    layout.scale = (1 + layout.p[size_t(seed.r[2])].norm() +
                    (layout.p[size_t(seed.r[2])] - Vec2(1, 0)).norm()) /
                   3;
    return true;
}

/** The heading that best explains robot r's labeled images of placed robots. */
double LayoutGrower::fitHeading(const Layout& layout, int r) const {
    double sx = 0, sy = 0;
    for (size_t img = 0; img < layout.labels[size_t(r)].size(); ++img)
        if (const int who = layout.labels[size_t(r)][img]; who >= 0 && layout.placed[size_t(who)]) {
            const double h =
                direction(layout.p[size_t(r)], layout.p[size_t(who)]) - table_.bearing(r, int(img));
            sx += std::cos(h), sy += std::sin(h);
        }
    return std::atan2(sy, sx);
}

/** Robots that could stand where a ray of s1 meets a ray of s2. */
std::vector<Candidate> LayoutGrower::candidates(const Layout& layout, int s1, int s2,
                                                size_t minRays, size_t minSeen) const {
    std::vector<Candidate> out, points;
    std::vector<std::pair<int, int>> rays;
    size_t maxRays = 0;
    const auto& lab = layout.labels;
    std::vector<std::pair<int, Vec2>> rays2;  // s2's unlabeled images and their rays
    for (size_t d = 0; d < lab[size_t(s2)].size(); ++d)
        if (lab[size_t(s2)][d] < 0)
            rays2.push_back(
                {int(d), unit(layout.heading[size_t(s2)] + table_.bearing(s2, int(d)))});
    for (size_t c = 0; c < lab[size_t(s1)].size(); ++c) {
        if (lab[size_t(s1)][c] >= 0) continue;
        const Vec2 u1 = unit(layout.heading[size_t(s1)] + table_.bearing(s1, int(c)));
        for (const auto& [d, u2] : rays2) {
            const double den = cross(u1, u2);
            if (std::abs(den) < kMinRayAngle) continue;  // nearly parallel: ill-conditioned
            const Vec2 w = layout.p[size_t(s2)] - layout.p[size_t(s1)];
            const double t1 = cross(w, u2) / den, t2 = cross(w, u1) / den;
            if (t1 <= 1e-9 || t2 <= 1e-9) continue;  // the rays meet behind a camera
            const Vec2 at = layout.p[size_t(s1)] + t1 * u1;
            rays.assign({{s1, int(c)}, {s2, d}});
            // Every other placed robot that sees the point confirms it. A chance meeting
            // of two rays is confirmed by few: stop checking once misses outweigh hits.
            size_t misses = 0;
            for (int s : layout.order) {
                if (s == s1 || s == s2) continue;
                const double b = direction(layout.p[size_t(s)], at) - layout.heading[size_t(s)];
                const double t = tolAt(layout, (at - layout.p[size_t(s)]).norm());
                if (const int img = table_.findImage(lab, s, b, t); img >= 0)
                    rays.push_back({s, img});
                else if (++misses > 2 * (rays.size() - 2) + kMissSlack)
                    break;
            }
            if (rays.size() < minRays) continue;
            maxRays = std::max(maxRays, rays.size());
            Candidate cand;
            cand.at = at;
            cand.raysIn = rays;
            points.push_back(std::move(cand));
        }
    }
    // Only points about as well confirmed as the best are worth identifying.
    for (auto& cand : points) {
        if (2 * cand.raysIn.size() < maxRays) continue;
        refinePoint(layout, cand);
        identifyRobot(layout, cand, minSeen, out);
    }
    return out;
}

/** Least-squares meeting point of the rays into a candidate. */
void LayoutGrower::refinePoint(const Layout& layout, Candidate& c) const {
    LineMeeting m;
    for (const auto& [s, img] : c.raysIn)
        m.add(layout.p[size_t(s)], layout.heading[size_t(s)] + table_.bearing(s, img));
    if (const auto at = m.solve()) c.at = *at;
}

/** Which unplaced robot sees the placed robots of c.raysIn from c.at, at the bearings
 *  that point predicts; appends every robot that does (with at least minSeen). */
void LayoutGrower::identifyRobot(const Layout& layout, const Candidate& c, size_t minSeen,
                                 std::vector<Candidate>& out) const {
    std::vector<double> dir, tol;
    for (const auto& [s, img] : c.raysIn) {
        dir.push_back(direction(c.at, layout.p[size_t(s)]));
        tol.push_back(tolAt(layout, (c.at - layout.p[size_t(s)]).norm()));
    }
    const double delta = wrapToPi(dir[1] - dir[0]);
    for (int l = 0; l < n_; ++l) {
        if (layout.placed[size_t(l)] || table_.view(l).size() < 2) continue;
        Candidate best;
        std::vector<std::pair<int, int>> seen;
        table_.forPairsNear(l, delta, tol[0] + tol[1], [&](int e, int f) {
            // Heading from the two anchors (the mean of what each implies, without trig:
            // the hot loop), then every other ray.
            const double h0 = dir[0] - table_.bearing(l, e);
            const double h = h0 + 0.5 * wrapToPi(dir[1] - table_.bearing(l, f) - h0);
            seen.clear();
            size_t misses = 0;  // a wrong robot fails fast: stop once misses outweigh hits
            for (size_t i = 0; i < c.raysIn.size(); ++i) {
                const int img = table_.findImage({}, l, dir[i] - h, tol[i]);
                const bool fresh =
                    img >= 0 && std::none_of(seen.begin(), seen.end(),
                                             [&](const auto& x) { return x.second == img; });
                if (fresh)
                    seen.push_back({c.raysIn[i].first, img});
                else if (++misses > 2 * seen.size() + kMissSlack)
                    return;
            }
            if (seen.size() < minSeen) return;
            const size_t evidence = c.raysIn.size() + seen.size();
            if (best.robot >= 0 && evidence < best.evidence()) return;
            Candidate k;
            k.robot = l;
            k.at = c.at;
            k.heading = h;
            k.raysIn = c.raysIn;
            k.seen = seen;
            k.residual = residual(layout, k);
            if (best.robot < 0 || k.evidence() > best.evidence() ||
                (k.evidence() == best.evidence() && k.residual < best.residual))
                best = std::move(k);
        });
        if (best.robot >= 0) out.push_back(std::move(best));
    }
}

double LayoutGrower::residual(const Layout& layout, const Candidate& c) const {
    double r = 0;
    for (const auto& [s, img] : c.raysIn)
        r += std::pow(wrapToPi(direction(layout.p[size_t(s)], c.at) - layout.heading[size_t(s)] -
                               table_.bearing(s, img)),
                      2);
    for (const auto& [s, img] : c.seen)
        r += std::pow(wrapToPi(direction(c.at, layout.p[size_t(s)]) - c.heading -
                               table_.bearing(c.robot, img)),
                      2);
    return r;
}

void LayoutGrower::place(Layout& layout, const Candidate& c) {
    layout.placed[size_t(c.robot)] = 1;
    layout.p[size_t(c.robot)] = c.at;
    layout.heading[size_t(c.robot)] = c.heading;
    layout.order.push_back(c.robot);
    for (const auto& [s, img] : c.raysIn) layout.labels[size_t(s)][size_t(img)] = c.robot;
    for (const auto& [s, img] : c.seen) layout.labels[size_t(c.robot)][size_t(img)] = s;
}

bool LayoutGrower::conflicts(const Layout& layout, const Candidate& c) {
    if (layout.placed[size_t(c.robot)]) return true;
    for (const auto& [s, img] : c.raysIn)
        if (layout.labels[size_t(s)][size_t(img)] >= 0) return true;
    return false;
}

void LayoutGrower::sortByEvidence(std::vector<Candidate>& found) {
    std::stable_sort(found.begin(), found.end(), [](const Candidate& a, const Candidate& b) {
        if (a.evidence() != b.evidence()) return a.evidence() > b.evidence();
        return a.residual < b.residual;
    });
}

/** One round: the candidates from the first anchor pair that yields any.
 *  - With the seed alone, a fourth robot is taken only if a fifth then fits with all
 *    four (one step of lookahead): three robots confirm a point too weakly.
 *  - While the layout is small, only a candidate every placed robot agrees with (but
 *    for one pair that cannot see each other).
 *  - Later, every candidate with at least half the round's best evidence, best first. */
bool LayoutGrower::growOnce(Layout& layout) const {
    const size_t placed = layout.order.size();
    // Anchor pairs: those among the first few placed robots together, then pairs of the
    // robots with most unlabeled images (they see what is left), one pair at a time.
    std::vector<std::vector<std::pair<int, int>>> groups(1);
    for (size_t a = 0; a < std::min(placed, kAnchors); ++a)
        for (size_t b = a + 1; b < std::min(placed, kAnchors); ++b)
            groups[0].push_back({layout.order[a], layout.order[b]});
    if (placed == 3) groups[0].resize(1);      // a true seed finds its fourth from one pair
    std::vector<std::pair<size_t, int>> open;  // (unlabeled images, robot)
    for (int r : layout.order) {
        const auto& lab = layout.labels[size_t(r)];
        if (const auto u = size_t(std::count(lab.begin(), lab.end(), -1)); u > 0)
            open.push_back({u, r});
    }
    std::stable_sort(open.begin(), open.end(), std::greater<>());
    for (size_t a = 0; a < open.size(); ++a)
        for (size_t b = a + 1; b < open.size() && groups.size() < kAnchorGroups; ++b)
            groups.push_back({{open[a].second, open[b].second}});
    for (size_t gi = 0; gi < groups.size() && gi < kAnchorGroups; ++gi) {
        const auto& group = groups[gi];
        std::vector<Candidate> found;
        for (const auto& [s1, s2] : group) {
            auto more = candidates(layout, s1, s2, 3, 3);
            found.insert(found.end(), std::make_move_iterator(more.begin()),
                         std::make_move_iterator(more.end()));
        }
        if (found.empty()) continue;
        sortByEvidence(found);
        if (placed == 3) {
            for (size_t i = 0; i < found.size() && i < kLookahead; ++i) {
                Layout trial = layout;
                place(trial, found[i]);
                if (confirmed(trial)) {
                    layout = std::move(trial);
                    return true;
                }
            }
            continue;
        }
        if (placed < kSmallLayout) {  // all agree, but for one pair hidden from each other
            if (found.front().evidence() + 2 < 2 * placed) continue;
            place(layout, found.front());
            return true;
        }
        // A robot must agree with at least a quarter of the placed robots (rays in plus
        // robots seen >= half the layout): chance agreement grows with the layout, true
        // agreement grows faster.
        const size_t bar = std::max({kMinEvidence, placed / 2, 3 * found.front().evidence() / 4});
        bool any = false;
        for (const auto& c : found) {
            const bool mutual =
                2 * c.seen.size() >= c.raysIn.size() && 2 * c.raysIn.size() >= c.seen.size();
            if (c.evidence() < bar || !mutual || conflicts(layout, c)) continue;
            place(layout, c);
            any = true;
        }
        if (any) return true;
    }
    return false;
}

/** Whether some unplaced robot fits with every robot placed so far (one pair may be
 *  hidden from each other) and with the newest one in particular; or none is left. */
bool LayoutGrower::confirmed(const Layout& layout) const {
    const size_t k = layout.order.size();
    const int newest = layout.order.back();
    bool left = false;
    for (int r = 0; r < n_; ++r) left |= !layout.placed[size_t(r)] && table_.view(r).size() >= 2;
    if (!left) return true;
    const auto involves = [&](const Candidate& c) {
        for (const auto& [s, img] : c.raysIn)
            if (s == newest) return true;
        for (const auto& [s, img] : c.seen)
            if (s == newest) return true;
        return false;
    };
    for (size_t a = 0; a < 2; ++a)  // the seed's rays: the best known
        for (size_t b = a + 1; b < 3; ++b)
            for (const auto& c : candidates(layout, layout.order[a], layout.order[b], k - 1, k - 1))
                if (c.evidence() + 2 >= 2 * k && involves(c)) return true;
    return false;
}

Layout LayoutGrower::growFrom(const Seed& seed, bool& ok) const {
    Layout layout;
    ok = placeSeed(seed, layout);
    if (!ok) return layout;
    while (growOnce(layout)) polish(layout, 2);
    for (int pass = 0; pass < 2; ++pass) {
        polish(layout, 3);
        relabel(layout);
    }
    return layout;
}

}  // namespace mrloc::omnivision::seedgrow
