// Seed and grow: re-fitting the layout and re-assigning images from it.
#include <algorithm>
#include <boost/pending/disjoint_sets.hpp>
#include <map>
#include <set>
#include <tuple>

#include "LayoutGrowth.h"

namespace mrloc::omnivision::seedgrow {

/** Re-fits every placed robot's position (least squares over the labeled rays into and
 *  out of it) and heading, so that errors do not pile up as the layout grows. */
void LayoutGrower::polish(Layout& layout, int sweeps) const {
    for (int it = 0; it < sweeps; ++it)
        for (size_t k = 2; k < layout.order.size(); ++k) {  // the first two fix the frame
            const int r = layout.order[k];
            // a ray from d away misses by d x its bearing's error: weigh it by 1 / d^2
            const auto weight = [&](int s) {
                return 1 /
                       std::max((layout.p[size_t(s)] - layout.p[size_t(r)]).squaredNorm(), 1e-6);
            };
            LineMeeting m;
            for (int s : layout.order) {
                if (s == r) continue;
                const auto& lab = layout.labels[size_t(s)];
                for (size_t img = 0; img < lab.size(); ++img)
                    if (lab[img] == r)
                        m.add(layout.p[size_t(s)],
                              layout.heading[size_t(s)] + table_.bearing(s, int(img)), weight(s));
            }
            const auto& own = layout.labels[size_t(r)];
            for (size_t img = 0; img < own.size(); ++img)
                if (own[img] >= 0 && layout.placed[size_t(own[img])])
                    m.add(layout.p[size_t(own[img])],
                          layout.heading[size_t(r)] + table_.bearing(r, int(img)),
                          weight(own[img]));
            if (const auto at = m.solve()) layout.p[size_t(r)] = *at;
            layout.heading[size_t(r)] = fitHeading(layout, r);
        }
    for (int r : layout.order) layout.heading[size_t(r)] = fitHeading(layout, r);
}

/** The placed robot whose labelled bearings (its images of others, others' images of it)
 *  fit the layout worst, by RMS in bearing sigmas, if that is over kMaxRms; else -1. */
int LayoutGrower::worstFit(const Layout& layout) const {
    const double sigma = o_.bearingTolerance / 4;  // the tolerance is 4 sigma
    std::vector<double> sum(size_t(n_), 0);
    std::vector<size_t> count(size_t(n_), 0), in(size_t(n_), 0), out(size_t(n_), 0);
    for (int u : layout.order) {
        const auto& lab = layout.labels[size_t(u)];
        for (size_t img = 0; img < lab.size(); ++img) {
            const int w = lab[img];
            if (w < 0 || !layout.placed[size_t(w)]) continue;
            const double e = wrapToPi(direction(layout.p[size_t(u)], layout.p[size_t(w)]) -
                                      layout.heading[size_t(u)] - table_.bearing(u, int(img)));
            for (int r : {u, w}) sum[size_t(r)] += e * e, ++count[size_t(r)];
            ++out[size_t(u)], ++in[size_t(w)];
        }
    }
    // Sight is mutual (a camera's range, a marker in the line of sight): a robot that the
    // others see where it stands but that sees few of them from there is another robot's
    // look-alike (near it, its view of the far robots differs from the true one's by little
    // parallax). The most one-sided goes first.
    int oneSided = -1;
    double worstShare = kMinSightShare;
    for (int r : layout.order)
        if (in[size_t(r)] >= kMinEvidence)
            if (const double share = double(out[size_t(r)]) / double(in[size_t(r)]);
                share < worstShare)
                oneSided = r, worstShare = share;
    if (oneSided >= 0) return oneSided;
    // A robot placed a little off where it stands (near it, its images of the far robots
    // fit by little parallax) has robots in sight with no image where it predicts them.
    // From its true place every placed robot in sight falls on one of its images (its own
    // or, hidden, its occluder's), and it on one of theirs. Bands hide more than the line
    // to their centre (a 0.15 m band 3 m away, 3 degrees), so misses are counted against
    // the layout's median share of them.
    const double reach = sightReach(layout) / kReachMargin;  // the longest labelled sight
    std::vector<std::pair<double, int>> missShare;
    for (int u : layout.order) {
        size_t checks = 0, misses = 0;
        for (int w : layout.order) {
            const Vec2 d = layout.p[size_t(w)] - layout.p[size_t(u)];
            if (w == u || d.norm() > reach) continue;
            const double t = tolAt(layout, d.norm()), toW = std::atan2(d.y(), d.x());
            misses += table_.findImage({}, u, toW - layout.heading[size_t(u)], t) < 0;
            misses += table_.findImage({}, w, toW + M_PI - layout.heading[size_t(w)], t) < 0;
            checks += 2;
        }
        if (checks >= 2 * kMinEvidence) missShare.push_back({double(misses) / double(checks), u});
    }
    if (!missShare.empty()) {
        std::sort(missShare.begin(), missShare.end());
        const double median = missShare[missShare.size() / 2].first;
        if (missShare.back().first > std::max(kMaxMissShare, kMissOverMedian * median))
            return missShare.back().second;
    }
    int worst = -1;
    double worstRms = kMaxRms;
    for (int r : layout.order)
        if (count[size_t(r)] > 0)
            if (const double rms = std::sqrt(sum[size_t(r)] / double(count[size_t(r)])) / sigma;
                rms > worstRms)
                worst = r, worstRms = rms;
    return worst;
}

/** Takes robot r out of the layout, with every label to or from it. */
void LayoutGrower::unplace(Layout& layout, int r) {
    layout.placed[size_t(r)] = 0;
    layout.order.erase(std::find(layout.order.begin(), layout.order.end(), r));
    for (auto& lab : layout.labels)
        for (int& w : lab)
            if (w == r) w = -1;
    std::fill(layout.labels[size_t(r)].begin(), layout.labels[size_t(r)].end(), -1);
}

/** Re-assigns every placed camera's labels from the polished layout: each image goes to
 *  the placed robot whose predicted bearing it matches best, one image per robot. This
 *  undoes a swap made early, when two robots were nearly in line from a camera. */
std::vector<LayoutGrower::Match> LayoutGrower::matchesAt(const Layout& layout, int u) const {
    std::vector<Match> ms;
    const auto& v = table_.view(u).bearings;
    for (int w : layout.order) {
        if (w == u) continue;
        const double b =
            direction(layout.p[size_t(u)], layout.p[size_t(w)]) - layout.heading[size_t(u)];
        const double t = tolAt(layout, (layout.p[size_t(w)] - layout.p[size_t(u)]).norm());
        for (size_t i = 0; i < v.size(); ++i)
            if (const double e = std::abs(wrapToPi(v[i] - b)); e <= t)
                ms.push_back({e / t, int(i), w});
    }
    return ms;
}

void LayoutGrower::relabel(Layout& layout) const {
    for (int u : layout.order) {
        auto ms = matchesAt(layout, u);
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
            const auto dist = [&](int w) {
                return (layout.p[size_t(w)] - layout.p[size_t(u)]).norm();
            };
            if (o == 0 || dist(m.robot) < dist(o - 1)) o = m.robot + 1;
        }
        auto& lab = layout.labels[size_t(u)];
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

/** Images relabel() left unlabelled because two placed robots lie near their line (or one
 *  robot near two images): once the layout is final its predicted bearings are far better
 *  than a tolerance, and the images of a few robots nearly in line can be matched as a
 *  whole. Each group of unlabelled images and free robots linked by matches within the
 *  tolerance, with as many images as robots (no one hidden), takes its best one-to-one
 *  assignment when every other assignment is kAssignMargin worse in squared bearing sigmas
 *  (the tolerance is 4 sigma), or when it is the only one. */
void LayoutGrower::assignNearLines(Layout& layout) const {
    for (int u : layout.order) {
        auto& lab = layout.labels[size_t(u)];
        const size_t images = lab.size();
        std::vector<char> taken(size_t(n_), 0);
        for (int w : lab)
            if (w >= 0) taken[size_t(w)] = 1;
        std::map<std::pair<int, int>, double> cost;  // (image, robot) -> squared sigmas
        // groups: images and robots joined by a match (image i as i, robot w as images + w)
        boost::disjoint_sets_with_storage<> joined(images + size_t(n_));
        for (const auto& m : matchesAt(layout, u))
            if (lab[size_t(m.image)] < 0 && !taken[size_t(m.robot)]) {
                cost[{m.image, m.robot}] = std::pow(kSigmasPerTolerance * m.err, 2);
                joined.union_set(size_t(m.image), images + size_t(m.robot));
            }
        std::map<size_t, std::pair<std::vector<int>, std::vector<int>>> groups;
        for (const auto& [m, c] : cost) {
            auto& [groupImages, groupRobots] = groups[joined.find_set(size_t(m.first))];
            if (std::find(groupImages.begin(), groupImages.end(), m.first) == groupImages.end())
                groupImages.push_back(m.first);
            if (std::find(groupRobots.begin(), groupRobots.end(), m.second) == groupRobots.end())
                groupRobots.push_back(m.second);
        }
        for (auto& [root, group] : groups) {
            auto& [groupImages, robots] = group;
            if (groupImages.size() != robots.size() || robots.size() < 2 ||
                robots.size() > kMaxNearLine)
                continue;
            std::sort(robots.begin(), robots.end());
            double best = INFINITY, second = INFINITY;
            std::vector<int> bestRobots;
            do {
                double total = 0;
                for (size_t k = 0; k < robots.size() && std::isfinite(total); ++k) {
                    const auto it = cost.find({groupImages[k], robots[k]});
                    total = it == cost.end() ? INFINITY : total + it->second;
                }
                if (total < best)
                    second = best, best = total, bestRobots = robots;
                else if (total < second)
                    second = total;
            } while (std::next_permutation(robots.begin(), robots.end()));
            if (!std::isfinite(best) || second - best < kAssignMargin) continue;
            for (size_t k = 0; k < robots.size(); ++k) lab[size_t(groupImages[k])] = bestRobots[k];
        }
    }
}

}  // namespace mrloc::omnivision::seedgrow
