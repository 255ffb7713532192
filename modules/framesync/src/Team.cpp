#include <mrloc/common/Rawlog.h>
#include <mrloc/framesync/Team.h>
#include <mrpt/obs/CObservationOdometry.h>

namespace mrloc::framesync {

RobotNode::RobotNode(std::string name, const TeamOptions& options, WallBus& bus)
    : name_(std::move(name)),
      options_(options),
      manager_(name_, options.priority, options.manager, bus) {
    manager_.addListener(this);
}

void RobotNode::odometry(double t, const mrpt::poses::CPose2D& odometry) {
    odometry_ = odometry;
    hasOdometry_ = true;
    manager_.setPose(t, estimate());
}

void RobotNode::sonar(double t, int sensor, const mrpt::poses::CPose2D& sensorOnRobot, double range,
                      bool echo, double halfAperture) {
    auto it = detectors_.find(sensor);
    if (it == detectors_.end()) {
        WallDetectorOptions o = options_.detector;
        o.halfAperture = halfAperture;
        it = detectors_.emplace(sensor, WallDetector(o)).first;
    }
    SonarReading r;
    r.t = t;
    r.sensor = estimate() + sensorOnRobot;
    r.range = range;
    r.echo = echo;
    found(t, sensor, it->second.add(r));
}

void RobotNode::found(double t, int sensor, const std::optional<Wall>& wall) {
    if (!wall) return;
    walls_.push_back({name_, sensor, t, manager_.version(), *wall});
    if (options_.sharing) manager_.announce(*wall);
}

void RobotNode::onRedefinition(const RedefinitionEvent& e) {
    for (auto& [id, d] : detectors_) {
        if (options_.onRedefinition == TeamOptions::OnRedefinition::Drop)
            d.drop();  // seed 004 sec. 5.1: ERPs from the old frame are discarded
        else
            d.transform(e.redefinition.correction);
    }
}

WallDetectorCounts RobotNode::detectorCounts() const {
    WallDetectorCounts sum;
    for (const auto& [id, d] : detectors_) {
        const auto& c = d.counts();
        sum.readings += c.readings, sum.erps += c.erps, sum.noWall += c.noWall;
        sum.outOfCone += c.outOfCone, sum.ambiguous += c.ambiguous, sum.walls += c.walls;
        sum.tooShort += c.tooShort, sum.offLine += c.offLine;
        sum.notPerpendicular += c.notPerpendicular;
    }
    return sum;
}

/** The decision layers: they record every redefinition they are told of. */
class FrameTeam::Recorder : public FrameListener {
 public:
    explicit Recorder(std::vector<RedefinitionEvent>& events) : events_(events) {}
    void onRedefinition(const RedefinitionEvent& e) override { events_.push_back(e); }

 private:
    std::vector<RedefinitionEvent>& events_;
};

FrameTeam::FrameTeam(TeamOptions options)
    : options_(std::move(options)), recorder_(std::make_unique<Recorder>(events_)) {}

FrameTeam::~FrameTeam() = default;

RobotNode& FrameTeam::node(const std::string& robot) {
    auto it = robots_.find(robot);
    if (it == robots_.end()) {
        it = robots_.emplace(robot, std::make_unique<RobotNode>(robot, options_, bus_)).first;
        it->second->manager().addListener(recorder_.get());
    }
    return *it->second;
}

void FrameTeam::process(const mrpt::obs::CObservation::Ptr& obs) {
    const double t = mrpt::Clock::toDouble(obs->timestamp);
    if (const auto odo = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(obs)) {
        const std::string robot = common::robotOfLabel(odo->sensorLabel);
        RobotNode& n = node(robot);
        n.odometry(t, odo->odometry);
        estimates_[robot].push_back({t, mrpt::poses::CPose3D(n.estimate())});
        odometry_[robot].push_back({t, mrpt::poses::CPose3D(odo->odometry)});
        return;
    }
    const auto range = std::dynamic_pointer_cast<mrpt::obs::CObservationRange>(obs);
    if (!range) return;
    RobotNode& n = node(common::robotOfLabel(range->sensorLabel));
    for (const auto& m : range->sensedData) {
        ++readings_;
        if (!n.hasPose()) {
            ++unplaced_;
            continue;
        }
        const auto& p = m.sensorPose;
        // no echo: 0 (MRPT's CObservationRange), or a reading outside the sensor's span
        const bool echo = m.sensedDistance < range->maxSensorDistance &&
                          m.sensedDistance > range->minSensorDistance;
        n.sonar(t, m.sensorID, mrpt::poses::CPose2D(p.x, p.y, p.yaw), m.sensedDistance, echo,
                range->sensorConeApperture / 2);
    }
}

std::vector<RedefinitionEvent> FrameTeam::takeNewEvents() {
    std::vector<RedefinitionEvent> out(events_.begin() + long(newEvents_), events_.end());
    newEvents_ = events_.size();
    return out;
}

}  // namespace mrloc::framesync
