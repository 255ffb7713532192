// The paper's triangle search (seed 000 eq. (9)) and the identification by votes of
// triangle pairs (Fig. 4-6): the test oracle of the seed-and-grow search.
#include <mrloc/common/Error.h>
#include <mrloc/omnivision/TriangleSearch.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace mrloc::omnivision {

// ---------------------------------------------------------------------------------------
// The paper's search (eq. (9)) and identification by votes (Fig. 4-6)
// ---------------------------------------------------------------------------------------

std::vector<Triangle> bruteForceTriangles(const Snapshot& s, double tol) {
    const int n = int(s.robots());
    std::vector<std::vector<ImageAngle>> angles(static_cast<size_t>(n));
    for (int r = 0; r < n; ++r) angles[size_t(r)] = anglesOf(s.views[size_t(r)]);
    std::vector<Triangle> out;
    for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j)
            for (int k = j + 1; k < n; ++k)
                for (const auto& a : angles[size_t(i)])
                    for (const auto& b : angles[size_t(j)])
                        for (const auto& c : angles[size_t(k)])
                            if (std::abs(a.angle + b.angle + c.angle - M_PI) <= tol)
                                out.push_back({{i, j, k},
                                               {{{a.p, a.q}, {b.p, b.q}, {c.p, c.q}}},
                                               {a.angle, b.angle, c.angle}});
    return out;
}

namespace {

int vertexOf(const Triangle& t, int robot) {
    for (int v = 0; v < 3; ++v)
        if (t.robot[size_t(v)] == robot) return v;
    return -1;
}

int thirdRobot(const Triangle& t, int u, int v) {
    for (int r : t.robot)
        if (r != u && r != v) return r;
    return -1;
}

/** Greedy assignment by vote count, one image per robot and one robot per image; at each
 *  count, a candidate that competes with another of the same count is left out. */
std::vector<int> assign(std::map<std::pair<int, int>, int> votes, size_t images) {
    std::vector<int> label(images, -1);
    std::set<int> usedRobots;
    std::map<int, std::vector<std::pair<int, int>>, std::greater<int>> byCount;
    for (const auto& [key, count] : votes) byCount[count].push_back(key);
    for (const auto& [count, keys] : byCount) {
        std::map<int, int> imageUses, robotUses;
        std::vector<std::pair<int, int>> free;
        for (const auto& [image, robot] : keys)
            if (label[size_t(image)] < 0 && !usedRobots.count(robot)) {
                free.push_back({image, robot});
                ++imageUses[image];
                ++robotUses[robot];
            }
        for (const auto& [image, robot] : free)
            if (imageUses[image] == 1 && robotUses[robot] == 1) {
                label[size_t(image)] = robot;
                usedRobots.insert(robot);
            }
    }
    return label;
}

}  // namespace

Labels labelsByVotes(const Snapshot& s, const std::vector<Triangle>& candidates) {
    const int n = int(s.robots());
    std::map<std::pair<int, int>, std::vector<size_t>> byPair;
    for (size_t t = 0; t < candidates.size(); ++t) {
        const auto& r = candidates[t].robot;
        for (int a = 0; a < 3; ++a)
            for (int b = a + 1; b < 3; ++b)
                byPair[{std::min(r[size_t(a)], r[size_t(b)]), std::max(r[size_t(a)], r[size_t(b)])}]
                    .push_back(t);
    }
    std::vector<std::map<std::pair<int, int>, int>> votes(
        static_cast<size_t>(n));  // robot: (image, who)
    const auto voteAt = [&](int robot, const Triangle& t1, const Triangle& t2, int other) {
        const auto& i1 = t1.images[size_t(vertexOf(t1, robot))];
        const auto& i2 = t2.images[size_t(vertexOf(t2, robot))];
        int shared = -1, sharedCount = 0;
        for (int a : i1)
            for (int b : i2)
                if (a == b) shared = a, ++sharedCount;
        if (sharedCount != 1) return;  // no common image, or the same angle: no information
        const int rest1 = i1[0] == shared ? i1[1] : i1[0];
        const int rest2 = i2[0] == shared ? i2[1] : i2[0];
        auto& v = votes[size_t(robot)];
        ++v[{shared, other}];
        ++v[{rest1, thirdRobot(t1, robot, other)}];
        ++v[{rest2, thirdRobot(t2, robot, other)}];
    };
    for (const auto& [pair, list] : byPair)
        for (size_t a = 0; a < list.size(); ++a)
            for (size_t b = a + 1; b < list.size(); ++b) {
                const auto& t1 = candidates[list[a]];
                const auto& t2 = candidates[list[b]];
                if (thirdRobot(t1, pair.first, pair.second) ==
                    thirdRobot(t2, pair.first, pair.second))
                    continue;  // two readings of one robot triple: they compete
                voteAt(pair.first, t1, t2, pair.second);
                voteAt(pair.second, t1, t2, pair.first);
            }
    Labels labels(static_cast<size_t>(n));
    for (int r = 0; r < n; ++r)
        labels[size_t(r)] = assign(votes[size_t(r)], s.views[size_t(r)].size());
    return labels;
}

