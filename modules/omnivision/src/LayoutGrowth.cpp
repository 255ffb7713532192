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

Layout LayoutGrower::emptyLayout() const {
    Layout layout;
    layout.placed.assign(size_t(n_), 0);
    layout.p.assign(size_t(n_), Vec2::Zero());
    layout.heading.assign(size_t(n_), 0);
    layout.labels.resize(size_t(n_));
    for (int r = 0; r < n_; ++r) layout.labels[size_t(r)].assign(table_.view(r).size(), -1);
    return layout;
}

/** Places a seed triangle with |r0 r1| = 1; false if it is degenerate. */
bool LayoutGrower::placeSeed(const Seed& seed, Layout& layout) const {
    if (seed.pair) return placePair(seed, layout);
    std::array<double, 3> theta{};
    for (size_t v = 0; v < 3; ++v) {
        theta[v] = signedAngle(table_.view(seed.r[v]), seed.image[v][0], seed.image[v][1]);
        if (theta[v] <= 1e-6 || theta[v] >= M_PI) return false;
    }
    const double third = M_PI - theta[0] - theta[1];
    if (third < 1e-6) return false;
    layout = emptyLayout();
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

/** Places a pair seed at (0, 0) and (1, 0); false if both are one robot. */
bool LayoutGrower::placePair(const Seed& seed, Layout& layout) const {
    const int i = seed.r[0], j = seed.r[1];
    if (i == j) return false;
    layout = emptyLayout();
    layout.p[size_t(j)] = {1, 0};
    for (const int r : {i, j}) layout.placed[size_t(r)] = 1, layout.order.push_back(r);
    layout.labels[size_t(i)][size_t(seed.image[0][0])] = j;
    layout.labels[size_t(j)][size_t(seed.image[1][1])] = i;
    for (const int r : {i, j}) layout.heading[size_t(r)] = fitHeading(layout, r);
    layout.scale = 1;
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
                                                size_t minRays, size_t minSeen,
                                                Round& round) const {
    std::vector<Candidate> out, points;
    std::vector<std::pair<int, int>> rays;
    const double sigma2 = std::pow(o_.bearingTolerance / kSigmasPerTolerance, 2);
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
            Vec2 at = layout.p[size_t(s1)] + t1 * u1;
            rays.assign({{s1, int(c)}, {s2, d}});
            // The point's uncertainty from its rays' bearing noise (a ray d away errs by
            // d sigma across it), refined with every ray that confirms it: a point where two
            // rays meet at a narrow angle is uncertain along them, and the bearings it
            // predicts for the other robots are only as good as it (their tolerance widens
            // by that, then narrows as rays are added).
            LineMeeting meeting;
            const auto addRay = [&](int s, double angle, double dist) {
                meeting.add(layout.p[size_t(s)], angle, 1 / (dist * dist * sigma2));
            };
            addRay(s1, std::atan2(u1.y(), u1.x()), t1);
            addRay(s2, std::atan2(u2.y(), u2.x()), t2);
            Eigen::Matrix2d cov = meeting.information().inverse();
            // Every other placed robot that sees the point confirms it. A chance meeting
            // of two rays is confirmed by few: stop checking once misses outweigh hits,
            // unless the cameras' range bounds the checks. There a true point misses most
            // of the placed robots in range, hidden by nearer bands, and was dropped after
            // its first few misses (measured in occluded scenes at N = 75 and 0.02 deg:
            // 4 wrong labels and 3 scenes under 90 % labelled, none with no early stop).
            size_t misses = 0, checks = 0;
            for (int s : layout.order) {
                if (s == s1 || s == s2) continue;
                const Vec2 to = at - layout.p[size_t(s)];
                const double dist = to.norm();
                if (dist > round.reach) continue;  // out of its camera's range
                const Vec2 across = Vec2(-to.y(), to.x()) / std::max(dist, 1e-9);
                const double spread = std::sqrt(across.dot(cov * across)) / std::max(dist, 1e-9);
                if (spread > kMaxSpread * o_.bearingTolerance) continue;  // it cannot tell
                ++checks;
                const double t =
                    std::max(tolAt(layout, dist), std::hypot(o_.bearingTolerance, 4 * spread));
                const double b = std::atan2(to.y(), to.x()) - layout.heading[size_t(s)];
                if (const int img = table_.findImage(lab, s, b, t); img >= 0) {
                    rays.push_back({s, img});
                    addRay(s, layout.heading[size_t(s)] + table_.bearing(s, img), dist);
                    if (const auto better = meeting.solve()) at = *better;
                    cov = meeting.information().inverse();
                } else if (++misses > 2 * (rays.size() - 2) + kMissSlack && !round.bounded) {
                    break;
                }
            }
            if (rays.size() < minRays) continue;
            maxRays = std::max(maxRays, rays.size());
            Candidate cand;
            cand.at = at;
            cand.raysIn = rays;
            cand.rayChecks = checks;
            points.push_back(std::move(cand));
        }
    }
    // Only points about as well confirmed as the best are worth identifying; while the
    // layout is small, only those all placed robots see but one (growOnce's rule).
    const bool small = layout.order.size() < kSmallLayout;
    for (auto& cand : points) {
        if (small ? cand.raysIn.size() + 1 < maxRays : 2 * cand.raysIn.size() < maxRays) continue;
        const auto again =
            std::count_if(cand.raysIn.begin(), cand.raysIn.end(),
                          [&](const auto& ray) { return round.claimed.count(ray) > 0; });
        // Found from another pair; not from a pair seed's two robots, whose points have two
        // rays each: chance points identified first claimed both rays of every true one.
        if (layout.order.size() > 2 && 2 * size_t(again) > cand.raysIn.size()) continue;
        refinePoint(layout, cand);
        const size_t before = out.size();
        identifyRobot(layout, cand, minSeen, out);
        if (out.size() > before) round.claimed.insert(cand.raysIn.begin(), cand.raysIn.end());
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
            k.rayChecks = c.rayChecks;
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

bool LayoutGrower::conflicts(const Layout& layout, const Candidate& c, bool bounded) {
    if (layout.placed[size_t(c.robot)]) return true;
    for (const auto& [s, img] : c.raysIn) {
        const int w = layout.labels[size_t(s)][size_t(img)];
        if (w < 0) continue;
        // w was placed this round on an image that was free when c was found: the image
        // shows the nearer of the two (relabel's rule), whose band hides the other
        const double toPoint = (c.at - layout.p[size_t(s)]).norm();
        if (!bounded || (layout.p[size_t(w)] - layout.p[size_t(s)]).norm() <= kInFront * toPoint)
            return true;
    }
    return false;
}

void LayoutGrower::sortByEvidence(std::vector<Candidate>& found) {
    std::stable_sort(found.begin(), found.end(), [](const Candidate& a, const Candidate& b) {
        if (a.evidence() != b.evidence()) return a.evidence() > b.evidence();
        return a.residual < b.residual;
    });
}

double LayoutGrower::sightReach(const Layout& layout) const {
    double longest = 0;
    size_t sights = 0;
    for (int u : layout.order)
        for (int w : layout.labels[size_t(u)])
            if (w >= 0 && layout.placed[size_t(w)]) {
                longest = std::max(longest, (layout.p[size_t(u)] - layout.p[size_t(w)]).norm());
                ++sights;
            }
    const size_t k = layout.order.size();
    return double(sights) >= 0.9 * double(k * (k - 1)) ? INFINITY : longest * kReachMargin;
}

bool LayoutGrower::rangeBounded(const Layout& layout, double reach) {
    if (std::isinf(reach)) return false;
    for (int u : layout.order)
        for (int w : layout.order)
            if ((layout.p[size_t(u)] - layout.p[size_t(w)]).norm() > reach) return true;
    return false;
}

/** One round: the candidates from the first anchor pair that yields any.
 *  - With the seed alone, the largest group of candidates that all see each other
 *    (placeMutualGroup): three robots confirm a point too weakly.
 *  - While the layout is small, only a candidate every placed robot agrees with (but
 *    for one pair that cannot see each other).
 *  - Later, every candidate whose agreement is beyond chance (significant), best first. */
bool LayoutGrower::growOnce(Layout& layout, size_t anchorGroups) const {
    const size_t placed = layout.order.size();
    // Anchor pairs: those among the first few placed robots together, then pairs of the
    // robots with most unlabeled images (they see what is left), one pair at a time.
    std::vector<std::vector<std::pair<int, int>>> groups(1);
    for (size_t a = 0; a < std::min(placed, kAnchors); ++a)
        for (size_t b = a + 1; b < std::min(placed, kAnchors); ++b)
            groups[0].push_back({layout.order[a], layout.order[b]});
    if (placed <= 3) groups[0].resize(1);      // a true seed finds its fourth from one pair
    std::vector<std::pair<size_t, int>> open;  // (unlabeled images, robot)
    for (int r : layout.order) {
        const auto& lab = layout.labels[size_t(r)];
        if (const auto u = size_t(std::count(lab.begin(), lab.end(), -1)); u > 0)
            open.push_back({u, r});
    }
    std::stable_sort(open.begin(), open.end(), std::greater<>());
    for (size_t a = 0; a < open.size(); ++a)
        for (size_t b = a + 1; b < open.size() && groups.size() < anchorGroups; ++b)
            groups.push_back({{open[a].second, open[b].second}});
    const double reach = sightReach(layout);
    const bool bounded = rangeBounded(layout, reach);
    for (size_t gi = 0; gi < groups.size() && gi < anchorGroups; ++gi) {
        const auto& group = groups[gi];
        std::vector<Candidate> found;
        Round round;
        round.reach = reach;
        round.bounded = bounded;
        for (const auto& [s1, s2] : group) {
            // a pair seed's candidates are seen by, and see, its two robots only
            const size_t least = std::min<size_t>(3, placed);
            auto more = candidates(layout, s1, s2, least, least, round);
            found.insert(found.end(), std::make_move_iterator(more.begin()),
                         std::make_move_iterator(more.end()));
        }
        if (found.empty()) continue;
        sortByEvidence(found);
        if (placed <= 3) {
            if (placeMutualGroup(layout, found)) return true;
            continue;
        }
        if (placed < kSmallLayout) {  // all agree, but for one pair hidden from each other
            if (found.front().evidence() + 2 < 2 * placed) continue;
            place(layout, found.front());
            return true;
        }
        // A robot must agree with the layout beyond chance: chance agreement grows with
        // the images per view (N), true agreement with the robots placed.
        bool any = false;
        for (const auto& c : found) {
            const bool mutual =
                2 * c.seen.size() >= c.raysIn.size() && 2 * c.raysIn.size() >= c.seen.size();
            if (c.evidence() < kMinEvidence || !significant(c) || !mutual ||
                conflicts(layout, c, bounded))
                continue;
            place(layout, c);
            any = true;
        }
        if (any) return true;
    }
    return false;
}

bool LayoutGrower::significant(const Candidate& c) const {
    const double m = double(c.checks()), h = double(c.hits());  // h <= m
    if (h < 1) return false;
    // the binomial tail P(X >= h), bounded by C(m, h) p^h
    const double logTail =
        std::lgamma(m + 1) - std::lgamma(h + 1) - std::lgamma(m - h + 1) + h * std::log(chance_);
    return logTail < std::log(0.01) - 4 * std::log(double(std::max(n_, 2)));
}

double LayoutGrower::chancePerCheck(const ImageTable& table, const SearchOptions& o) {
    size_t images = 0;
    for (int r = 0; r < table.robots(); ++r) images += table.view(r).size();
    const double perView = double(images) / std::max(1, table.robots());
    return std::min(0.5, perView * 4 * o.bearingTolerance / (2 * M_PI));
}

/** From the seed alone a point is confirmed by three robots, too few to tell a true robot
 *  from chance once N is large (at N = 100 some 7,000 candidates for 97 robots, about 60
 *  robots per point). But true candidates see each other: robot a has an image where its
 *  point predicts b's point, and b one towards a's, which a chance candidate does with few.
 *  The largest group of candidates that all see each other (greedy, the best connected
 *  first; one candidate per robot, no image twice) is placed at once when it is large
 *  enough to be beyond chance (at most kMinGroup robots). Two passes:
 *  - the best kPerRobot candidates of each robot (by evidence, then residual), each one's
 *    degree the candidates it sees that see it back: enough where few candidates share a
 *    point (sparse or occluded swarms);
 *  - else every candidate, each one's degree the points it sees that see it back (some
 *    candidate there looks towards it): one robot stands at a point however many chance
 *    candidates share it, so a true candidate's degree is the true points it sees, a chance
 *    one's the few its images hit by accident. At N = 100 the true candidate is rarely
 *    among a robot's best three. */
bool LayoutGrower::placeMutualGroup(Layout& layout, const std::vector<Candidate>& all) const {
    // A swarm with fewer robots left than kMinGroup (which may not all see each other):
    // one robot at a time, as every placed robot agrees with it (growOnce's small rule).
    size_t left = 0;
    for (int r = 0; r < n_; ++r) left += !layout.placed[size_t(r)] && table_.view(r).size() >= 2;
    // The smallest group beyond chance: g candidates that all see each other pass g (g - 1)
    // bearing checks, each by chance with probability chance_, among about k^2 pairs
    // tried: chance_^(g (g - 1)) k^2 under 1e-6.
    const auto smallestGroup = [&](size_t k) {
        if (left < kMinGroup) return size_t(1);
        size_t g = 2;
        while (g<kMinGroup&& double(g * (g - 1)) * std::log(chance_) + 2 * std::log(double(k) + 1)>
                   std::log(1e-6))
            ++g;
        return g;
    };
    const auto seesPoint = [&](const Candidate& a, const Vec2& at) {
        const Vec2 d = at - a.at;
        return d.norm() > 1e-3 * layout.scale &&
               table_.findImage({}, a.robot, std::atan2(d.y(), d.x()) - a.heading,
                                tolAt(layout, d.norm())) >= 0;
    };
    // The greedy group over `found`, highest degree first; placed if large enough.
    const auto placeGroup = [&](const std::vector<Candidate>& found,
                                const std::vector<size_t>& degree, size_t minGroup,
                                const auto& mutual) {
        std::vector<size_t> order(found.size());
        for (size_t i = 0; i < order.size(); ++i) order[i] = i;
        std::stable_sort(order.begin(), order.end(),
                         [&](size_t a, size_t b) { return degree[a] > degree[b]; });
        std::vector<size_t> group;
        std::set<std::pair<int, int>> used;  // one image cannot show two robots
        for (size_t c : order) {
            if (degree[c] + 1 < minGroup) break;
            if (!std::all_of(group.begin(), group.end(), [&](size_t g) { return mutual(c, g); }) ||
                std::any_of(found[c].raysIn.begin(), found[c].raysIn.end(),
                            [&](const auto& ray) { return used.count(ray) > 0; }))
                continue;
            group.push_back(c);
            used.insert(found[c].raysIn.begin(), found[c].raysIn.end());
        }
        if (group.size() < minGroup) return false;
        for (size_t g : group) place(layout, found[g]);
        return true;
    };

    // 1. The best few per robot, degrees over candidates (all is sorted by evidence).
    {
        std::vector<Candidate> found;
        std::vector<size_t> perRobot(size_t(n_), 0);
        for (const auto& c : all)
            if (perRobot[size_t(c.robot)]++ < kPerRobot) found.push_back(c);
        const size_t k = found.size();
        std::vector<std::vector<char>> sees(k, std::vector<char>(k, 0));
        std::vector<size_t> degree(k, 0);
        for (size_t a = 0; a < k; ++a)
            for (size_t b = a + 1; b < k; ++b)
                if (found[a].robot != found[b].robot && seesPoint(found[a], found[b].at) &&
                    seesPoint(found[b], found[a].at))
                    sees[a][b] = sees[b][a] = 1, ++degree[a], ++degree[b];
        const size_t minGroup = smallestGroup(k);
        if (k >= minGroup &&
            placeGroup(found, degree, minGroup, [&](size_t a, size_t b) { return sees[a][b]; }))
            return true;
    }
    // 2. Every candidate, degrees over points.
    const size_t k = all.size();
    const size_t minGroup = smallestGroup(k);
    if (k < minGroup) return false;
    std::map<std::vector<std::pair<int, int>>, size_t> pointIndex;
    std::vector<Vec2> points;
    std::vector<size_t> pointOf(k);
    for (size_t c = 0; c < k; ++c) {
        const auto [it, added] = pointIndex.emplace(all[c].raysIn, points.size());
        if (added) points.push_back(all[c].at);
        pointOf[c] = it->second;
    }
    const size_t m = points.size();
    // sees[c][q]: candidate c has an image towards point q; the directions and tolerances
    // between points are shared by the candidates at a point.
    std::vector<std::vector<double>> towards(m, std::vector<double>(m, 0)), tol = towards;
    for (size_t p = 0; p < m; ++p)
        for (size_t q = 0; q < m; ++q) {
            const Vec2 d = points[q] - points[p];
            towards[p][q] = std::atan2(d.y(), d.x());
            tol[p][q] = d.norm() <= 1e-3 * layout.scale ? -1 : tolAt(layout, d.norm());
        }
    std::vector<std::vector<char>> sees(k, std::vector<char>(m, 0));
    for (size_t c = 0; c < k; ++c) {
        const size_t p = pointOf[c];
        for (size_t q = 0; q < m; ++q)
            sees[c][q] =
                tol[p][q] > 0 &&
                table_.findImage({}, all[c].robot, towards[p][q] - all[c].heading, tol[p][q]) >= 0;
    }
    // back[q][p]: some candidate at q sees p.
    std::vector<std::vector<char>> back(m, std::vector<char>(m, 0));
    for (size_t c = 0; c < k; ++c)
        for (size_t p = 0; p < m; ++p) back[pointOf[c]][p] |= sees[c][p];
    std::vector<size_t> degree(k, 0);
    for (size_t c = 0; c < k; ++c)
        for (size_t q = 0; q < m; ++q) degree[c] += sees[c][q] && back[q][pointOf[c]];
    return placeGroup(all, degree, minGroup, [&](size_t a, size_t b) {
        return all[a].robot != all[b].robot && sees[a][pointOf[b]] && sees[b][pointOf[a]];
    });
}

void LayoutGrower::growAll(Layout& layout, size_t anchorGroups) const {
    while (growOnce(layout, anchorGroups)) {
        polish(layout, 2);
        relabel(layout);
    }
}

Layout LayoutGrower::growFrom(const Seed& seed, bool& ok) const {
    Layout layout;
    ok = placeSeed(seed, layout);
    if (!ok) return layout;
    growAll(layout);
    for (int pass = 0; pass < 2; ++pass) {
        polish(layout, 3);
        relabel(layout);
    }
    // robots that do not fit out, one at a time (the worst first), then grown again
    for (size_t pruned = 0; pruned < size_t(n_) && layout.order.size() > 3;) {
        const int worst = worstFit(layout);
        if (worst < 0) break;
        unplace(layout, worst);
        ++pruned;
        polish(layout, 2);
        relabel(layout);
        if (worstFit(layout) < 0) growAll(layout);
    }
    keepMutual(layout);
    return layout;
}

void LayoutGrower::growFreed(Layout& layout) const {
    growAll(layout, rangeBounded(layout, sightReach(layout)) ? size_t(-1) : kAnchorGroups);
    keepMutual(layout);
}

/** A label u -> w stands only if w has a label -> u: a robot placed a little off its true
 *  place (on rays that met by chance near it) keeps some images that fit it, but the
 *  others' images of it no longer match and lose their labels. Visibility is mutual
 *  (a camera's range, a marker in the line of sight), so a true label rarely lacks its
 *  reverse. */
void LayoutGrower::keepMutual(Layout& layout) {
    std::vector<std::vector<char>> sees(layout.labels.size(),
                                        std::vector<char>(layout.labels.size(), 0));
    for (size_t u = 0; u < layout.labels.size(); ++u)
        for (int w : layout.labels[u])
            if (w >= 0) sees[u][size_t(w)] = 1;
    for (size_t u = 0; u < layout.labels.size(); ++u)
        for (int& w : layout.labels[u])
            if (w >= 0 && !sees[size_t(w)][u]) w = -1;
}

}  // namespace mrloc::omnivision::seedgrow
