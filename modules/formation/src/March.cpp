#include <mrloc/common/Error.h>
#include <mrloc/formation/March.h>

#include <cmath>

namespace mrloc::formation {

double drawAxisError(double mean, double sd, mrpt::random::CRandomGenerator& rng) {
    if (!(mean > 0) || !(sd > 0))
        throw Error("formation: vertex error mean and sd must be positive");
    // gamma(shape k, scale theta): mean k theta, variance k theta^2
    const double k = (mean / sd) * (mean / sd), theta = sd * sd / mean;
    // Marsaglia and Tsang (2000); for k < 1, boost by one and scale by U^(1/k)
    const double shape = k < 1 ? k + 1 : k;
    const double d = shape - 1.0 / 3, c = 1 / std::sqrt(9 * d);
    double g = 0;
    for (;;) {
        double x, v;
        do {
            x = rng.drawGaussian1D_normalized();
            v = 1 + c * x;
        } while (v <= 0);
        v = v * v * v;
        const double u = rng.drawUniform(0.0, 1.0);
        if (u < 1 - 0.0331 * x * x * x * x ||
            std::log(u) < 0.5 * x * x + d * (1 - v + std::log(v))) {
            g = d * v;
            break;
        }
    }
    if (k < 1) g *= std::pow(rng.drawUniform(0.0, 1.0), 1 / k);
    const double sign = rng.drawUniform(0.0, 1.0) < 0.5 ? -1 : 1;
    return sign * g * theta;
}

namespace {

double pathLength(const TPoint2D& from, const std::vector<TPoint2D>& path) {
    double length = 0;
    TPoint2D at = from;
    for (const auto& p : path) length += (p - at).norm(), at = p;
    return length;
}

}  // namespace

TPoint2D algorithmOneVertex(const TPoint2D& b1, const TPoint2D& b2, const TPoint2D& anchor,
                            double side) {
    // The rear camera's focal length in pixels for d_t: the ideal vertex sees b1 and b2 at
    // depth h and lateral +-side/2, d_t pixels off the axis: f = d_t h / (side / 2). Only
    // the ratio matters, so d_t = 1.
    const double h = side * std::sqrt(3.0) / 2;
    const double f = h / (side / 2);
    // The residuals of Algorithm 1's two conditions at robot position R: b1 at +d_t and b2
    // at -d_t (lateral image offsets from the anchor on the optical axis).
    const auto residual = [&](const TPoint2D& R) {
        const TPoint2D axis = (anchor - R) * (1 / (anchor - R).norm());
        const auto lateral = [&](const TPoint2D& p) {
            const TPoint2D d = p - R;
            return f * (axis.x * d.y - axis.y * d.x) / (axis.x * d.x + axis.y * d.y);
        };
        const double l1 = lateral(b1), l2 = lateral(b2);
        return TPoint2D{l1 + l2, std::abs(l1 - l2) - 2};
    };
    TPoint2D R = b1 + b2 - anchor;     // start: the reflection (exact for a perfect triangle)
    for (int it = 0; it < 20; ++it) {  // Newton, numeric Jacobian
        const TPoint2D r0 = residual(R);
        if (r0.norm() < 1e-12) break;
        const double e = 1e-7 * side;
        const TPoint2D jx = (residual(R + TPoint2D{e, 0}) - r0) * (1 / e);
        const TPoint2D jy = (residual(R + TPoint2D{0, e}) - r0) * (1 / e);
        const double det = jx.x * jy.y - jy.x * jx.y;
        if (std::abs(det) < 1e-15) break;
        R = R - TPoint2D{(jy.y * r0.x - jy.x * r0.y) / det, (-jx.y * r0.x + jx.x * r0.y) / det};
    }
    return R;
}

StepError stepError(const TPoint2D& b1, const TPoint2D& b2, const TPoint2D& anchor,
                    const TPoint2D& end) {
    const TPoint2D vertex = b1 + b2 - anchor;  // the real anchor reflected
    const TPoint2D along = (b2 - b1) * (1 / (b2 - b1).norm());
    const TPoint2D d = end - vertex;
    return {d.x * along.x + d.y * along.y, -d.x * along.y + d.y * along.x};
}

TPoint2D moveEnd(const Move& move, const std::vector<TPoint2D>& ideal,
                 const std::vector<TPoint2D>& actual, const MarchOptions& options,
                 const VertexErrorModel& errors, mrpt::random::CRandomGenerator& rng) {
    const auto& [i, j] = move.base;
    const size_t k = move.anchor;
    // seed 003 Algorithm 1 puts the robot at the vertex the real beacons make, up to the
    // per-step error along and across the base (seed 003 fig. 10-11)
    TPoint2D vertex;
    switch (options.carry) {
        case MarchOptions::Carry::Base:
            vertex = move.target + ((actual[i] - ideal[i]) + (actual[j] - ideal[j])) * 0.5;
            break;
        case MarchOptions::Carry::Reflection:
            vertex = actual[i] + actual[j] - actual[k];
            break;
        case MarchOptions::Carry::AlgorithmOne:
            vertex = algorithmOneVertex(actual[i], actual[j], actual[k], options.formation.side);
            break;
    }
    const TPoint2D along = (actual[j] - actual[i]) * (1 / (actual[j] - actual[i]).norm());
    const TPoint2D across{-along.y, along.x};
    const double lateral = drawAxisError(errors.lateralMean, errors.lateralSd, rng);
    const double longitudinal = drawAxisError(errors.longitudinalMean, errors.longitudinalSd, rng);
    return vertex + along * lateral + across * longitudinal;
}

MarchResult march(size_t robots, const std::vector<TPoint2D>& route,
                  const std::vector<Obstacle>& obstacles, const MarchOptions& options,
                  const VertexErrorModel& errors, mrpt::random::CRandomGenerator& rng) {
    const double s = options.formation.side;
    const double speed = options.wheelRadius * options.wheelSpeed;
    if (!(speed > 0) || !std::isfinite(speed))
        throw Error("formation: the robots' speed must be positive");
    for (size_t w = 0; w < route.size(); ++w)
        if (!std::isfinite(route[w].x) || !std::isfinite(route[w].y))
            throw Error("formation: route point " + std::to_string(w + 1) + " is not finite");
    MarchResult r;
    r.ideal = r.actual = initialStrip(robots, s);
    double time = 0;
    RoutePlanner planner(route, options.formation, options.maxMoves);  // the team's planner
    for (;;) {
        const auto outcome = planner.plan(r.ideal, obstacles);
        if (outcome == RoutePlanner::Outcome::Stuck) return r;  // arrived stays false
        if (outcome == RoutePlanner::Outcome::Arrived) break;
        const auto& move = planner.move();
        const size_t m = move->robot;
        const TPoint2D end = moveEnd(*move, r.ideal, r.actual, options, errors, rng);
        time += pathLength(r.ideal[m], move->path) / speed;
        r.ideal[m] = move->target;
        r.actual[m] = end;
        r.moves.push_back({time, m, r.ideal[m], r.actual[m]});
    }
    r.arrived = true;
    return r;
}

}  // namespace mrloc::formation
