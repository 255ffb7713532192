#include <mrloc/beacons/BeaconPayload.h>
#include <mrloc/common/KeyTable.h>
#include <mrpt/core/format.h>
#include <mrpt/math/wrap2pi.h>

#include <algorithm>

namespace mrloc::beacons {

namespace {
/** Where a receiver mounted at `onRobot` is when the robot is at `pose`. */
mrpt::math::TPoint3D receiverAt(const mrpt::poses::CPose2D& pose,
                                const mrpt::math::TPoint3D& onRobot) {
    return mrpt::poses::CPose3D(pose).composePoint(onRobot);
}
}  // namespace

const common::KeyTable<BeaconRobotOptions>& BeaconRobotOptions::keys() {
    using R = BeaconRobotOptions;
    static const auto table =
        common::KeyTable<R>("robot.<name>")
            .custom(
                "receiver", "m", "", "(beacons) the beacon receiver on the robot, `x y z`",
                [](common::IniSection& s, R& r) {
                    const auto rc =
                        s.reals("receiver", {r.receiver.x, r.receiver.y, r.receiver.z}, 3);
                    r.receiver = {rc[0], rc[1], rc[2]};
                },
                [](const R& r) {
                    return common::keyListText({r.receiver.x, r.receiver.y, r.receiver.z});
                })
            .real("beacon_rate", MRLOC_KEY_FIELD(beaconRate), {0.01, 1000}, "Hz",
                  "(beacons) most ranging epochs per second the robot asks the RF beacon for")
            .integer("ranging_epochs", MRLOC_KEY_FIELD(rangingEpochs), 0, 1000000000L, "",
                     "(beacons) stops asking after this many epochs (0: never); paper 001's 10 "
                     "trials per point")
            .custom(
                "ranging_pause", "s", "",
                "(beacons) `t0 t1`: asks for no ranging epoch from t0 to t1 s after the start "
                "(out of the beacons' reach: a gap in the ranges)",
                [](common::IniSection& s, R& r) {
                    if (!s.has("ranging_pause")) return;
                    const auto v = s.reals("ranging_pause", {}, 2);
                    if (!(v[0] >= 0 && v[1] > v[0])) s.fail("ranging_pause", "needs 0 <= t0 < t1");
                    r.pauseStart = v[0], r.pauseEnd = v[1];
                },
                [](const R& r) -> std::optional<std::string> {
                    if (r.pauseEnd <= r.pauseStart) return std::nullopt;
                    return common::keyListText({r.pauseStart, r.pauseEnd});
                });
    return table;
}

std::vector<std::string> BeaconRobotOptions::keyNames() {
    std::vector<std::string> names;
    for (const auto& k : keys().docs().keys) names.push_back(k.name);
    return names;
}

void BeaconRobotOptions::load(const mrpt::config::CConfigFileBase& ini, const std::string& robot) {
    common::IniSection s(ini, "robot." + robot);  // the simulator checks the other keys
    keys().load(s, *this);
}

void BeaconRobotOptions::save(mrpt::config::CConfigFileBase& t, const std::string& robot) const {
    keys().save(*this, t, "robot." + robot);
}

BeaconPayload::BeaconPayload(const mrpt::config::CConfigFileBase& ini, const BeaconMap& beacons,
                             SensorOptions sensors, UltrasonicOptions ultrasonic,
                             std::vector<BeaconRobotOptions> robots)
    : onboard_(ini),
      beacons_(beacons),
      sensors_(sensors),
      ultrasonic_(ultrasonic),
      robots_(std::move(robots)) {}

void BeaconPayload::onObservation(const mrpt::obs::CObservation::Ptr& obs) {
    onboard_.localizer.process(obs);
}

void BeaconPayload::fireDue(sim::Step& step) {
    if (!ranging_->inEpoch()) return;
    const size_t i = epochRobot_;
    const sim::Robot& robot = step.fleet.robot(i);
    const double t = step.t;
    // A shot falls between two steps: the receiver is where the robot was at that time.
    const auto receiverAtTime = [&](double when) {
        const double a = std::clamp(1.0 - (t - when) / step.dt, 0.0, 1.0);
        const auto& p0 = step.fleet.previousPose(i);
        const auto& p1 = robot.pose();
        const mrpt::poses::CPose2D p(p0.x() + a * (p1.x() - p0.x()), p0.y() + a * (p1.y() - p0.y()),
                                     p0.phi() + a * mrpt::math::wrapToPi(p1.phi() - p0.phi()));
        return receiverAt(p, robots_[i].receiver);
    };
    auto obs = ranging_->fireDue(t, receiverAtTime, robots_[i].receiver, step.rng, shots_);
    if (!obs) return;
    obs->sensorLabel = robot.options().name + ".beacons";
    obs->timestamp = mrpt::Clock::fromDouble(step.startTime + ranging_->lastShotTime());
    step.emit(obs);
}

// What a robot tells the RF beacon: the receiver where its own estimate puts it (its
// configured start before the first estimate: robots start at a surveyed spot).
RobotReport BeaconPayload::report(const sim::Step& step, size_t i) const {
    const auto& ro = step.fleet.robot(i).options();
    RobotReport r;
    r.robot = ro.name;
    r.speed = step.fleet.odometrySpeed(i);
    const auto est = onboard_.localizer.latestEstimate(ro.name);
    const mrpt::poses::CPose2D believed =
        est ? mrpt::poses::CPose2D(est->x(), est->y(), est->yaw()) : ro.start;
    r.receiver = receiverAt(believed, robots_[i].receiver);
    return r;
}

void BeaconPayload::sense(sim::Step& step) {
    if (!ranging_) {
        ranging_ = std::make_unique<BeaconRanging>(step.world, beacons_, sensors_, ultrasonic_);
        state_.assign(step.fleet.size(), {});
    }
    fireDue(step);
    const double t = step.t;
    if (ranging_->inEpoch() || t < channelFree_ - 1e-9) return;
    std::vector<RobotReport> requests;
    for (size_t i = 0; i < step.fleet.size(); ++i) {
        const long cap = robots_[i].rangingEpochs;
        const bool paused = t >= robots_[i].pauseStart && t < robots_[i].pauseEnd;
        if (t - state_[i].lastEpoch >= 1.0 / robots_[i].beaconRate - 1e-9 &&
            (cap == 0 || state_[i].epochs < cap) && !paused)
            requests.push_back(report(step, i));
    }
    if (requests.empty()) return;
    const auto epoch =
        (controller_ ? *controller_ : static_cast<RangingController&>(onboard_.rfBeacon))
            .nextEpoch(t, requests);
    if (!epoch) return;
    const size_t i = epochRobot_ = step.fleet.indexOf(epoch->robot);
    state_[i].lastEpoch = t;
    ++state_[i].epochs;
    channelFree_ = ranging_->begin(t, *epoch);
    fireDue(step);  // heads already aimed: the first shot leaves now
}

std::vector<std::string> BeaconPayload::finish(const std::string& rawlogPath) {
    const std::string path = shotLogPath(rawlogPath);
    saveShotLog(path, shots_);
    return {path};
}

}  // namespace mrloc::beacons
