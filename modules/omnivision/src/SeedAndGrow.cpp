// Seed and grow: the fast triangle search and identification (see TriangleSearch.h).
#include <mrloc/omnivision/TriangleSearch.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <tuple>

namespace mrloc::omnivision {

namespace {

/** Wraps to (-pi, pi] for angles a few turns away at most: the hot loops call it often
 *  and mrpt::math::wrapToPi's fmod dominated their profile. */
inline double wrapToPi(double a) {
    while (a > M_PI) a -= 2 * M_PI;
    while (a <= -M_PI) a += 2 * M_PI;
    return a;
}
using Vec2 = Eigen::Vector2d;

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }
Vec2 unit(double angle) { return {std::cos(angle), std::sin(angle)}; }
double direction(const Vec2& from, const Vec2& to) {
    return std::atan2(to.y() - from.y(), to.x() - from.x());
}

/** The least-squares meeting point of lines, each through a point at a direction. */
class LineMeeting {
 public:
    void add(const Vec2& through, double angle) {
        const Vec2 normal(-std::sin(angle), std::cos(angle));
        A_ += normal * normal.transpose();
        b_ += normal * normal.dot(through);
    }
    /** None when the lines are (nearly) parallel. */
    std::optional<Vec2> solve() const {
        if (std::abs(A_.determinant()) <= 1e-12) return std::nullopt;
        return A_.ldlt().solve(b_);
    }

 private:
    Eigen::Matrix2d A_ = Eigen::Matrix2d::Zero();
    Eigen::Vector2d b_ = Eigen::Vector2d::Zero();
};

/** A triangle whose identities are fixed, counter-clockwise r[0] -> r[1] -> r[2]. At
 *  r[v], image[v][0] shows the next robot and image[v][1] the previous one, so that the
 *  signed angle from the first to the second is the interior angle. */
struct Seed {
    std::array<int, 3> r{};
    std::array<std::array<int, 2>, 3> image{};
};

/** A robot placed (up to scale) in the growing layout. */
struct Layout {
    std::vector<char> placed;
    std::vector<Vec2> p;
    std::vector<double> heading;
    Labels labels;
    std::vector<int> order;  ///< placement order
    double scale = 1;        ///< the seed triangle's mean side
};

/** A robot that might stand where the rays of placed robots meet. */
struct Candidate {
    int robot = -1;
    Vec2 at;
    double heading = 0;
    std::vector<std::pair<int, int>> raysIn;  ///< placed robot, its image of `robot`
    std::vector<std::pair<int, int>> seen;    ///< placed robot, `robot`'s image of it
    double residual = 0;                      ///< sum of squared bearing errors
    size_t evidence() const { return raysIn.size() + seen.size(); }
};

class Grower {
 public:
    Grower(const Snapshot& s, const SearchOptions& o) : s_(s), o_(o), n_(int(s.robots())) {
        pairs_.resize(size_t(n_));
        for (int r = 0; r < n_; ++r) {
            const auto& v = s_.views[size_t(r)];
            for (int e = 0; e < int(v.size()); ++e)
                for (int f = 0; f < int(v.size()); ++f)
                    if (e != f) pairs_[size_t(r)].push_back({signedAngle(v, e, f), e, f});
            std::sort(pairs_[size_t(r)].begin(), pairs_[size_t(r)].end(),
                      [](const PairAngle& a, const PairAngle& b) { return a.angle < b.angle; });
        }
    }

    /** Calls f(e, g) for every ordered pair of robot r's images whose signed angle is
     *  within tol of delta. */
    template <class F>
    void forPairsNear(int r, double delta, double tol, F&& f) const {
        const auto& ps = pairs_[size_t(r)];
        const auto scan = [&](double lo, double hi) {
            auto it = std::lower_bound(ps.begin(), ps.end(), lo,
                                       [](const PairAngle& p, double v) { return p.angle < v; });
            for (; it != ps.end() && it->angle <= hi; ++it) f(it->from, it->to);
        };
        scan(delta - tol, delta + tol);
        if (delta - tol < -M_PI) scan(delta - tol + 2 * M_PI, M_PI);
        if (delta + tol > M_PI) scan(-M_PI, delta + tol - 2 * M_PI);
    }

