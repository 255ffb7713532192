#include <mrloc/common/Error.h>
#include <mrloc/common/Polygon.h>
#include <mrloc/formation/Formation.h>

#include <algorithm>
#include <cmath>
#include <tuple>

namespace mrloc::formation {

namespace {

/** Three points stand on an equilateral triangle of side s, within 1 % of s. */
bool equilateral(const TPoint2D& a, const TPoint2D& b, const TPoint2D& c, double s) {
    const double tol = 0.01 * s;
    return std::abs((a - b).norm() - s) <= tol && std::abs((b - c).norm() - s) <= tol &&
           std::abs((c - a).norm() - s) <= tol;
}

/** Every robot stands on at least one triangle of the formation. */
bool onePiece(const std::vector<TPoint2D>& p, double s) {
    const size_t n = p.size();
    std::vector<bool> covered(n, false);
    for (size_t i = 0; i < n; ++i)
        for (size_t j = i + 1; j < n; ++j)
            for (size_t k = j + 1; k < n; ++k)
                if (equilateral(p[i], p[j], p[k], s)) covered[i] = covered[j] = covered[k] = true;
    return std::all_of(covered.begin(), covered.end(), [](bool c) { return c; });
}

}  // namespace

std::vector<TPoint2D> initialStrip(size_t robots, double side) {
    const double height = side * std::sqrt(3.0) / 2;
    std::vector<TPoint2D> out;
    for (size_t n = 0; n < robots; ++n) {
        const double i = double(n / 2);
        out.push_back(n % 2 == 0 ? TPoint2D{side / 2 + side * i, 0} : TPoint2D{side * i, height});
    }
    return out;
}

double arrivalHeading(const Move& m, const std::vector<TPoint2D>& believed) {
    const TPoint2D& anchor = believed[m.anchor];
    return std::atan2(m.target.y - anchor.y, m.target.x - anchor.x);
}

std::vector<TPoint2D> innerPath(const std::array<TPoint2D, 3>& beacons, const TPoint2D& from,
                                const TPoint2D& target) {
    // seed 003 Algorithm 2, step 1: the centre points between the beacons
    const std::array<TPoint2D, 3> centres{(beacons[0] + beacons[1]) * 0.5,
                                          (beacons[1] + beacons[2]) * 0.5,
                                          (beacons[2] + beacons[0]) * 0.5};
    const auto nearest = [&centres](const TPoint2D& p) {
        return *std::min_element(
            centres.begin(), centres.end(),
            [&p](const TPoint2D& a, const TPoint2D& b) { return (a - p).norm() < (b - p).norm(); });
    };
    std::vector<TPoint2D> path{nearest(from)};                                             // step 2
    if (const TPoint2D last = nearest(target); last != path.back()) path.push_back(last);  // step 3
    path.push_back(target);                                                                // step 4
    return path;
}

bool clearOf(const TPoint2D& from, const std::vector<TPoint2D>& path,
             const std::vector<Obstacle>& obstacles, double margin) {
    TPoint2D at = from;
    for (const auto& next : path) {
        for (const auto& o : obstacles)
            if (common::distanceToSegment(o.centre, at, next) < o.radius + margin) return false;
        at = next;
    }
    return true;
}

std::optional<Move> nextMove(const std::vector<TPoint2D>& believed, const TPoint2D& destination,
                             const std::vector<Obstacle>& obstacles,
                             const FormationOptions& options) {
    const size_t n = believed.size();
    const double s = options.side;
    if (n < 4) throw Error("formation: at least 4 robots, got " + std::to_string(n));
    if (!(s > 0) || !std::isfinite(s))
        throw Error("formation: the triangles' side must be a positive length");
    if (!std::isfinite(destination.x) || !std::isfinite(destination.y))
        throw Error("formation: the destination is not a finite point");
    for (size_t i = 0; i < n; ++i)
        if (!std::isfinite(believed[i].x) || !std::isfinite(believed[i].y))
            throw Error("formation: robot " + std::to_string(i) + "'s position is not finite");
    // Movers, farthest from the destination first (seed 003 sec. 3, "snake-like" marching).
    std::vector<size_t> movers(n);
    for (size_t i = 0; i < n; ++i) movers[i] = i;
    std::stable_sort(movers.begin(), movers.end(), [&](size_t a, size_t b) {
        return (believed[a] - destination).norm() > (believed[b] - destination).norm();
    });
    for (const size_t m : movers) {
        const double now = (believed[m] - destination).norm();
        // The candidate vertices: a beacon reflected across the side of two others.
        std::vector<std::tuple<double, size_t, Move>> candidates;  // distance, order, move
        for (size_t i = 0; i < n; ++i)
            for (size_t j = i + 1; j < n; ++j)
                for (size_t k = 0; k < n; ++k) {
                    if (i == m || j == m || k == m || k == i || k == j) continue;
                    if (!equilateral(believed[i], believed[j], believed[k], s)) continue;
                    Move move;
                    move.robot = m;
                    move.base = {i, j};
                    move.anchor = k;
                    move.target = believed[i] + believed[j] - believed[k];
                    const bool free = std::none_of(
                        believed.begin(), believed.end(),
                        [&](const TPoint2D& p) { return (p - move.target).norm() < s / 2; });
                    // a move must bring its robot nearer: without it, a robot blocked by an
                    // obstacle and the next one can swap places for ever (doc/formation.md)
                    if (!free || (move.target - destination).norm() >= now - 1e-9 * s) continue;
                    auto after = believed;
                    after[m] = move.target;
                    if (!onePiece(after, s)) continue;
                    move.path = innerPath({believed[i], believed[j], believed[k]}, believed[m],
                                          move.target);
                    candidates.emplace_back((move.target - destination).norm(), candidates.size(),
                                            std::move(move));
                }
        std::sort(candidates.begin(), candidates.end(), [](const auto& a, const auto& b) {
            return std::tie(std::get<0>(a), std::get<1>(a)) <
                   std::tie(std::get<0>(b), std::get<1>(b));
        });
        // The nearest whose path keeps out of the safety zones (seed 003 fig. 6).
        for (auto& [distance, order, move] : candidates)
            if (clearOf(believed[m], move.path, obstacles, options.safetyMargin))
                return std::move(move);
    }
    return std::nullopt;
}

RoutePlanner::RoutePlanner(std::vector<TPoint2D> route, FormationOptions options, size_t maxMoves)
    : route_(std::move(route)), options_(options), maxMoves_(maxMoves) {
    if (route_.empty()) throw Error("formation: the route needs a destination");
}

RoutePlanner::Outcome RoutePlanner::plan(const std::vector<TPoint2D>& believed,
                                         const std::vector<Obstacle>& obstacles) {
    move_.reset();
    const double reach = options_.side / std::sqrt(3.0) * (1 + 1e-9);
    const auto reached = [&](const TPoint2D& wp) {
        return std::any_of(believed.begin(), believed.end(),
                           [&](const TPoint2D& p) { return (p - wp).norm() <= reach; });
    };
    while (next_ < route_.size() && reached(route_[next_])) ++next_;
    if (next_ == route_.size()) return Outcome::Arrived;
    if (planned_ >= maxMoves_)
        throw Error("formation: the route needs more than " + std::to_string(maxMoves_) +
                    " moves (max_moves)");
    move_ = nextMove(believed, route_[next_], obstacles, options_);
    if (!move_) return Outcome::Stuck;
    ++planned_;
    return Outcome::Move;
}

}  // namespace mrloc::formation
