#include <mrloc/common/Error.h>
#include <mrloc/formation/FormationPayload.h>
#include <mrloc/formation/PixelMarch.h>
#include <mrloc/sim/Scanner.h>
#include <mrpt/core/format.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/obs/CObservationBearingRange.h>
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

void FormationPayload::startCameraMove(sim::Step& step) {
    const Move& m = *team_.current();
    if (!camera_) {  // the cameras and the scene, once for the march
        lens_.emplace(config_.cameraIntrinsics(), config_.lens);
        camera_ = std::make_unique<sim::PinholeCamera>(lens_->renderIntrinsics());
        scene_.emplace(robots_, MarkerOptions{});
    }
    // The scene about the moving robot (single precision), the mover not in its own view.
    const auto& mover = step.fleet.robot(m.robot).pose();
    scene_->setOrigin({mover.x(), mover.y()});
    for (size_t i = 0; i < robots_; ++i) {
        scene_->place(i, step.fleet.robot(i).pose());
        scene_->show(i, i != m.robot);
    }
    std::vector<double> headings;
    for (size_t i = 0; i < robots_; ++i) headings.push_back(team_.believedHeading(i));
    cameraMove_.emplace(m, team_.believed(), headings, cameraMoveOptions(config_));
    maneuvers_.clear();
    enqueue(cameraMove_->start(), step.rng);
    driving_ = true;
}

void FormationPayload::enqueue(const std::vector<Maneuver>& maneuvers,
                               mrpt::random::CRandomGenerator& rng) {
    for (const auto& m : maneuvers) maneuvers_.push_back(executed(m, config_.maneuverNoise, rng));
}

void FormationPayload::executeManeuver(sim::Step& step) {
    auto& robot = step.fleet.robot(team_.current()->robot);
    while (!maneuvers_.empty() && std::abs(maneuvers_.front().amount) < 1e-12)
        maneuvers_.pop_front();
    if (maneuvers_.empty()) {
        robot.stop();  // waits for the next frame's decision
        return;
    }
    auto& m = maneuvers_.front();
    const bool turn = m.kind == Maneuver::Kind::Turn;
    const double cap = (turn ? config_.maxTurnRate : config_.speed()) * step.dt;
    const double now = std::clamp(m.amount, -cap, cap);
    robot.go();
    if (turn)
        robot.drive(0, now / step.dt);
    else
        robot.drive(now / step.dt, 0);
    m.amount -= now;
    if (std::abs(m.amount) < 1e-12) maneuvers_.pop_front();
}

void FormationPayload::cameraFrame(sim::Step& step) {
    const auto& robot = step.fleet.robot(team_.current()->robot);
    const bool front = cameraMove_->camera() == CameraMove::Camera::Front;
    const MarkerOptions markers;
    const auto local = scene_->local(robot.pose());
    const auto pose = front ? frontCameraPose(local, markers.bodySize, markers.tagHeight)
                            : rearCameraPose(local, markers.bodySize, markers.tagHeight);
    // through the camera model, at full resolution (a far anchor seen edge-on shows two
    // small tags, which the detector's decimation loses)
    const auto tags = lens_->see(camera_->render(scene_->scene(), pose), step.rng);
    // the frame's tags as bearings from the camera (MRPT's class for landmark sightings)
    const auto& k = lens_->intrinsics();  // the undistorted tags' frame
    auto obs = mrpt::obs::CObservationBearingRange::Create();
    obs->sensorLabel = robot.options().name + (front ? ".front" : ".rear");
    obs->timestamp = step.stamp;
    obs->sensorLocationOnRobot =
        mrpt::poses::CPose3D(front ? markers.bodySize / 2 : -markers.bodySize / 2, 0,
                             markers.tagHeight, front ? 0 : M_PI, 0, 0);
    obs->fieldOfView_yaw = float(2 * std::atan2(k.cx(), k.fx()));
    obs->fieldOfView_pitch = float(2 * std::atan2(k.cy(), k.fy()));
    for (const auto& t : tags) {
        mrpt::obs::CObservationBearingRange::TMeasurement m;
        m.range = 0;  // a monocular camera: no range
        m.yaw = float(std::atan2(k.cx() - t.u, k.fx()));
        m.pitch = float(std::atan2(k.cy() - t.v, k.fy()));
        m.landmarkID = t.id;
        obs->sensedData.push_back(m);
    }
    step.emit(obs);
    enqueue(cameraMove_->decide(tags), step.rng);
}

