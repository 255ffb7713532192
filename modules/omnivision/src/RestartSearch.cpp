#include <mrloc/common/Error.h>
#include <mrloc/omnivision/Geometry.h>
#include <mrloc/omnivision/RelativeLocation.h>
#include <mrloc/omnivision/RestartSearch.h>
#include <mrpt/core/format.h>
#include <mrpt/math/wrap2pi.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>

namespace mrloc::omnivision {

namespace {

/** The image of a view (sorted) nearest to `bearing`, by bisection, if within `tolerance`. */
std::optional<int> imageNear(const View& v, double bearing, double tolerance) {
    const auto& b = v.bearings;
    if (b.empty()) return std::nullopt;
    const double w = mrpt::math::wrapToPi(bearing);
    const size_t hi = size_t(std::lower_bound(b.begin(), b.end(), w) - b.begin());
    std::optional<int> best;
    double bestErr = tolerance;
    for (const size_t i : {hi % b.size(), (hi + b.size() - 1) % b.size()})
        if (const double e = std::abs(mrpt::math::wrapToPi(b[i] - w)); e <= bestErr)
            best = int(i), bestErr = e;
    return best;
}

/** Whether another image of `v` lies within `tolerance` of image i. */
bool crowded(const View& v, int i, double tolerance) {
    const size_t n = v.size(), k = size_t(i);
    return n > 1 &&
           (std::abs(mrpt::math::wrapToPi(v.bearings[(k + 1) % n] - v.bearings[k])) < tolerance ||
            std::abs(mrpt::math::wrapToPi(v.bearings[k] - v.bearings[(k + n - 1) % n])) <
                tolerance);
}

int imageLabelled(const Labels& labels, int observer, int who) {
    const auto& l = labels[size_t(observer)];
    const auto it = std::find(l.begin(), l.end(), who);
    return it == l.end() ? -1 : int(it - l.begin());
}

/** A robot an observer saw at t_e, placed at t_e in the frame A and B hold (units of |AB|),
 *  with how far off that place may be from the bearing noise (units of |AB|). */
struct Placed {
    int robot = -1;
    Vec2 at;
    double uncertainty = 0;
};

/** How far a point placed by rays from A and B meeting at `angle` may be off, in units of
 *  |AB|: each ray off by the tolerance moves it by the ray's length times that, over
 *  sin(angle). */
double placementUncertainty(const Vec2& at, double angle, double bearingTolerance) {
    return (at.norm() + (at - Vec2(1, 0)).norm()) * bearingTolerance /
           std::max(std::sin(angle), 1e-3);
}

/** The robots `observer` sees at t_e (but A, B and itself), each placed from A's and B's
 *  images of it at t_e. One that A or B does not see, or that stands nearly on the line AB,
 *  is left out. */
std::vector<Placed> seenAtTe(const Snapshot& after, const Identification& id, int a, int b,
                             int observer, int abImage, int baImage, double bearingTolerance) {
    const View &va = after.views[size_t(a)], &vb = after.views[size_t(b)];
    std::vector<Placed> out;
    for (const int j : id.labels[size_t(observer)]) {
        if (j < 0 || j == a || j == b || j == observer) continue;
        const int ia = imageLabelled(id.labels, a, j), ib = imageLabelled(id.labels, b, j);
        if (ia < 0 || ib < 0) continue;
        const double sa = signedAngle(va, abImage, ia), sb = signedAngle(vb, baImage, ib);
        if ((sa >= 0) == (sb >= 0)) continue;  // not a triangle A, B, j (noise at the line)
        const double atJ = M_PI - std::abs(sa) - std::abs(sb);
        if (atJ < 10 * bearingTolerance) continue;  // the rays nearly parallel: j far off
        Placed p;
        p.robot = j;
        try {
            p.at = unitBaselinePoint(lineDirections(std::abs(sa), std::abs(sb), sa >= 0 ? 1 : -1));
        } catch (const Error&) {
            continue;
        }
        p.uncertainty = placementUncertainty(p.at, atJ, bearingTolerance);
        out.push_back(p);
    }
    return out;
}

/** Heading-free confirmation of a candidate triangle at t_b (the gap of eq. (11)-(12) filled
 *  with what the paper's setting gives: every robot's odometer distance and the images of
 *  t_e). The candidate places K at t_b and, through its image of A, turns K's view into the
 *  frame of A and B; eq. (8) gives |AB| from K's own travel. Every robot j that K saw at t_e
 *  then stood, at t_b, within its own odometer distance of its t_e place: K's view at t_b must
 *  hold an image within the angle that disc spans. The true triangle finds nearly every one;
 *  a chance triangle, whose K is elsewhere or turned otherwise, finds those its images hit by
 *  chance. */
struct Agreement {
    size_t checked = 0;  ///< robots whose disc spans less than 60 degrees from K
    size_t found = 0;    ///< of those, an image of K's view at t_b within the disc's angle
    double chance = 0;   ///< found expected of a view of that many random bearings
    double excess() const { return double(found) - chance; }
};

/** Misses beyond which a candidate is dropped before all robots are checked: the true
 *  triangle misses only robots hidden or gone from K's view in [t_b, t_e]. */
constexpr double kMissShare = 0.1;

/** `unitsPerMetre`: eq. (8)'s scale from the candidate, at most (see its computation). */
Agreement agreementOf(const View& vk, const Vec2& kBefore, double kUncertainty,
                      double headingBefore, double unitsPerMetre,
                      const std::vector<Placed>& seen, const std::vector<double>& travelled,
                      double bearingTolerance) {
    Agreement g;
    size_t missed = 0;
    for (const auto& s : seen) {
        const Vec2 d = s.at - kBefore;
        const double distance = d.norm();
        const double reach =
            travelled[size_t(s.robot)] * unitsPerMetre + s.uncertainty + kUncertainty;
        if (!(distance > 2 * reach)) continue;  // the disc spans 60 degrees or more: no test
        const double halfAngle = std::asin(reach / distance) + bearingTolerance;
        ++g.checked;
        const double bearing = std::atan2(d.y(), d.x()) - headingBefore;
        g.chance += 1 - std::pow(1 - std::min(1.0, halfAngle / M_PI), double(vk.size()));
        if (imageNear(vk, bearing, halfAngle))
            ++g.found;
        else if (double(++missed) > kMissShare * double(seen.size()))
            return Agreement{};  // early out: not the true triangle
    }
    return g;
}

/** Witnesses the heading-free search tries before it gives up (the caller then runs the full
 *  search at t_b). */
constexpr size_t kMaxWitnesses = 10;

/** Robots found beyond chance within which a second labelling makes a witness ambiguous. */
constexpr double kTwinMargin = 3;

/** Whether an agreement is beyond chance: no more than kMissShare of the robots checked
 *  missed, and those found three standard deviations above what K's images would hit at
 *  random (binomial; with few robots or wide discs no triangle passes, and the full search
 *  runs instead). */
bool beyondChance(const Agreement& g) {
    const double n = double(g.checked);
    if (g.checked == 0 || double(g.found) < (1 - kMissShare) * n) return false;
    const double p = std::min(1.0, g.chance / n);
    return g.excess() > 3 * std::sqrt(n * p * (1 - p));
}

/** Whether an image of an observer at `from` (frame of A and B, units of |AB|) whose camera
 *  points `heading` could show, besides the robot the candidate names, another robot it saw at
 *  t_e, within that robot's reach (its odometer distance at `unitsPerMetre`): the robot
 *  nearly in line with the one named, whose image the candidate may have taken. */
bool anotherCouldBe(const View& v, int image, const Vec2& from, double heading, int named,
                    const std::vector<Placed>& seen, const std::vector<double>& travelled,
                    double unitsPerMetre, double bearingTolerance) {
    for (const auto& s : seen) {
        if (s.robot == named) continue;
        const Vec2 d = s.at - from;
        const double reach = travelled[size_t(s.robot)] * unitsPerMetre + s.uncertainty;
        if (!(d.norm() > reach)) return true;  // the observer may stand where it stood
        const double bearing = std::atan2(d.y(), d.x()) - heading;
        if (std::abs(mrpt::math::wrapToPi(v.bearings[size_t(image)] - bearing)) <=
            std::asin(reach / d.norm()) + 2 * bearingTolerance)
            return true;
    }
    return false;
}

}  // namespace

RestartSearch localizedRestartSearch(const Snapshot& before, const Snapshot& after,
                                     const Identification& idAfter, int a, int b,
                                     const std::vector<double>& travelled,
                                     const std::vector<double>& turned, const SearchOptions& o,
                                     bool useOdometerTurn) {
    const View &va = before.views[size_t(a)], &vb = before.views[size_t(b)];
    // A and B stood still: each one's image of the other keeps its t_e bearing.
    const int abAfter = imageLabelled(idAfter.labels, a, b);
    const int baAfter = imageLabelled(idAfter.labels, b, a);
    if (abAfter < 0 || baAfter < 0)
        throw Error(
            "omnivision: the stopped robots do not see each other at t_e: stop another pair "
            "(paper 000 section 3)");
    const auto ab =
        imageNear(va, after.views[size_t(a)].bearings[size_t(abAfter)], o.bearingTolerance);
    const auto ba =
        imageNear(vb, after.views[size_t(b)].bearings[size_t(baAfter)], o.bearingTolerance);
    if (!ab || !ba)
        throw Error(
            "omnivision: a stopped robot's image of the other moved between t_b and t_e: "
            "they did not stand still");

    // heading-free: the robots A and B saw at t_e, placed
    const auto seenByA =
        useOdometerTurn ? std::vector<Placed>{}
                        : seenAtTe(after, idAfter, a, b, a, abAfter, baAfter, o.bearingTolerance);
    const auto seenByB =
        useOdometerTurn ? std::vector<Placed>{}
                        : seenAtTe(after, idAfter, a, b, b, abAfter, baAfter, o.bearingTolerance);

    // Eq. (11): the witnesses of t_e, farthest travelled first.
    std::vector<int> witnesses;
    for (int k = 0; k < int(before.robots()); ++k)
        if (k != a && k != b && travelled[size_t(k)] > 0 && findTriangle(idAfter, a, b, k))
            witnesses.push_back(k);
    std::stable_sort(witnesses.begin(), witnesses.end(),
                     [&](int p, int q) { return travelled[size_t(p)] > travelled[size_t(q)]; });

    RestartSearch out;
    for (const int k : witnesses) {
        // heading-free, a bounded number of witnesses: with many robots in reach of each
        // other most are ambiguous, and the full search is the fall-back
        if (!useOdometerTurn && out.witnessesTried == kMaxWitnesses) break;
        ++out.witnessesTried;
        const Triangle& te = *findTriangle(idAfter, a, b, k);
        const Vec2 kAfter = unitBaselinePoint(
            lineDirections(angleAt(te, a), angleAt(te, b), sideAt(after, te, a, b)));
        const View& vk = before.views[size_t(k)];
        // the full search's work bound, and at least 1e8 triples (a second or so): a
        // hostile log's views may be huge
        if (double(va.size()) * double(vb.size()) * double(vk.size()) >
            std::max(1e8, double(o.maxPairVisits(before.robots()))))
            throw Error(mrpt::format(
                "omnivision: the localized search at t_b would examine %zu x %zu x %zu image "
                "triples, beyond the search's work bound (doc/errors.md, \"Work\")",
                va.size(), vb.size(), vk.size()));
        // K's heading at t_e, in the frame of A and B, from its image of A.
        const double headingAfter =
            std::atan2(-kAfter.y(), -kAfter.x()) -
            after.views[size_t(k)].bearings[size_t(imageLabelled(idAfter.labels, k, a))];
        // heading-free (the paper's setting): the robots K saw at t_e, placed at t_e
        const auto seen = useOdometerTurn ? std::vector<Placed>{}
                                          : seenAtTe(after, idAfter, a, b, k, abAfter, baAfter,
                                                     o.bearingTolerance);
        struct Found {
            int ak, bk, ka, kb;
            double moved;     // |K_b - K_e| in units of |AB|
            double mismatch;  // |K's turn - its odometer's| (rad), with useOdometerTurn
            double excess;    // robots found in K's view beyond chance, heading-free
            Vec2 at;          // K at t_b
            double heading;   // K's camera at t_b, in the frame of A and B
            double unitsPerMetre;  // eq. (8)'s scale, at most
            bool operator<(const Found& o) const {
                if (excess != o.excess) return excess > o.excess;
                return moved != o.moved ? moved < o.moved : mismatch < o.mismatch;
            }
        };
        // Heading-free, the candidates' sum within twice the tolerance: the sum of six noisy
        // bearings errs by sqrt(6) sigma, so 6 sigma loses the true triangle in about one
        // witness of a hundred, and a twin of it (rays of other robots crossing near K) is
        // then all that is left; the robots K saw reject what the wider sum lets in.
        const double sumTolerance = useOdometerTurn ? o.sumTolerance : 2 * o.sumTolerance;
        std::optional<Found> best, runnerUp;  // runnerUp: heading-free, the next labelling
        size_t found = 0;
        // Eq. (12): A's image of K, B's image of K, K's image of A.
        for (int ak = 0; ak < int(va.size()); ++ak) {
            if (ak == *ab) continue;
            const double sa = signedAngle(va, *ab, ak);
            const int side = sa >= 0 ? 1 : -1;  // K left of A->B: counter-clockwise from A
            for (int bk = 0; bk < int(vb.size()); ++bk) {
                if (bk == *ba) continue;
                const double sb = signedAngle(vb, *ba, bk);
                if ((sb >= 0 ? 1 : -1) == side) continue;  // the same side of AB from B
                const double atK = M_PI - std::abs(sa) - std::abs(sb);
                if (atK < -sumTolerance) continue;
                // K at t_b from A's and B's images alone (none: K on the line AB, no triangle)
                std::optional<Vec2> placed;
                try {
                    placed = unitBaselinePoint(lineDirections(std::abs(sa), std::abs(sb), side));
                } catch (const Error&) {
                }
                for (int ka = 0; ka < int(vk.size()); ++ka) {
                    ++out.triples;
                    // Counter-clockwise triangle A, B, K: from K, B lies counter-clockwise of A.
                    const auto kb =
                        imageNear(vk, vk.bearings[size_t(ka)] + side * atK, sumTolerance);
                    if (!kb || *kb == ka) continue;
                    ++found;
                    if (!placed) continue;
                    const Vec2& kBefore = *placed;
                    // K's heading at t_b, from this triangle's image of A
                    const double headingBefore =
                        std::atan2(-kBefore.y(), -kBefore.x()) - vk.bearings[size_t(ka)];
                    const double moved = (kBefore - kAfter).norm();
                    Found f{ak, bk, ka, *kb, moved, 0, 0, kBefore, headingBefore, 0};
                    if (useOdometerTurn) {
                        // beyond the paper: K's turn against its odometer's
                        f.mismatch = std::abs(
                            mrpt::math::wrapToPi(headingAfter - headingBefore - turned[size_t(k)]));
                        if (f.mismatch > kTurnTolerance) continue;  // not K's turn: chance
                    } else {
                        const double uncertainty =
                            placementUncertainty(kBefore, std::max(atK, 0.0), o.bearingTolerance);
                        // eq. (8): |AB| = l_K / |K_b - K_e|, so a robot's odometer distance l_j
                        // is l_j * moved / l_K in units of |AB| (at most: both places of K may
                        // be off by their uncertainty)
                        f.unitsPerMetre = (moved + 2 * uncertainty) / travelled[size_t(k)];
                        const auto g = agreementOf(vk, kBefore, uncertainty, headingBefore,
                                                   f.unitsPerMetre, seen, travelled,
                                                   o.bearingTolerance);
                        if (!beyondChance(g)) continue;  // chance
                        f.excess = g.excess();
                    }
                    if (!best || f < *best)
                        runnerUp = best, best = f;
                    else if (!runnerUp || f < *runnerUp)
                        runnerUp = f;
                }
            }
        }
        // A robot nearly in line with K from A, B or K has an image the 180-degree sum
        // cannot tell from K's: its triangle fits as well. Such a witness is skipped.
        // Heading-free, two labellings that the robots K saw explain about as well: rays of
        // other robots crossing near K's place (one image away at A or B) give K nearly
        // the same pose. Such a witness is skipped.
        if (best && runnerUp && !useOdometerTurn && runnerUp->excess > best->excess - kTwinMargin)
            continue;
        // Heading-free, an image of the triangle that another robot seen at t_e, within its
        // reach, could have made: that robot nearly in line with the one named (the twin
        // above with its rival below the rival's sum). Such a witness is skipped.
        if (best && !useOdometerTurn) {
            const double u = best->unitsPerMetre, tol = o.bearingTolerance;
            const double headingA = -va.bearings[size_t(*ab)];
            const double headingB = M_PI - vb.bearings[size_t(*ba)];
            if (anotherCouldBe(va, best->ak, Vec2(0, 0), headingA, k, seenByA, travelled, u, tol) ||
                anotherCouldBe(vb, best->bk, Vec2(1, 0), headingB, k, seenByB, travelled, u, tol) ||
                anotherCouldBe(vk, best->ka, best->at, best->heading, a, seen, travelled, u, tol) ||
                anotherCouldBe(vk, best->kb, best->at, best->heading, b, seen, travelled, u, tol))
                continue;
        }
        if (!best || crowded(va, best->ak, o.sumTolerance) ||
            crowded(vb, best->bk, o.sumTolerance) || crowded(vk, best->ka, o.sumTolerance) ||
            crowded(vk, best->kb, o.sumTolerance))
            continue;
        Labels labels(before.robots());
        for (size_t r = 0; r < before.robots(); ++r) labels[r].assign(before.views[r].size(), -1);
        labels[size_t(a)][size_t(*ab)] = b, labels[size_t(a)][size_t(best->ak)] = k;
        labels[size_t(b)][size_t(*ba)] = a, labels[size_t(b)][size_t(best->bk)] = k;
        labels[size_t(k)][size_t(best->ka)] = a, labels[size_t(k)][size_t(best->kb)] = b;
        out.before = consistentTriangles(before, std::move(labels), o.sumTolerance);
        out.witness = k;
        out.triangles = found;
        return out;
    }
    out.unconfirmed = mrpt::format(
        "none of the %zu moving robots that A and B both see at t_e (%zu tried) forms a "
        "triangle with them at t_b%s (%zu image triples searched, paper 000 eq. (12))",
        witnesses.size(), out.witnessesTried,
        useOdometerTurn ? "" : " that the robots it saw confirm and no other robot could make",
        out.triples);
    return out;
}

}  // namespace mrloc::omnivision
