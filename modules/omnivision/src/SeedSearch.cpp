// Seed and grow: the image table and the seed triangles it offers.
#include <mrpt/core/format.h>

#include <map>
#include <set>
#include <tuple>

#include "LayoutGrowth.h"

namespace mrloc::omnivision::seedgrow {

Error ImageTable::tooMuchWork() const {
    return Error(mrpt::format(
        "[omnivision] sum_tolerance, bearing_tolerance, bearing_sigma: the identification of "
        "%zu robots examined over %zu angle pairs and images without settling (tolerances too loose for "
        "the bearings' noise; doc/errors.md, \"Work\")",
        snapshot_.robots(), maxVisits_));
}

ImageTable::ImageTable(const Snapshot& s, size_t maxVisits)
    : snapshot_(s),
      pairs_(s.robots()),
      unrolled_(s.robots()),
      cells_(s.robots()),
      maxVisits_(maxVisits) {
    for (int r = 0; r < robots(); ++r) {
        const auto& v = view(r);
        auto& unrolled = unrolled_[size_t(r)];
        for (const double turn : {-2 * M_PI, 0.0, 2 * M_PI})
            for (const double b : v.bearings) unrolled.push_back(b + turn);
        auto& first = cells_[size_t(r)];
        first.resize(kCells);
        for (size_t i = 0, img = 0; i < kCells; ++i) {
            while (img < unrolled.size() && unrolled[img] < cellStart(i)) ++img;
            first[i] = uint32_t(img);
        }
        for (int e = 0; e < int(v.size()); ++e)
            for (int f = 0; f < int(v.size()); ++f)
                if (e != f) pairs_[size_t(r)].push_back({signedAngle(v, e, f), e, f});
        std::sort(pairs_[size_t(r)].begin(), pairs_[size_t(r)].end(),
                  [](const PairAngle& a, const PairAngle& b) { return a.angle < b.angle; });
    }
}

/** The unlabeled image of robot r nearest the bearing b (robot frame), within tol. */
int ImageTable::findImage(const Labels& labels, int r, double b, double tol) const {
    const auto& unrolled = unrolled_[size_t(r)];
    const size_t n = unrolled.size() / 3;
    if (n == 0 || !std::isfinite(b)) return -1;  // wrapToPi loops on infinity
    if (++visits_ > maxVisits_) throw tooMuchWork();  // a lookup counts, as do its images
    b = wrapToPi(b);                                  // the one wrap: the query's
    tol = std::min(tol, M_PI);                        // each image once, at most
    const double lo = b - tol, hi = b + tol;          // within (-2 pi, 2 pi]
    size_t i = cells_[size_t(r)][cellOf(lo)];
    while (i < unrolled.size() && unrolled[i] < lo) ++i;
    int best = -1;
    double bestD = tol;
    for (; i < unrolled.size() && unrolled[i] <= hi; ++i) {
        // the work meter counts the images looked at too: with loose tolerances this scan,
        // not the angle pairs, is where the time goes (30 deg: 27 s before the pairs' bound)
        if (++visits_ > maxVisits_) throw tooMuchWork();
        const size_t img = i % n;
        const double d = std::abs(unrolled[i] - b);
        if ((labels.empty() || labels[size_t(r)][img] < 0) && d <= bestD)
            best = int(img), bestD = d;
    }
    return best;
}

namespace {

/** A view's gap wider than 180 degrees (the robot stands on the hull of what it sees): its
 *  first image counter-clockwise after the gap and its last before it. */
std::optional<std::pair<int, int>> gapOf(const View& view) {
    const auto& v = view.bearings;
    if (v.size() < 2) return std::nullopt;
    for (size_t i = 0; i < v.size(); ++i) {
        const size_t next = (i + 1) % v.size();
        double gap = v[next] - v[i];
        if (next == 0) gap += 2 * M_PI;
        if (gap > M_PI) return std::make_pair(int(next), int(i));  // at most one such gap
    }
    return std::nullopt;
}

/** The robots whose view has such a gap, and per robot its first and last image (-1). */
struct HullGaps {
    std::vector<int> hull, first, last;
};
HullGaps hullGaps(const ImageTable& table) {
    HullGaps g;
    g.first.assign(size_t(table.robots()), -1);
    g.last.assign(size_t(table.robots()), -1);
    for (int r = 0; r < table.robots(); ++r)
        if (const auto gap = gapOf(table.view(r))) {
            std::tie(g.first[size_t(r)], g.last[size_t(r)]) = *gap;
            g.hull.push_back(r);
        }
    return g;
}

}  // namespace

bool tryHullSeeds(const ImageTable& table, const SearchOptions& o, const SeedAttempt& attempt) {
    const auto [hull, first, last] = hullGaps(table);
    // Three hull robots in a row, i -> j -> k counter-clockwise: i's first image shows j, j's
    // first and last show k and i, k's last shows j. From i, k lies a few images past j (only
    // the robots inside the ear i-j-k lie between), and from k, i a few images before j: the
    // ear's images are searched kEar deep. A true triple's neighbours along the hull are
    // seeds too (j -> k -> l, h -> i -> j), a chance one's rarely: seeds that chain come
    // first, then those with fewer robots inside the ear, then the best conditioned.
    constexpr size_t kEar = 6;
    constexpr double kFlatSeed = 5 * M_PI / 180;  ///< rad: a seed angle below it is flat
    struct HullSeed {
        int chain = 0;
        size_t inside = 0;
        double conditioning = 0;
        Seed seed;
    };
    std::vector<HullSeed> seeds;
    for (int i : hull)
        for (int j : hull)
            for (int k : hull) {
                if (i == j || j == k || i == k) continue;
                const double thetaJ = signedAngle(table.view(j), first[size_t(j)], last[size_t(j)]);
                const size_t ni = table.view(i).size(), nk = table.view(k).size();
                for (size_t off = 1; off <= kEar && off < ni; ++off) {
                    const int x = int((size_t(first[size_t(i)]) + off) % ni);
                    const double thetaI = signedAngle(table.view(i), first[size_t(i)], x);
                    const double thetaK = M_PI - thetaI - thetaJ;
                    if (thetaK <= 0) continue;
                    const int y = table.findImage({}, k, table.bearing(k, last[size_t(k)]) - thetaK,
                                                  o.sumTolerance);
                    if (y < 0 || y == last[size_t(k)]) continue;
                    const size_t before = (size_t(last[size_t(k)]) + nk - size_t(y)) % nk;
                    if (before > kEar) continue;
                    const Seed seed{{i, j, k},
                                    {{{first[size_t(i)], x},
                                      {first[size_t(j)], last[size_t(j)]},
                                      {y, last[size_t(k)]}}}};
                    seeds.push_back(
                        {0, off + before - 2, std::min({thetaI, thetaJ, thetaK}), seed});
                }
            }
    std::set<std::pair<int, int>> heads, tails;  // (r0, r1) and (r1, r2) of every seed
    for (const auto& h : seeds)
        heads.insert({h.seed.r[0], h.seed.r[1]}), tails.insert({h.seed.r[1], h.seed.r[2]});
    for (auto& h : seeds)
        h.chain = int(heads.count({h.seed.r[1], h.seed.r[2]})) +
                  int(tails.count({h.seed.r[0], h.seed.r[1]}));
    // Hull robots nearly in line make a flat triangle (at N = 100 angles of 0.5 degrees):
    // its shape errs by percent, so the headings it gives point the rays past the robots they
    // should meet, and it grows nothing. Such seeds come last.
    const auto flat = [](const HullSeed& h) { return h.conditioning < kFlatSeed; };
    std::stable_sort(seeds.begin(), seeds.end(), [&](const HullSeed& a, const HullSeed& b) {
        if (flat(a) != flat(b)) return flat(b);
        if (a.chain != b.chain) return a.chain > b.chain;
        if (a.inside != b.inside) return a.inside < b.inside;
        return a.conditioning > b.conditioning;
    });
    for (const auto& h : seeds)
        if (attempt(h.seed)) return true;
    return false;
}

bool tryPairSeeds(const ImageTable& table, const SeedAttempt& attempt) {
    // Only where cameras see their neighbours: a pair's first group identifies a robot at
    // each meeting of two rays, about (images per view)^2 points, where a triangle asks a
    // third ray first. Where most robots are in sight the hull seeds serve, and the pairs
    // cost: `omnivision_swarm100.ini`'s run (100 robots) took over 10 minutes, not 12 s.
    size_t images = 0;
    for (int r = 0; r < table.robots(); ++r) images += table.view(r).size();
    if (2 * images >= size_t(table.robots()) * size_t(std::max(table.robots() - 1, 0)))
        return false;
    const auto [hull, first, last] = hullGaps(table);
    for (const int i : hull)
        for (const int j : hull) {
            if (i == j) continue;
            Seed seed;
            seed.pair = true;
            seed.r = {i, j, -1};
            seed.image[0][0] = first[size_t(i)];
            seed.image[1][1] = last[size_t(j)];
            if (attempt(seed)) return true;
        }
    return false;
}

bool tryGeneralSeeds(const ImageTable& table, const SearchOptions& o, const SeedAttempt& attempt) {
    // The counter-clockwise pairs (angle in (0, pi)): a slice of each robot's table.
    using It = std::vector<ImageTable::PairAngle>::const_iterator;
    std::vector<std::pair<It, It>> ccw;
    for (const auto& ps : table.pairTables()) {
        const auto byAngle = [](const ImageTable::PairAngle& x, double v) { return x.angle < v; };
        const It from =
            std::upper_bound(ps.begin(), ps.end(), 0.0,
                             [](double v, const ImageTable::PairAngle& x) { return v < x.angle; });
        ccw.push_back({from, std::lower_bound(from, ps.end(), M_PI, byAngle)});
    }
    const double tol = o.sumTolerance;
    for (int i = 0; i < table.robots(); ++i)
        for (int j = i + 1; j < table.robots(); ++j)
            for (int k = i + 1; k < table.robots(); ++k) {
                if (k == j) continue;
                const auto [kFrom, kTo] = ccw[size_t(k)];
                for (auto a = ccw[size_t(i)].first; a != ccw[size_t(i)].second; ++a)
                    for (auto b = ccw[size_t(j)].first; b != ccw[size_t(j)].second; ++b) {
                        const double g = M_PI - a->angle - b->angle;
                        if (g <= -tol) break;
                        auto c = std::lower_bound(
                            kFrom, kTo, g - tol,
                            [](const ImageTable::PairAngle& x, double v) { return x.angle < v; });
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

}  // namespace mrloc::omnivision::seedgrow
