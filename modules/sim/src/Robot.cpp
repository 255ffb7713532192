#include <mrloc/common/KeyTable.h>
#include <mrloc/sim/Robot.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/poses/CPose3D.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace mrloc::sim {

namespace {

void loadWaypoints(common::IniSection& s, RobotOptions& r) {
    r.waypoints.clear();
    std::stringstream list(s.text("waypoints", ""));
    for (std::string item; std::getline(list, item, ',');) {
        std::istringstream in(item);
        double x, y;
        std::string extra;
        if (!(in >> x >> y) || (in >> extra) || !std::isfinite(x) || !std::isfinite(y))
            s.fail("waypoints", "expected 'x y, x y, ...', got '" + item + "'");
        r.waypoints.push_back({x, y});
    }
}

std::string waypointsText(const RobotOptions& r) {
    std::string wp;
    for (const auto& p : r.waypoints)
        wp += (wp.empty() ? "" : ", ") + common::keyListText({p.x, p.y});
    return wp;
}

}  // namespace

const common::KeyTable<RobotOptions>& RobotOptions::keys() {
    using R = RobotOptions;
    static const auto table =
        common::KeyTable<R>("robot.<name>")
            .custom(
                "start", "m m deg", "", "`x y heading_deg`",
                [](common::IniSection& s, R& r) {
                    if (!r.startInSection) return;  // the scenario sets it: the key is an error
                    const auto st = s.requireReals("start", 3);
                    r.start = mrpt::poses::CPose2D(st[0], st[1], mrpt::DEG2RAD(st[2]));
                },
                [](const R& r) -> std::optional<std::string> {
                    if (!r.startInSection) return std::nullopt;
                    return common::keyListText({r.start.x(), r.start.y()}) + " " +
                           common::keyDegreesText(r.start.phi());
                },
                "(required)")
            .custom("waypoints", "m", "", "`x y, x y, ...`; none: the robot stands at `start`",
                    loadWaypoints, [](const R& r) { return waypointsText(r); })
            .flag("loop", MRLOC_KEY_FIELD(loop), "start over at the first waypoint")
            .real("speed", MRLOC_KEY_FIELD(speed), {1e-3, 10}, "m/s", "driving speed")
            .real("max_turn_rate", MRLOC_KEY_FIELD(maxTurnRate), {1e-3, 100}, "rad/s",
                  "the fastest turn towards a waypoint")
            .real("odometry_rate", MRLOC_KEY_FIELD(odometryRate), {0.1, 1000}, "Hz",
                  "odometry readings")
            .real("odometry_sigma_xy", MRLOC_KEY_FIELD(odometrySigmaXY), {0, 1}, "m/m",
                  "odometry noise per metre travelled")
            .real("odometry_sigma_phi", MRLOC_KEY_FIELD(odometrySigmaPhi), {0, 1}, "rad/rad",
                  "heading noise per radian turned")
            .real("odometry_sigma_phi_per_m", MRLOC_KEY_FIELD(odometrySigmaPhiPerMetre), {0, 1},
                  "rad/m", "heading noise per metre travelled")
            .real("odometry_scale_error", MRLOC_KEY_FIELD(odometryScaleError), {-0.5, 0.5}, "",
                  "systematic: every distance odometry reads is (1 + this) times the true one "
                  "(a wheel radius error)")
            .real("odometry_scale_error_sigma", MRLOC_KEY_FIELD(odometryScaleErrorSigma), {0, 0.5},
                  "",
                  "drawn once per run: the scale error is N(`odometry_scale_error`, this); 0: "
                  "none drawn")
            .degrees("odometry_heading_drift", MRLOC_KEY_FIELD(odometryHeadingDrift), {-90, 90},
                     "systematic heading drift per metre driven (unequal wheels); deg/m")
            .degrees("odometry_heading_drift_sigma", MRLOC_KEY_FIELD(odometryHeadingDriftSigma),
                     {0, 90}, "drawn once per run, per metre, as above; deg/m")
            .real("actuation_sigma_v", MRLOC_KEY_FIELD(actuationSigmaV), {0, 1}, "",
                  "relative noise on the commanded speed each step (0: none drawn)")
            .real("actuation_sigma_w", MRLOC_KEY_FIELD(actuationSigmaW), {0, 10}, "rad/s",
                  "noise on the commanded turn rate each step (0: none drawn)");
    return table;
}

void RobotOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& src,
                                      const std::string& section) {
    common::IniSection s(src, section);
    keys().load(s, *this);
    for (const auto& k : methodKeys) s.allowKey(k);
    s.finish();
}

void RobotOptions::saveToConfigFile(mrpt::config::CConfigFileBase& t,
                                    const std::string& section) const {
    keys().save(*this, t, section);
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