void FormationPayload::arrive(sim::Step& step) {
    const size_t mover = team_.current()->robot;
    auto& robot = step.fleet.robot(mover);
    robot.stop();
    driving_ = false;
    if (cameraMove_ && cameraMove_->lost()) {
        auto lost = mrpt::obs::CObservationComment::Create();
        lost->text = lostBeaconsText(robot.options().name);
        lost->timestamp = step.stamp;
        step.emit(lost);
    }
    cameraMove_.reset();
    emitScan(step, mover);  // from the new vertex, before the arrival: the next plan sees it
    auto arrived = mrpt::obs::CObservationComment::Create();
    arrived->sensorLabel = robot.options().name + ".arrived";
    arrived->timestamp = step.stamp;
    arrived->text = arrivalText(robot.options().name);
    step.emit(arrived);  // the team plans the next move (onObservation)
}

void FormationPayload::command(sim::Step& step) {
    if (step.index == 0) {
        for (size_t i = 0; i < robots_; ++i) step.fleet.robot(i).stop();
        auto& dr = step.fleet.robot(robots_);
        auto route = config_.worldRoute();
        route.erase(route.begin());
        dr.setWaypoints(route, false);
        deadReckoner_.emplace(config_.deadReckoning, config_.wheelRadius, position(dr));
        drRouteLength_ = 0;
        for (size_t k = 0; k < route.size(); ++k)
            drRouteLength_ += (route[k] - (k == 0 ? position(dr) : route[k - 1])).norm();
        drLast_ = position(dr);
    }
    if (team_.state() != Team::State::Moving) return;
    if (config_.mode == FormationConfig::Mode::Pixel) {
        if (!driving_) startCameraMove(step);
        executeManeuver(step);
        return;
    }
    if (!driving_) startMove(step);
    steer(step);
}

void FormationPayload::readDeadReckoning(sim::Step& step) {
    if (drDone_ || step.index % drEvery_ != 0) return;
    const auto& robot = step.fleet.robot(robots_);
    const TPoint2D at = position(robot);
    if (step.index > 0) deadReckoner_->update(robot.pose().phi(), (at - drLast_).norm(), step.rng);
    drTravelled_ += (at - drLast_).norm();
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
    // at the destination, once it has driven most of the way (a patrol ends where it starts)
    drDone_ = std::hypot(goal.x - at.x, goal.y - at.y) < robot.arrivalRadius(step.dt) &&
              drTravelled_ > 0.5 * drRouteLength_;
}

void FormationPayload::sense(sim::Step& step) {
    if (step.index == 0)
        for (size_t i = 0; i < robots_; ++i) emitScan(step, i);
    readDeadReckoning(step);
    if (!driving_) return;
    if (config_.mode == FormationConfig::Mode::Pixel) {
        if (!maneuvers_.empty()) return;  // still executing
        if (cameraMove_->camera()) cameraFrame(step);
        if (!cameraMove_->camera() && maneuvers_.empty()) arrive(step);
        return;
    }
    const size_t mover = team_.current()->robot;
    auto& robot = step.fleet.robot(mover);
    if (leg_ < path_.size()) {
        if ((path_[leg_] - position(robot)).norm() > kOnPoint) return;
        ++leg_;
    }
    if (leg_ < path_.size() || std::abs(headingError(step)) > 1e-9) return;
    arrive(step);
}

}  // namespace mrloc::formation
