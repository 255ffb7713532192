#include <mrloc/common/Error.h>
#include <mrloc/formation/FormationPayload.h>
#include <mrloc/sim/Scanner.h>
#include <mrpt/core/format.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/obs/CObservationComment.h>
#include <mrpt/obs/CObservationOdometry.h>

#include <algorithm>
#include <cmath>

namespace mrloc::formation {

namespace {

TPoint2D position(const sim::Robot& robot) { return {robot.pose().x(), robot.pose().y()}; }

/** Within this of a path point, the robot is there (m): the controller lands on it to
 *  rounding, so this only absorbs floating point. */
constexpr double kOnPoint = 1e-6;

}  // namespace

TeamOptions teamOptions(const FormationConfig& c) {
    TeamOptions t;
    t.formation = c.formation;
    t.names = formationRobotNames(c.robots);
    t.start = c.worldStrip();
    t.route = c.worldRoute();
    t.maxMoves = c.maxMoves;
    t.obstacleCell = c.obstacleCell;
    return t;
}

FormationPayload::FormationPayload(const FormationConfig& config, double dt)
    : config_(config), team_(teamOptions(config)), robots_(config.robots) {
    drEvery_ = std::lround(config.deadReckoning.dt / dt);
    if (drEvery_ < 1 || std::abs(double(drEvery_) * dt - config.deadReckoning.dt) > 1e-9 * dt)
        throw Error(mrpt::format(
            "[formation] dr_period = %g s must be a whole number of [scenario] dt = %g s",
            config.deadReckoning.dt, dt));
}

void FormationPayload::onObservation(const mrpt::obs::CObservation::Ptr& obs) {
    team_.observe(obs);
}

void FormationPayload::emitScan(sim::Step& step, size_t robot) {
    const auto& r = step.fleet.robot(robot);
    auto scan = sim::scanWorld(step.world, r.pose(), config_.obstacleSensorHeight,
                               config_.obstacleSensor, step.rng);
    scan->sensorLabel = r.options().name + ".obstacles";
    scan->timestamp = step.stamp;
    step.emit(scan);
}

void FormationPayload::startMove(sim::Step& step) {
    const Move& m = *team_.current();
    std::vector<TPoint2D> actual;
    for (size_t i = 0; i < robots_; ++i) actual.push_back(position(step.fleet.robot(i)));
    MarchOptions o;
    o.formation = config_.formation;
    o.carry = config_.carry;
    const TPoint2D end = moveEnd(m, team_.believed(), actual, o, config_.vertexErrors, step.rng);
    // seed 003 Algorithm 2 among the real beacons: the robot steers by what it sees
    path_ =
        innerPath({actual[m.base[0]], actual[m.base[1]], actual[m.anchor]}, actual[m.robot], end);
    leg_ = 0;
    driving_ = true;
}

void FormationPayload::steer(sim::Step& step) {
    const Move& m = *team_.current();
    auto& robot = step.fleet.robot(m.robot);
    robot.go();
    if (leg_ == path_.size()) {  // at the vertex: turn the rear camera onto the anchor
        robot.drive(
            0, std::clamp(headingError(step) / step.dt, -config_.maxTurnRate, config_.maxTurnRate));
        return;
    }
    const TPoint2D at = position(robot), to = path_[leg_];
    const double d = (to - at).norm();
    const double err =
        mrpt::math::wrapToPi(std::atan2(to.y - at.y, to.x - at.x) - robot.pose().phi());
    if (d > kOnPoint && std::abs(err) > 1e-9)  // turn on the spot first
        robot.drive(0, std::clamp(err / step.dt, -config_.maxTurnRate, config_.maxTurnRate));
    else
        robot.drive(std::min(config_.speed(), d / step.dt), 0);
}

double FormationPayload::headingError(const sim::Step& step) const {
    const Move& m = *team_.current();
    const TPoint2D at = position(step.fleet.robot(m.robot));
    const TPoint2D anchor = position(step.fleet.robot(m.anchor));
    return mrpt::math::wrapToPi(std::atan2(at.y - anchor.y, at.x - anchor.x) -
                                step.fleet.robot(m.robot).pose().phi());
}

void FormationPayload::command(sim::Step& step) {
    if (step.index == 0) {
        for (size_t i = 0; i < robots_; ++i) step.fleet.robot(i).stop();
        auto& dr = step.fleet.robot(robots_);
        auto route = config_.worldRoute();
        route.erase(route.begin());
        dr.setWaypoints(route, false);
        deadReckoner_.emplace(config_.deadReckoning, config_.wheelRadius, position(dr));
        drLast_ = position(dr);
    }
    if (team_.state() != Team::State::Moving) return;
    if (!driving_) startMove(step);
    steer(step);
}

void FormationPayload::readDeadReckoning(sim::Step& step) {
    if (drDone_ || step.index % drEvery_ != 0) return;
    const auto& robot = step.fleet.robot(robots_);
    const TPoint2D at = position(robot);
    if (step.index > 0) deadReckoner_->update(robot.pose().phi(), (at - drLast_).norm(), step.rng);
    drLast_ = at;
    auto odo = mrpt::obs::CObservationOdometry::Create();
    odo->sensorLabel = kDeadReckoningLabel;
    odo->timestamp = step.stamp;
    const TPoint2D e = deadReckoner_->estimate();
    odo->odometry = mrpt::poses::CPose2D(
        e.x, e.y, step.index > 0 ? deadReckoner_->sensedHeading() : robot.pose().phi());
    odo->hasVelocities = true;
    odo->velocityLocal = {step.index > 0 ? deadReckoner_->sensedSpeed() : 0.0, 0, 0};
    step.emit(odo);
    const auto& goal = robot.options().waypoints.back();
    drDone_ = std::hypot(goal.x - at.x, goal.y - at.y) < robot.arrivalRadius(step.dt);
}

void FormationPayload::sense(sim::Step& step) {
    if (step.index == 0)
        for (size_t i = 0; i < robots_; ++i) emitScan(step, i);
    readDeadReckoning(step);
    if (!driving_) return;
    const size_t mover = team_.current()->robot;
    auto& robot = step.fleet.robot(mover);
    if (leg_ < path_.size()) {
        if ((path_[leg_] - position(robot)).norm() > kOnPoint) return;
        ++leg_;
    }
    if (leg_ < path_.size() || std::abs(headingError(step)) > 1e-9) return;
    robot.stop();
    driving_ = false;
    emitScan(step, mover);  // from the new vertex, before the arrival: the next plan sees it
    auto arrived = mrpt::obs::CObservationComment::Create();
    arrived->sensorLabel = robot.options().name + ".arrived";
    arrived->timestamp = step.stamp;
    arrived->text = arrivalText(robot.options().name);
    step.emit(arrived);  // the team plans the next move (onObservation)
}

}  // namespace mrloc::formation