    /** The unlabeled image of robot r nearest the bearing b (robot frame), within tol. */
    int findImage(const Labels& labels, int r, double b, double tol) const {
        const auto& v = s_.views[size_t(r)].bearings;
        const size_t n = v.size();
        if (n == 0) return -1;
        b = wrapToPi(b);
        const size_t start = size_t(std::lower_bound(v.begin(), v.end(), b) - v.begin()) % n;
        int best = -1;
        double bestD = tol;
        const auto consider = [&](size_t i) {
            const double d = std::abs(wrapToPi(v[i] - b));
            if (d > tol) return false;
            if ((labels.empty() || labels[size_t(r)][i] < 0) && d <= bestD)
                best = int(i), bestD = d;
            return true;
        };
        for (size_t k = 0; k < n && consider((start + k) % n); ++k) {
        }
        for (size_t k = 1; k <= n && consider((start + n - k) % n); ++k) {
        }
        return best;
    }

    /** Tolerance of a bearing predicted to a point `dist` away: the layout's positions err
     *  by about a bearing tolerance times its scale, which matters more for near points. */
    double tolAt(const Layout& L, double dist) const {
        return o_.bearingTolerance * std::min(2.0, 1 + 0.5 * L.scale / std::max(dist, 1e-9));
    }

    double bearing(int r, int image) const { return s_.views[size_t(r)].bearings[size_t(image)]; }

    /** Places a seed triangle with |r0 r1| = 1; false if it is degenerate. */
    bool placeSeed(const Seed& seed, Layout& L) const {
        std::array<double, 3> theta{};
        for (size_t v = 0; v < 3; ++v) {
            theta[v] = signedAngle(s_.views[size_t(seed.r[v])], seed.image[v][0], seed.image[v][1]);
            if (theta[v] <= 1e-6 || theta[v] >= M_PI) return false;
        }
        const double third = M_PI - theta[0] - theta[1];
        if (third < 1e-6) return false;
        L = Layout{};
        L.placed.assign(size_t(n_), 0);
        L.p.assign(size_t(n_), Vec2::Zero());
        L.heading.assign(size_t(n_), 0);
        L.labels.resize(size_t(n_));
        for (int r = 0; r < n_; ++r) L.labels[size_t(r)].assign(s_.views[size_t(r)].size(), -1);
        L.p[size_t(seed.r[1])] = {1, 0};
        L.p[size_t(seed.r[2])] = std::sin(theta[1]) / std::sin(third) * unit(theta[0]);
        for (size_t v = 0; v < 3; ++v) {
            const int r = seed.r[v];
            L.placed[size_t(r)] = 1;
            L.order.push_back(r);
            L.labels[size_t(r)][size_t(seed.image[v][0])] = seed.r[(v + 1) % 3];
            L.labels[size_t(r)][size_t(seed.image[v][1])] = seed.r[(v + 2) % 3];
        }
        for (int r : seed.r) L.heading[size_t(r)] = fitHeading(L, r);
        L.scale =
            (1 + L.p[size_t(seed.r[2])].norm() + (L.p[size_t(seed.r[2])] - Vec2(1, 0)).norm()) / 3;
        return true;
    }

    /** The heading that best explains robot r's labeled images of placed robots. */
    double fitHeading(const Layout& L, int r) const {
        double sx = 0, sy = 0;
        for (size_t img = 0; img < L.labels[size_t(r)].size(); ++img)
            if (const int who = L.labels[size_t(r)][img]; who >= 0 && L.placed[size_t(who)]) {
                const double h = direction(L.p[size_t(r)], L.p[size_t(who)]) - bearing(r, int(img));
                sx += std::cos(h), sy += std::sin(h);
            }
        return std::atan2(sy, sx);
    }

