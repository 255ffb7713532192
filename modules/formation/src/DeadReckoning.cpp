#include <mrloc/common/Error.h>
#include <mrloc/formation/DeadReckoning.h>

#include <algorithm>

namespace mrloc::formation {

DeadReckoner::DeadReckoner(const DeadReckoningOptions& o, double wheelRadius, const TPoint2D& start)
    : o_(o), wheelRadius_(wheelRadius), estimate_(start) {
    if (!(o.dt > 0) || !(o.headingTau > 0) || !(wheelRadius > 0))
        throw Error(
            "formation: dead reckoning needs a positive period, correlation time and wheel "
            "radius");
    gyro_ = o.headingModel == DeadReckoningOptions::HeadingModel::Gyro;
    const double sigma = gyro_ ? o.headingSigma / o.headingTau : o.headingSigma;
    phi_ = std::exp(-o.dt / o.headingTau);
    drive_ = sigma * std::sqrt(1 - phi_ * phi_);
    // the heading is aligned at the start, and a gyro's bias was measured standing still
    gm_ = 0;
}

void DeadReckoner::update(double trueHeading, double distance,
                          mrpt::random::CRandomGenerator& rng) {
    gm_ = phi_ * gm_ + drive_ * rng.drawGaussian1D_normalized();
    headingError_ = gyro_ ? headingError_ + gm_ * o_.dt : gm_;  // seed 003 sec. 5 / sec. 4.2
    sensedHeading_ =
        trueHeading + headingError_ + o_.headingWhite * rng.drawGaussian1D_normalized();
    // seed 003 eq. 3: v = (R + dR)(1 + s) w + n, w the wheel's true rotational speed
    const double wheel = distance / o_.dt / wheelRadius_;
    sensedSpeed_ = (wheelRadius_ + o_.radiusBias) * (1 + o_.scaleFactor) * wheel +
                   o_.speedNoise * rng.drawGaussian1D_normalized();
    estimate_ = advance(estimate_, sensedHeading_, sensedSpeed_, o_.dt);
}

TPoint2D DeadReckoner::advance(const TPoint2D& from, double sensedHeading, double sensedSpeed,
                               double dt) {
    return from + TPoint2D{std::cos(sensedHeading), std::sin(sensedHeading)} * (sensedSpeed * dt);
}

std::vector<ErrorSample> deadReckon(const std::vector<TPoint2D>& route, double wheelRadius,
                                    double wheelSpeed, const DeadReckoningOptions& o,
                                    mrpt::random::CRandomGenerator& rng) {
    const double v = wheelRadius * wheelSpeed;
    if (!(v > 0) || !(o.dt > 0) || !(o.headingTau > 0))
        throw Error(
            "formation: dead reckoning needs a positive speed, period and correlation time");
    if (route.size() < 2) throw Error("formation: a route needs at least 2 points");
    for (size_t w = 0; w < route.size(); ++w)
        if (!std::isfinite(route[w].x) || !std::isfinite(route[w].y))
            throw Error("formation: route point " + std::to_string(w + 1) + " is not finite");
    DeadReckoner robot(o, wheelRadius, route.front());
    std::vector<ErrorSample> out{{0, 0}};
    double t = 0;
    for (size_t leg = 0; leg + 1 < route.size(); ++leg) {
        const TPoint2D a = route[leg], b = route[leg + 1];
        const double length = (b - a).norm();
        const double heading = std::atan2(b.y - a.y, b.x - a.x);
        const long steps = std::max(1L, std::lround(length / (v * o.dt)));
        for (long k = 1; k <= steps; ++k) {
            robot.update(heading, length / double(steps), rng);
            t += o.dt;
            const TPoint2D truth = a + (b - a) * (double(k) / double(steps));
            out.push_back({t, (robot.estimate() - truth).norm()});
        }
    }
    return out;
}

}  // namespace mrloc::formation