Identification consistentTriangles(const Snapshot& s, Labels labels, double tol) {
    const int n = int(s.robots());
    Identification id;
    std::vector<std::vector<int>> imageOf(size_t(n), std::vector<int>(size_t(n), -1));
    for (int r = 0; r < n; ++r)
        for (size_t img = 0; img < labels[size_t(r)].size(); ++img)
            if (const int who = labels[size_t(r)][img]; who >= 0)
                imageOf[size_t(r)][size_t(who)] = int(img);
    std::vector<char> resolved(size_t(n), 0);
    const auto img = [&](int r, int who) { return imageOf[size_t(r)][size_t(who)]; };
    for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j) {
            if (img(i, j) < 0 || img(j, i) < 0) continue;
            for (int k = j + 1; k < n; ++k) {
                if (img(i, k) < 0 || img(j, k) < 0 || img(k, i) < 0 || img(k, j) < 0) continue;
                Triangle t{
                    {i, j, k},
                    {{{img(i, j), img(i, k)}, {img(j, i), img(j, k)}, {img(k, i), img(k, j)}}},
                    {}};
                for (size_t v = 0; v < 3; ++v)
                    t.angle[v] =
                        interiorAngle(s.views[size_t(t.robot[v])], t.images[v][0], t.images[v][1]);
                if (std::abs(t.sum() - M_PI) > tol) continue;
                id.triangles.push_back(t);
                resolved[size_t(i)] = resolved[size_t(j)] = resolved[size_t(k)] = 1;
            }
        }
    for (int r = 0; r < n; ++r)
        if (!resolved[size_t(r)]) id.unresolved.push_back(r);
    id.labels = std::move(labels);
    return id;
}

UnresolvedReason whyUnresolved(const Snapshot& s, const Identification& id, int robot) {
    const auto r = size_t(robot);
    if (s.views[r].size() < 2) return UnresolvedReason::SeesTooFew;
    size_t mutual = 0;
    for (const int w : id.labels[r])
        if (w >= 0 && std::count(id.labels[size_t(w)].begin(), id.labels[size_t(w)].end(), robot))
            ++mutual;
    return mutual < 2 ? UnresolvedReason::NotPlaced : UnresolvedReason::NoTriangle;
}

const UnresolvedReasonText& textOf(UnresolvedReason reason) {
    for (const auto& t : kUnresolvedReasons)
        if (t.reason == reason) return t;
    throw Error("omnivision: an unresolved reason without words (internal error)");
}

Identification identifyBruteForce(const Snapshot& s, const SearchOptions& o) {
    const auto candidates = bruteForceTriangles(s, o.sumTolerance);
    auto id = consistentTriangles(s, labelsByVotes(s, candidates), o.sumTolerance);
    id.candidates = candidates.size();
    return id;
}

}  // namespace mrloc::omnivision
