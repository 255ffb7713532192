#include <mrloc/common/Error.h>
#include <mrloc/omnivision/RelativeLocation.h>
#include <mrpt/core/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <deque>

namespace mrloc::omnivision {

const Triangle* findTriangle(const Identification& id, int i, int j, int k) {
    std::array<int, 3> want{i, j, k};
    std::sort(want.begin(), want.end());
    for (const auto& t : id.triangles)
        if (t.robot == want) return &t;
    return nullptr;
}

namespace {
size_t vertex(const Triangle& t, int r) {
    for (size_t v = 0; v < 3; ++v)
        if (t.robot[v] == r) return v;
    throw Error("omnivision: robot not in triangle");
}
int other(const Triangle& t, int u, int v) {
    for (int r : t.robot)
        if (r != u && r != v) return r;
    return -1;
}
std::pair<int, int> key(int i, int j) { return {std::min(i, j), std::max(i, j)}; }
}  // namespace

double angleAt(const Triangle& t, int r) { return t.angle[vertex(t, r)]; }

int sideAt(const Snapshot& s, const Triangle& t, int r, int toward) {
    // Triangle images at robot[v] are stored in the order of the other two robots (i < j).
    const size_t v = vertex(t, r);
    const int third = other(t, r, toward);
    int others[2], n = 0;
    for (int x : t.robot)
        if (x != r) others[n++] = x;
    const int imgToward = t.images[v][others[0] == toward ? 0 : 1];
    const int imgThird = t.images[v][others[0] == third ? 0 : 1];
    return signedAngle(s.views[size_t(r)], imgToward, imgThird) >= 0 ? 1 : -1;
}

std::vector<std::optional<double>> headingsFromLayout(
    const Snapshot& s, const Labels& labels, const std::vector<std::optional<Vec2>>& position) {
    std::vector<std::optional<double>> out(position.size());
    for (size_t o = 0; o < position.size(); ++o) {
        if (!position[o] || o >= labels.size()) continue;
        double sx = 0, sy = 0;
        for (size_t img = 0; img < labels[o].size(); ++img) {
            const int t = labels[o][img];
            if (t < 0 || !position[size_t(t)]) continue;
            const Vec2 d = *position[size_t(t)] - *position[o];
            const double h = std::atan2(d.y(), d.x()) - s.views[o].bearings[img];
            sx += std::cos(h), sy += std::sin(h);
        }
        if (sx != 0 || sy != 0) out[o] = std::atan2(sy, sx);
    }
    return out;
}

Solution solveFromBaseline(const Snapshot& s, const Identification& id, int a, int b,
                           double baseline) {
    const size_t n = s.robots();
    Solution out;
    out.a = a, out.b = b, out.baseline = baseline;
    out.position.assign(n, std::nullopt);
    const bool shared = std::any_of(id.triangles.begin(), id.triangles.end(), [&](const auto& t) {
        return std::count(t.robot.begin(), t.robot.end(), a) &&
               std::count(t.robot.begin(), t.robot.end(), b);
    });
    if (!shared)
        throw Error(mrpt::format("omnivision: robots %d and %d are in no common triangle", a, b));
    // Sine rule, breadth first from |AB|.
    std::deque<std::pair<int, int>> queue{key(a, b)};
    out.distance[key(a, b)] = baseline;
    while (!queue.empty()) {
        const auto [i, j] = queue.front();
        queue.pop_front();
        const double dij = out.distance.at({i, j});
        for (const auto& t : id.triangles) {
            if (std::find(t.robot.begin(), t.robot.end(), i) == t.robot.end() ||
                std::find(t.robot.begin(), t.robot.end(), j) == t.robot.end())
                continue;
            const int k = other(t, i, j);
            if (out.distance.count(key(i, k)) && out.distance.count(key(j, k))) continue;
            const auto [dik, djk] = sineRule(dij, angleAt(t, i), angleAt(t, j), angleAt(t, k));
            for (const auto& [e, d] : {std::pair{key(i, k), dik}, std::pair{key(j, k), djk}})
                if (out.distance.emplace(e, d).second) queue.push_back(e);
        }
    }
    // Layout: A at the origin, B on the x axis; every other robot by eq. (3) on the first
    // triangle it shares with two placed robots.
    out.position[size_t(a)] = Vec2(0, 0);
    out.position[size_t(b)] = Vec2(baseline, 0);
    for (bool grew = true; grew;) {
        grew = false;
        for (const auto& t : id.triangles)
            for (size_t v = 0; v < 3; ++v) {
                const int x = t.robot[v], u = t.robot[(v + 1) % 3], w = t.robot[(v + 2) % 3];
                if (out.position[size_t(x)] || !out.position[size_t(u)] || !out.position[size_t(w)])
                    continue;
                const Vec2 pu = *out.position[size_t(u)], pw = *out.position[size_t(w)];
                const Vec2 axis = pw - pu;
                const auto dirs = lineDirections(angleAt(t, u), angleAt(t, w), sideAt(s, t, u, w));
                const Vec2 local = unitBaselinePoint(dirs);  // frame: u at 0, w at (1, 0)
                const Eigen::Rotation2Dd rot(std::atan2(axis.y(), axis.x()));
                out.position[size_t(x)] = pu + axis.norm() * (rot * local);
                grew = true;
            }
    }
    out.heading = headingsFromLayout(s, id.labels, out.position);
    return out;
}

std::vector<int> commonWitnesses(const Identification& before, const Identification& after, int a,
                                 int b) {
    std::vector<int> out;
    const int n = int(before.labels.size());
    for (int c = 0; c < n; ++c)
        if (c != a && c != b && findTriangle(before, a, b, c) && findTriangle(after, a, b, c))
            out.push_back(c);
    return out;
}

ProposedSolution proposedMethod(const Snapshot& before, const Identification& idBefore,
                                const Snapshot& after, const Identification& idAfter, int a, int b,
                                const std::vector<double>& travelled) {
    const auto witnesses = commonWitnesses(idBefore, idAfter, a, b);
    if (witnesses.empty())
        throw Error(
            "omnivision: the stopped robots share no robot that both see, and that sees "
            "them, at t_b and t_e: stop another pair (paper 000 section 3)");
    ProposedSolution out;
    out.moving = witnesses.front();
    for (int c : witnesses)
        if (travelled[size_t(c)] > travelled[size_t(out.moving)]) out.moving = c;
    const int c = out.moving;
    out.travelled = travelled[size_t(c)];
    const Triangle& tb = *findTriangle(idBefore, a, b, c);
    const Triangle& te = *findTriangle(idAfter, a, b, c);
    const auto dirsBefore =
        lineDirections(angleAt(tb, a), angleAt(tb, b), sideAt(before, tb, a, b));
    const auto dirsAfter = lineDirections(angleAt(te, a), angleAt(te, b), sideAt(after, te, a, b));
    const double L = baselineFromMotion(dirsBefore, dirsAfter, out.travelled);  // eq. (8)
    out.before = solveFromBaseline(before, idBefore, a, b, L);
    out.after = solveFromBaseline(after, idAfter, a, b, L);
    return out;
}

}  // namespace mrloc::omnivision
