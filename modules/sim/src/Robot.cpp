#include <mrloc/common/IniSection.h>
#include <mrloc/sim/Robot.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/poses/CPose3D.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace mrloc::sim {

void RobotOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& src,
                                      const std::string& section) {
    common::IniSection s(src, section);
    if (startInSection) {
        const auto st = s.requireReals("start", 3);
        start = mrpt::poses::CPose2D(st[0], st[1], mrpt::DEG2RAD(st[2]));
    }
    waypoints.clear();
    std::stringstream list(s.text("waypoints", ""));
    for (std::string item; std::getline(list, item, ',');) {
        std::istringstream in(item);
        double x, y;
        std::string extra;
        if (!(in >> x >> y) || (in >> extra) || !std::isfinite(x) || !std::isfinite(y))
            s.fail("waypoints", "expected 'x y, x y, ...', got '" + item + "'");
        waypoints.push_back({x, y});
    }
    loop = s.flag("loop", loop);
    speed = s.real("speed", speed, 1e-3, 10);
    maxTurnRate = s.real("max_turn_rate", maxTurnRate, 1e-3, 100);
    odometryRate = s.real("odometry_rate", odometryRate, 0.1, 1000);
    odometrySigmaXY = s.real("odometry_sigma_xy", odometrySigmaXY, 0, 1);
    odometrySigmaPhi = s.real("odometry_sigma_phi", odometrySigmaPhi, 0, 1);
    odometrySigmaPhiPerMetre = s.real("odometry_sigma_phi_per_m", odometrySigmaPhiPerMetre, 0, 1);
    odometryScaleError = s.real("odometry_scale_error", odometryScaleError, -0.5, 0.5);
    odometryScaleErrorSigma = s.real("odometry_scale_error_sigma", odometryScaleErrorSigma, 0, 0.5);
    odometryHeadingDrift = mrpt::DEG2RAD(s.real("odometry_heading_drift", 0, -90, 90));
    odometryHeadingDriftSigma = mrpt::DEG2RAD(s.real("odometry_heading_drift_sigma", 0, 0, 90));
    actuationSigmaV = s.real("actuation_sigma_v", actuationSigmaV, 0, 1);
    actuationSigmaW = s.real("actuation_sigma_w", actuationSigmaW, 0, 10);
    for (const auto& k : methodKeys) s.allowKey(k);
    s.finish();
}

void RobotOptions::saveToConfigFile(mrpt::config::CConfigFileBase& t,
                                    const std::string& section) const {
    if (startInSection)
        t.write(section, "start",
                mrpt::format("%g %g %g", start.x(), start.y(), mrpt::RAD2DEG(start.phi())));
    std::string wp;
    for (const auto& p : waypoints)
        wp += (wp.empty() ? "" : ", ") + mrpt::format("%g %g", p.x, p.y);
    t.write(section, "waypoints", wp);
    t.write(section, "loop", loop);
    t.write(section, "speed", speed);
    t.write(section, "max_turn_rate", maxTurnRate);
    t.write(section, "odometry_rate", odometryRate);
    t.write(section, "odometry_sigma_xy", odometrySigmaXY);
    t.write(section, "odometry_sigma_phi", odometrySigmaPhi);
    t.write(section, "odometry_sigma_phi_per_m", odometrySigmaPhiPerMetre);
    t.write(section, "odometry_scale_error", odometryScaleError);
    t.write(section, "odometry_scale_error_sigma", odometryScaleErrorSigma);
    t.write(section, "odometry_heading_drift", mrpt::RAD2DEG(odometryHeadingDrift));
    t.write(section, "odometry_heading_drift_sigma", mrpt::RAD2DEG(odometryHeadingDriftSigma));
    t.write(section, "actuation_sigma_v", actuationSigmaV);
    t.write(section, "actuation_sigma_w", actuationSigmaW);
}

Robot::Robot(RobotOptions options) : options_(std::move(options)), pose_(options_.start) {}

void Robot::setWaypoints(std::vector<mrpt::math::TPoint2D> waypoints, bool loop) {
    options_.waypoints = std::move(waypoints);
    options_.loop = loop;
    next_ = 0;
    velocity_.reset();
}

double arrivalRadius(double speed, double dt) { return std::max(0.02, speed * dt); }

double Robot::arrivalRadius(double dt) const { return sim::arrivalRadius(options_.speed, dt); }

void Robot::drive(double v, double w) {
    velocity_ = std::make_pair(std::clamp(v, -options_.speed, options_.speed),
                               std::clamp(w, -options_.maxTurnRate, options_.maxTurnRate));
}

std::pair<double, double> Robot::command(double dt) {
    if (velocity_) return {velocity_->first * dt, velocity_->second * dt};
    auto& wps = options_.waypoints;
    const double reach = arrivalRadius(dt);
    while (next_ < wps.size() &&
           std::hypot(wps[next_].x - pose_.x(), wps[next_].y - pose_.y()) < reach) {
        ++next_;
        if (next_ == wps.size() && options_.loop) next_ = 0;
    }
    if (next_ >= wps.size()) return {0, 0};  // route done: stand still
    const auto& target = wps[next_];
    const double bearing = std::atan2(target.y - pose_.y(), target.x - pose_.x());
    const double err = mrpt::math::wrapToPi(bearing - pose_.phi());
    const double maxTurn = options_.maxTurnRate * dt;
    // Slow down while facing away from the waypoint, so that turns stay tight.
    return {options_.speed * std::max(0.0, std::cos(err)) * dt, std::clamp(err, -maxTurn, maxTurn)};
}

mrpt::poses::CPose2D Robot::step(double dt, mrpt::random::CRandomGenerator& rng) {
    auto [v, w] = command(dt);  // this step's distance (m) and turn (rad)
    if (v == 0 && w == 0) return {};
    if (options_.actuationSigmaV > 0) v *= 1 + rng.drawGaussian1D(0, options_.actuationSigmaV);
    if (options_.actuationSigmaW > 0) w += rng.drawGaussian1D(0, options_.actuationSigmaW) * dt;
    // Exact unicycle arc for constant (v, w) over dt.
    const mrpt::poses::CPose2D delta =
        std::abs(w) < 1e-12
            ? mrpt::poses::CPose2D(v, 0, 0)
            : mrpt::poses::CPose2D(v / w * std::sin(w), v / w * (1 - std::cos(w)), w);
    pose_ = pose_ + delta;
    return delta;
}

}  // namespace mrloc::sim
