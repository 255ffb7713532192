#include <mrloc/common/Error.h>
#include <mrloc/common/Names.h>
#include <mrloc/formation/Team.h>
#include <mrpt/core/format.h>
#include <mrpt/obs/CObservationComment.h>
#include <mrpt/poses/CPoint2D.h>
#include <mrpt/poses/CPose2D.h>

#include <algorithm>
#include <cmath>
#include <optional>

namespace mrloc::formation {

namespace {

/** "formation: <robot><tail>" -> "<robot>"; anything else -> nothing. */
std::optional<std::string> messageRobot(const std::string& text, const std::string& tail) {
    const std::string head = "formation: ";
    if (text.size() <= head.size() + tail.size() || text.compare(0, head.size(), head) != 0 ||
        text.compare(text.size() - tail.size(), tail.size(), tail) != 0)
        return std::nullopt;
    return text.substr(head.size(), text.size() - head.size() - tail.size());
}

}  // namespace

std::string arrivedLabel(const std::string& text) {
    const auto robot = messageRobot(text, " arrived");
    return robot ? *robot + ".arrived" : "";
}

Team::Team(TeamOptions options)
    : options_(std::move(options)),
      planner_(options_.route, options_.formation, options_.maxMoves) {
    if (options_.names.size() != options_.start.size())
        throw Error("formation: the team needs one start per robot");
    if (options_.start.size() < 4) throw Error("formation: the team needs at least 4 robots");
    if (options_.route.empty()) throw Error("formation: the team needs a destination");
    believed_ = options_.start;
    heading_.assign(believed_.size(), 0);  // seed 003 sec. 5: every robot faces east
    scanned_.assign(believed_.size(), false);
}

std::optional<size_t> Team::indexOf(const std::string& name) const {
    const auto it = std::find(options_.names.begin(), options_.names.end(), name);
    if (it == options_.names.end()) return std::nullopt;
    return size_t(it - options_.names.begin());
}

std::string arrivalText(const std::string& robot) { return "formation: " + robot + " arrived"; }

std::string lostBeaconsText(const std::string& robot) {
    return "formation: " + robot + " lost the beacons";
}

bool isLostBeaconsText(const std::string& text) {
    return messageRobot(text, " lost the beacons").has_value();
}

bool Team::observe(const mrpt::obs::CObservation::Ptr& obs) {
    // MRPT stores a comment's text and time, not its label: the text names the robot
    const auto comment = std::dynamic_pointer_cast<mrpt::obs::CObservationComment>(obs);
    const std::string label = comment ? arrivedLabel(comment->text) : obs->sensorLabel;
    const auto [name, sensor] = common::parseSensorLabel(label);
    const auto robot = indexOf(name);
    if (!robot) return false;
    if (sensor == "obstacles") {
        const auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservation2DRangeScan>(obs);
        if (!scan)
            throw Error("formation: " + obs->sensorLabel + " is a " +
                        obs->GetRuntimeClass()->className + ", expected CObservation2DRangeScan");
        addScan(*robot, *scan);
        scanned_[*robot] = true;
        if (state_ == State::Waiting &&
            std::all_of(scanned_.begin(), scanned_.end(), [](bool b) { return b; })) {
            plan();
            return current_.has_value();
        }
        return false;
    }
    if (sensor != "arrived") return false;
    if (state_ != State::Moving || current_->robot != *robot)
        throw Error(mrpt::format(
            "formation: %s reports an arrival, but %s; was the rawlog recorded with another "
            "[formation] section?",
            label.c_str(),
            state_ == State::Moving
                ? ("the moving robot is " + options_.names[current_->robot]).c_str()
                : "no robot is moving"));
    const Move& m = *current_;
    heading_[m.robot] = arrivalHeading(m, believed_);
    believed_[m.robot] = m.target;
    moves_.push_back({mrpt::Clock::toDouble(obs->timestamp), m});
    plan();
    return current_.has_value();
}

void Team::addScan(size_t robot, const mrpt::obs::CObservation2DRangeScan& scan) {
    // Where the robot believes it stands: its vertex and the heading its last path gave it;
    // the moving robot scans on arrival, from its target.
    const bool mover = state_ == State::Moving && current_->robot == robot;
    const TPoint2D at = mover ? current_->target : believed_[robot];
    const mrpt::poses::CPose2D pose(at.x, at.y,
                                    mover ? arrivalHeading(*current_, believed_) : heading_[robot]);
    const double step = scan.getScanSize() > 1 ? scan.aperture / double(scan.getScanSize() - 1) : 0;
    const double cell = options_.obstacleCell;
    for (size_t i = 0; i < scan.getScanSize(); ++i) {
        if (!scan.getScanRangeValidity(i)) continue;
        const double r = scan.getScanRange(i);
        const double a = scan.getScanAngle(i) + scan.sensorPose.yaw();
        const auto p = pose + mrpt::poses::CPoint2D(scan.sensorPose.x() + r * std::cos(a),
                                                    scan.sensorPose.y() + r * std::sin(a));
        // A beam stands for the arc between its neighbours: half the gap at that range.
        const double radius = r * std::sin(step / 2);
        const std::pair<long, long> key{std::lround(std::floor(p.x() / cell)),
                                        std::lround(std::floor(p.y() / cell))};
        const auto [it, added] = cells_.emplace(key, obstacles_.size());
        if (added)
            obstacles_.push_back({{p.x(), p.y()}, radius});
        else
            obstacles_[it->second].radius = std::max(obstacles_[it->second].radius, radius);
    }
}

void Team::plan() {
    const auto outcome = planner_.plan(believed_, obstacles_);
    current_ = planner_.move();
    state_ = outcome == RoutePlanner::Outcome::Move      ? State::Moving
             : outcome == RoutePlanner::Outcome::Arrived ? State::Arrived
                                                         : State::Stuck;
}

}  // namespace mrloc::formation
