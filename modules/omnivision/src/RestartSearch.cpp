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

}  // namespace

RestartSearch localizedRestartSearch(const Snapshot& before, const Snapshot& after,
                                     const Identification& idAfter, int a, int b,
                                     const std::vector<double>& travelled,
                                     const std::vector<double>& turned, const SearchOptions& o) {
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

    // Eq. (11): the witnesses of t_e, farthest travelled first.
    std::vector<int> witnesses;
    for (int k = 0; k < int(before.robots()); ++k)
        if (k != a && k != b && travelled[size_t(k)] > 0 && findTriangle(idAfter, a, b, k))
            witnesses.push_back(k);
    std::stable_sort(witnesses.begin(), witnesses.end(),
                     [&](int p, int q) { return travelled[size_t(p)] > travelled[size_t(q)]; });

    RestartSearch out;
    for (const int k : witnesses) {
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
        struct Found {
            int ak, bk, ka, kb;
            double moved;     // |K_b - K_e| in units of |AB|
            double mismatch;  // |K's turn - its odometer's| (rad)
            bool operator<(const Found& o) const {
                return moved != o.moved ? moved < o.moved : mismatch < o.mismatch;
            }
        };
        std::optional<Found> best;
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
                if (atK < -o.sumTolerance) continue;
                for (int ka = 0; ka < int(vk.size()); ++ka) {
                    ++out.triples;
                    // Counter-clockwise triangle A, B, K: from K, B lies counter-clockwise of A.
                    const auto kb =
                        imageNear(vk, vk.bearings[size_t(ka)] + side * atK, o.sumTolerance);
                    if (!kb || *kb == ka) continue;
                    ++found;
                    Vec2 kBefore;
                    try {
                        kBefore =
                            unitBaselinePoint(lineDirections(std::abs(sa), std::abs(sb), side));
                    } catch (const Error&) {
                        continue;  // K on the line AB: not a triangle
                    }
                    // K's heading at t_b, from this triangle's image of A; its turn.
                    const double headingBefore =
                        std::atan2(-kBefore.y(), -kBefore.x()) - vk.bearings[size_t(ka)];
                    const double mismatch = std::abs(
                        mrpt::math::wrapToPi(headingAfter - headingBefore - turned[size_t(k)]));
                    if (mismatch > kTurnTolerance) continue;  // not K's turn: chance
                    const Found f{ak, bk, ka, *kb, (kBefore - kAfter).norm(), mismatch};
                    if (!best || f < *best) best = f;
                }
            }
        }
        // A robot nearly in line with K from A, B or K has an image the 180-degree sum
        // cannot tell from K's: its triangle fits as well. Such a witness is skipped.
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
    throw Error(mrpt::format(
        "omnivision: none of the %zu moving robots that A and B both see at t_e forms a "
        "triangle with them at t_b (%zu image triples searched, paper 000 eq. (12)): stop "
        "another pair",
        witnesses.size(), out.triples));
}

}  // namespace mrloc::omnivision
