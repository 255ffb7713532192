#pragma once
// The on-board system of seed 004 for every robot of a log: odometry, a wall detector per
// sonar, the manager, and the decision layer (which here, as in the paper's experiment,
// only records the robot's estimate and the redefinitions it is told of). The robots talk
// through one WallBus. The simulator's payload and mrloc localize run this same code on the
// same observations: CObservationOdometry and CObservationRange (any number of sonars, each
// with its pose on the robot and its cone from the observation), robots told apart by the
// label's prefix.
#include <mrloc/common/Localizer.h>
#include <mrloc/framesync/FrameManager.h>
#include <mrloc/framesync/WallDetector.h>
#include <mrpt/obs/CObservation.h>
#include <mrpt/obs/CObservationRange.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace mrloc::framesync {

struct TeamOptions {
    bool sharing = true;  ///< false: every robot keeps its own odometry frame
    PriorityOrder priority;
    WallDetectorOptions detector;  ///< halfAperture comes from each observation
    /** On a redefinition the paper's wall detector drops its ERPs (seed 004 sec. 5.1);
     *  Transform carries them into the new frame instead. */
    enum class OnRedefinition { Drop, Transform } onRedefinition = OnRedefinition::Drop;
    ManagerOptions manager;
};

/** A wall a robot announced, as the log keeps it. */
struct AnnouncedWall {
    std::string robot;
    int sonar = 0;
    double time = 0;
    uint32_t frameVersion = 0;
    Wall wall;
};

/** One robot's on-board system. */
class RobotNode : public FrameListener {
 public:
    RobotNode(std::string name, const TeamOptions& options, WallBus& bus);
    void odometry(double t, const mrpt::poses::CPose2D& odometry);
    /** One sonar's reading; sensorOnRobot is its pose on the robot (x, y, yaw). */
    void sonar(double t, int sensor, const mrpt::poses::CPose2D& sensorOnRobot, double range,
               bool echo, double halfAperture);
    void onRedefinition(const RedefinitionEvent& event) override;

    bool hasPose() const { return hasOdometry_; }
    /** The estimate in the robot's current frame. */
    mrpt::poses::CPose2D estimate() const { return manager_.correction() + odometry_; }
    const mrpt::poses::CPose2D& odometryPose() const { return odometry_; }
    const FrameManager& manager() const { return manager_; }
    FrameManager& manager() { return manager_; }
    WallDetectorCounts detectorCounts() const;
    const std::vector<AnnouncedWall>& walls() const { return walls_; }

 private:
    void found(double t, int sensor, const std::optional<Wall>& wall);

    std::string name_;
    const TeamOptions& options_;
    FrameManager manager_;
    std::map<int, WallDetector> detectors_;  ///< per sonar id
    mrpt::poses::CPose2D odometry_;
    bool hasOdometry_ = false;
    std::vector<AnnouncedWall> walls_;
};

/** Every robot of a log on one in-process bus, and what the decision layers recorded. */
class FrameTeam {
 public:
    explicit FrameTeam(TeamOptions options);
    ~FrameTeam();
    FrameTeam(const FrameTeam&) = delete;
    FrameTeam& operator=(const FrameTeam&) = delete;

    /** Odometry and sonar observations; others are ignored. */
    void process(const mrpt::obs::CObservation::Ptr& obs);

    /** Per robot: the estimate in its shared frame at every odometry reading, and the
     *  odometry alone (no sharing). */
    const common::Trajectories& estimates() const { return estimates_; }
    const common::Trajectories& odometry() const { return odometry_; }
    const std::vector<RedefinitionEvent>& events() const { return events_; }
    const std::map<std::string, std::unique_ptr<RobotNode>>& robots() const { return robots_; }
    const TeamOptions& options() const { return options_; }
    /** Sonar readings before the robot's first odometry (no pose to place them). */
    size_t unplacedReadings() const { return unplaced_; }
    size_t readings() const { return readings_; }
    /** Redefinitions since the last call (for a decision layer that acts on them). */
    std::vector<RedefinitionEvent> takeNewEvents();

 private:
    class Recorder;
    RobotNode& node(const std::string& robot);

    TeamOptions options_;
    InProcessBus bus_;
    std::map<std::string, std::unique_ptr<RobotNode>> robots_;
    std::unique_ptr<Recorder> recorder_;
    common::Trajectories estimates_, odometry_;
    std::vector<RedefinitionEvent> events_;
    size_t newEvents_ = 0, unplaced_ = 0, readings_ = 0;
};

}  // namespace mrloc::framesync