    /** Robots that could stand where a ray of s1 meets a ray of s2. */
    std::vector<Candidate> candidates(const Layout& L, int s1, int s2, size_t minRays,
                                      size_t minSeen) const {
        std::vector<Candidate> out, points;
        std::vector<std::pair<int, int>> rays;
        size_t maxRays = 0;
        const auto& lab = L.labels;
        std::vector<std::pair<int, Vec2>> rays2;  // s2's unlabeled images and their rays
        for (size_t d = 0; d < lab[size_t(s2)].size(); ++d)
            if (lab[size_t(s2)][d] < 0)
                rays2.push_back({int(d), unit(L.heading[size_t(s2)] + bearing(s2, int(d)))});
        for (size_t c = 0; c < lab[size_t(s1)].size(); ++c) {
            if (lab[size_t(s1)][c] >= 0) continue;
            const Vec2 u1 = unit(L.heading[size_t(s1)] + bearing(s1, int(c)));
            for (const auto& [d, u2] : rays2) {
                const double den = cross(u1, u2);
                if (std::abs(den) < kMinRayAngle) continue;  // nearly parallel: ill-conditioned
                const Vec2 w = L.p[size_t(s2)] - L.p[size_t(s1)];
                const double t1 = cross(w, u2) / den, t2 = cross(w, u1) / den;
                if (t1 <= 1e-9 || t2 <= 1e-9) continue;  // the rays meet behind a camera
                const Vec2 at = L.p[size_t(s1)] + t1 * u1;
                rays.assign({{s1, int(c)}, {s2, d}});
                // Every other placed robot that sees the point confirms it. A chance meeting
                // of two rays is confirmed by few: stop checking once misses outweigh hits.
                size_t misses = 0;
                for (int s : L.order) {
                    if (s == s1 || s == s2) continue;
                    const double b = direction(L.p[size_t(s)], at) - L.heading[size_t(s)];
                    const double t = tolAt(L, (at - L.p[size_t(s)]).norm());
                    if (const int img = findImage(lab, s, b, t); img >= 0)
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
            refinePoint(L, cand);
            identifyRobot(L, cand, minSeen, out);
        }
        return out;
    }

    /** Least-squares meeting point of the rays into a candidate. */
    void refinePoint(const Layout& L, Candidate& c) const {
        LineMeeting m;
        for (const auto& [s, img] : c.raysIn)
            m.add(L.p[size_t(s)], L.heading[size_t(s)] + bearing(s, img));
        if (const auto at = m.solve()) c.at = *at;
    }

    /** Which unplaced robot sees the placed robots of c.raysIn from c.at, at the bearings
     *  that point predicts; appends every robot that does (with at least minSeen). */
    void identifyRobot(const Layout& L, const Candidate& c, size_t minSeen,
                       std::vector<Candidate>& out) const {
        std::vector<double> dir, tol;
        for (const auto& [s, img] : c.raysIn) {
            dir.push_back(direction(c.at, L.p[size_t(s)]));
            tol.push_back(tolAt(L, (c.at - L.p[size_t(s)]).norm()));
        }
        const double delta = wrapToPi(dir[1] - dir[0]);
        for (int l = 0; l < n_; ++l) {
            if (L.placed[size_t(l)] || s_.views[size_t(l)].size() < 2) continue;
            Candidate best;
            std::vector<std::pair<int, int>> seen;
            forPairsNear(l, delta, tol[0] + tol[1], [&](int e, int f) {
                // Heading from the two anchors (the mean of what each implies, without trig:
                // the hot loop), then every other ray.
                const double h0 = dir[0] - bearing(l, e);
                const double h = h0 + 0.5 * wrapToPi(dir[1] - bearing(l, f) - h0);
                seen.clear();
                size_t misses = 0;  // a wrong robot fails fast: stop once misses outweigh hits
                for (size_t i = 0; i < c.raysIn.size(); ++i) {
                    const int img = findImage({}, l, dir[i] - h, tol[i]);
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
                k.residual = residual(L, k);
                if (best.robot < 0 || k.evidence() > best.evidence() ||
                    (k.evidence() == best.evidence() && k.residual < best.residual))
                    best = std::move(k);
            });
            if (best.robot >= 0) out.push_back(std::move(best));
        }
    }

    double residual(const Layout& L, const Candidate& c) const {
        double r = 0;
        for (const auto& [s, img] : c.raysIn)
            r += std::pow(
                wrapToPi(direction(L.p[size_t(s)], c.at) - L.heading[size_t(s)] - bearing(s, img)),
                2);
        for (const auto& [s, img] : c.seen)
            r += std::pow(
                wrapToPi(direction(c.at, L.p[size_t(s)]) - c.heading - bearing(c.robot, img)), 2);
        return r;
    }

    static void place(Layout& L, const Candidate& c) {
        L.placed[size_t(c.robot)] = 1;
        L.p[size_t(c.robot)] = c.at;
        L.heading[size_t(c.robot)] = c.heading;
        L.order.push_back(c.robot);
        for (const auto& [s, img] : c.raysIn) L.labels[size_t(s)][size_t(img)] = c.robot;
        for (const auto& [s, img] : c.seen) L.labels[size_t(c.robot)][size_t(img)] = s;
    }

    static bool conflicts(const Layout& L, const Candidate& c) {
        if (L.placed[size_t(c.robot)]) return true;
        for (const auto& [s, img] : c.raysIn)
            if (L.labels[size_t(s)][size_t(img)] >= 0) return true;
        return false;
    }

    static void sortByEvidence(std::vector<Candidate>& cs) {
        std::stable_sort(cs.begin(), cs.end(), [](const Candidate& a, const Candidate& b) {
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
    bool growOnce(Layout& L) const {
        const size_t placed = L.order.size();
        // Anchor pairs: those among the first few placed robots together, then pairs of the
        // robots with most unlabeled images (they see what is left), one pair at a time.
        std::vector<std::vector<std::pair<int, int>>> groups(1);
        for (size_t a = 0; a < std::min(placed, kAnchors); ++a)
            for (size_t b = a + 1; b < std::min(placed, kAnchors); ++b)
                groups[0].push_back({L.order[a], L.order[b]});
        if (placed == 3) groups[0].resize(1);      // a true seed finds its fourth from one pair
        std::vector<std::pair<size_t, int>> open;  // (unlabeled images, robot)
        for (int r : L.order) {
            const auto& lab = L.labels[size_t(r)];
            if (const auto u = size_t(std::count(lab.begin(), lab.end(), -1)); u > 0)
                open.push_back({u, r});
        }
        std::stable_sort(open.begin(), open.end(), std::greater<>());
        for (size_t a = 0; a < open.size(); ++a)
            for (size_t b = a + 1; b < open.size() && groups.size() < kAnchorGroups; ++b)
                groups.push_back({{open[a].second, open[b].second}});
        for (size_t gi = 0; gi < groups.size() && gi < kAnchorGroups; ++gi) {
            const auto& group = groups[gi];
            std::vector<Candidate> cs;
            for (const auto& [s1, s2] : group) {
                auto more = candidates(L, s1, s2, 3, 3);
                cs.insert(cs.end(), std::make_move_iterator(more.begin()),
                          std::make_move_iterator(more.end()));
            }
            if (cs.empty()) continue;
            sortByEvidence(cs);
            if (placed == 3) {
                for (size_t i = 0; i < cs.size() && i < kLookahead; ++i) {
                    Layout trial = L;
                    place(trial, cs[i]);
                    if (confirmed(trial)) {
                        L = std::move(trial);
                        return true;
                    }
                }
                continue;
            }
            if (placed < kSmallLayout) {  // all agree, but for one pair hidden from each other
                if (cs.front().evidence() + 2 < 2 * placed) continue;
                place(L, cs.front());
                return true;
            }
            // A robot must agree with at least a quarter of the placed robots (rays in plus
            // robots seen >= half the layout): chance agreement grows with the layout, true
            // agreement grows faster.
            const size_t bar = std::max({kMinEvidence, placed / 2, 3 * cs.front().evidence() / 4});
            bool any = false;
            for (const auto& c : cs) {
                const bool mutual =
                    2 * c.seen.size() >= c.raysIn.size() && 2 * c.raysIn.size() >= c.seen.size();
                if (c.evidence() < bar || !mutual || conflicts(L, c)) continue;
                place(L, c);
                any = true;
            }
            if (any) return true;
        }
        return false;
    }

    /** Whether some unplaced robot fits with every robot placed so far (one pair may be
     *  hidden from each other) and with the newest one in particular; or none is left. */
    bool confirmed(const Layout& L) const {
        const size_t k = L.order.size();
        const int newest = L.order.back();
        bool left = false;
        for (int r = 0; r < n_; ++r)
            left |= !L.placed[size_t(r)] && s_.views[size_t(r)].size() >= 2;
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
                for (const auto& c : candidates(L, L.order[a], L.order[b], k - 1, k - 1))
                    if (c.evidence() + 2 >= 2 * k && involves(c)) return true;
        return false;
    }

    /** Re-fits every placed robot's position (least squares over the labeled rays into and
     *  out of it) and heading, so that errors do not pile up as the layout grows. */
    void polish(Layout& L, int sweeps) const {
        for (int it = 0; it < sweeps; ++it)
            for (size_t k = 2; k < L.order.size(); ++k) {  // the first two fix the frame
                const int r = L.order[k];
                LineMeeting m;
                for (int s : L.order) {
                    if (s == r) continue;
                    const auto& lab = L.labels[size_t(s)];
                    for (size_t img = 0; img < lab.size(); ++img)
                        if (lab[img] == r)
                            m.add(L.p[size_t(s)], L.heading[size_t(s)] + bearing(s, int(img)));
                }
                const auto& own = L.labels[size_t(r)];
                for (size_t img = 0; img < own.size(); ++img)
                    if (own[img] >= 0 && L.placed[size_t(own[img])])
                        m.add(L.p[size_t(own[img])], L.heading[size_t(r)] + bearing(r, int(img)));
                if (const auto at = m.solve()) L.p[size_t(r)] = *at;
                L.heading[size_t(r)] = fitHeading(L, r);
            }
        for (int r : L.order) L.heading[size_t(r)] = fitHeading(L, r);
    }

    /** Re-assigns every placed camera's labels from the polished layout: each image goes to
     *  the placed robot whose predicted bearing it matches best, one image per robot. This
     *  undoes a swap made early, when two robots were nearly in line from a camera. */
    void relabel(Layout& L) const {
        for (int u : L.order) {
            struct Match {
                double err;
                int image, robot;
            };
            std::vector<Match> ms;
            const auto& v = s_.views[size_t(u)].bearings;
            for (int w : L.order) {
                if (w == u) continue;
                const double b = direction(L.p[size_t(u)], L.p[size_t(w)]) - L.heading[size_t(u)];
                const double t = tolAt(L, (L.p[size_t(w)] - L.p[size_t(u)]).norm());
                for (size_t i = 0; i < v.size(); ++i)
                    if (const double e = std::abs(wrapToPi(v[i] - b)); e <= t)
                        ms.push_back({e / t, int(i), w});
            }
            std::sort(ms.begin(), ms.end(), [](const Match& a, const Match& b) {
                return std::tie(a.err, a.image, a.robot) < std::tie(b.err, b.image, b.robot);
            });
            // One image on the line to several robots is the nearest: its marker hides the
            // others. Otherwise two robots nearly in line from u (or one robot near two
            // images) cannot be told apart: such images stay unlabeled rather than guessed.
            std::map<int, int> perImage, perRobot;
            for (const auto& m : ms) ++perImage[m.image], ++perRobot[m.robot];
            std::map<int, int> occluder;  // image -> the nearest robot on its line
            for (const auto& m : ms) {
                if (perImage[m.image] < 2 || perRobot[m.robot] != 1) continue;
                auto& o = occluder[m.image];
                const auto dist = [&](int w) { return (L.p[size_t(w)] - L.p[size_t(u)]).norm(); };
                if (o == 0 || dist(m.robot) < dist(o - 1)) o = m.robot + 1;
            }
            auto& lab = L.labels[size_t(u)];
            std::fill(lab.begin(), lab.end(), -1);
            for (const auto& m : ms)
                if ((perImage[m.image] == 1 && perRobot[m.robot] == 1) ||
                    (occluder.count(m.image) && occluder[m.image] == m.robot + 1 &&
                     std::all_of(ms.begin(), ms.end(), [&](const Match& x) {
                         return x.image != m.image || perRobot[x.robot] == 1;
                     })))
                    lab[size_t(m.image)] = m.robot;
        }
    }

    Layout growFrom(const Seed& seed, bool& ok) const {
        Layout L;
        ok = placeSeed(seed, L);
        if (!ok) return L;
        while (growOnce(L)) polish(L, 2);
        for (int pass = 0; pass < 2; ++pass) {
            polish(L, 3);
            relabel(L);
        }
        return L;
    }

    /** Seeds from the hull: a robot whose images span less than 180 degrees sees the whole
     *  swarm in a half plane; its first image (counter-clockwise) is the next robot on the
     *  hull, whose last image is it. Three hull robots in a row fix a triangle up to two
     *  images, which the 180-degree sum pins down. */
    template <class Try>
    bool hullSeeds(Try&& attempt) const {
        std::vector<int> hull, first(size_t(n_), -1), last(size_t(n_), -1);
        for (int r = 0; r < n_; ++r) {
            const auto& v = s_.views[size_t(r)].bearings;
            if (v.size() < 2) continue;
            for (size_t i = 0; i < v.size(); ++i) {
                const size_t next = (i + 1) % v.size();
                double gap = v[next] - v[i];
                if (next == 0) gap += 2 * M_PI;
                if (gap > M_PI) {
                    first[size_t(r)] = int(next);
                    last[size_t(r)] = int(i);
                    hull.push_back(r);
                }
            }
        }
        std::vector<std::pair<double, Seed>> seeds;  // best conditioned first
        for (int i : hull)
            for (int j : hull)
                for (int k : hull) {
                    if (i == j || j == k || i == k) continue;
                    const double thetaJ =
                        signedAngle(s_.views[size_t(j)], first[size_t(j)], last[size_t(j)]);
                    for (size_t x = 0; x < s_.views[size_t(i)].size(); ++x) {
                        if (int(x) == first[size_t(i)]) continue;
                        const double thetaI =
                            signedAngle(s_.views[size_t(i)], first[size_t(i)], int(x));
                        const double thetaK = M_PI - thetaI - thetaJ;
                        if (thetaK <= 0) continue;
                        const int y =
                            findImage({}, k, bearing(k, last[size_t(k)]) - thetaK, o_.sumTolerance);
                        if (y < 0 || y == last[size_t(k)]) continue;
                        const Seed seed{{i, j, k},
                                        {{{first[size_t(i)], int(x)},
                                          {first[size_t(j)], last[size_t(j)]},
                                          {y, last[size_t(k)]}}}};
                        seeds.push_back({std::min({thetaI, thetaJ, thetaK}), seed});
                    }
                }
        std::stable_sort(seeds.begin(), seeds.end(),
                         [](const auto& a, const auto& b) { return a.first > b.first; });
        for (const auto& [conditioning, seed] : seeds)
            if (attempt(seed)) return true;
        return false;
    }

    /** Every triangle: counter-clockwise angle pairs at three robots summing to 180. */
    template <class Try>
    bool generalSeeds(Try&& attempt) const {
        // The counter-clockwise pairs (angle in (0, pi)): a slice of each robot's table.
        using It = std::vector<PairAngle>::const_iterator;
        std::vector<std::pair<It, It>> ccw;
        for (const auto& ps : pairs_) {
            const auto byAngle = [](const PairAngle& x, double v) { return x.angle < v; };
            const It from =
                std::upper_bound(ps.begin(), ps.end(), 0.0,
                                 [](double v, const PairAngle& x) { return v < x.angle; });
            ccw.push_back({from, std::lower_bound(from, ps.end(), M_PI, byAngle)});
        }
        const double tol = o_.sumTolerance;
        for (int i = 0; i < n_; ++i)
            for (int j = i + 1; j < n_; ++j)
                for (int k = i + 1; k < n_; ++k) {
                    if (k == j) continue;
                    const auto [kFrom, kTo] = ccw[size_t(k)];
                    for (auto a = ccw[size_t(i)].first; a != ccw[size_t(i)].second; ++a)
                        for (auto b = ccw[size_t(j)].first; b != ccw[size_t(j)].second; ++b) {
                            const double g = M_PI - a->angle - b->angle;
                            if (g <= -tol) break;
                            auto c = std::lower_bound(
                                kFrom, kTo, g - tol,
                                [](const PairAngle& x, double v) { return x.angle < v; });
                            for (; c != kTo && c->angle <= g + tol; ++c) {
                                const Seed seed{
                                    {i, j, k},
                                    {{{a->from, a->to}, {b->from, b->to}, {c->from, c->to}}}};
                                if (attempt(seed)) return true;
                            }
                        }
                }
        return false;
    }

 private:
    struct PairAngle {
        double angle;  ///< signed, from image `from` to image `to`
        int from, to;
    };
    std::vector<std::vector<PairAngle>> pairs_;   ///< per robot, sorted by angle
    static constexpr double kMinRayAngle = 0.02;  ///< sin of ~1.1 degrees
    static constexpr size_t kLookahead = 3;
    static constexpr size_t kSmallLayout = 6;
    static constexpr size_t kAnchors = 4;
    static constexpr size_t kMissSlack = 4;
    static constexpr size_t kAnchorGroups =
        8;  ///< anchor pairs tried per round, at most  ///< misses allowed beyond twice the hits
            ///< ///< the first robots, whose pairs all give rays
    static constexpr size_t kMinEvidence = 8;  ///< rays in plus robots seen
    const Snapshot& s_;
    const SearchOptions& o_;
    int n_;
};

size_t labelCount(const Layout& L) {
    size_t labeled = 0;
    for (const auto& lab : L.labels)
        for (int who : lab) labeled += who >= 0;
    return labeled;
}

/** The share of the placed robots' images that carry a label. */
double labeledShare(const Layout& L) {
    size_t images = 0;
    for (int r : L.order) images += L.labels[size_t(r)].size();
    return images ? double(labelCount(L)) / double(images) : 0;
}

constexpr double kDoneShare = 0.9;

}  // namespace

Identification identify(const Snapshot& s, const SearchOptions& o) {
    const Grower g(s, o);
    const int n = int(s.robots());
    size_t placeable = 0;
    for (const auto& v : s.views) placeable += v.size() >= 2;
    Layout best;
    size_t tried = 0, matched = 0, bestLabels = 0;
    const auto attempt = [&](const Seed& seed) {
        ++tried;
        bool ok = false;
        Layout L = g.growFrom(seed, ok);
        // The layout with most labels wins: chance growth from a false seed places robots
        // on a few rays each, a true layout labels nearly every image.
        const size_t labels = ok ? labelCount(L) : 0;
        if (labels > bestLabels) {
            if (labels > bestLabels + bestLabels / 50) matched = 0;
            best = std::move(L);
            bestLabels = labels;
        } else if (ok && L.order.size() > 3 && 2 * L.order.size() > placeable &&
                   labels + labels / 50 >= bestLabels) {
            ++matched;
        }
        // Done when everything that can be placed is, or when the best layout has been
        // grown again from three other seeds, or when the budget is spent.
        return (best.order.size() == placeable && labeledShare(best) >= kDoneShare) ||
               matched >= 3 || tried >= o.maxSeeds;
    };
    if (!g.hullSeeds(attempt)) g.generalSeeds(attempt);
    Labels labels = best.labels;
    if (labels.empty()) {
        labels.resize(size_t(n));
        for (int r = 0; r < n; ++r) labels[size_t(r)].assign(s.views[size_t(r)].size(), -1);
    }
    auto id = consistentTriangles(s, std::move(labels), o.sumTolerance);
    id.candidates = tried;
    return id;
}

}  // namespace mrloc::omnivision
