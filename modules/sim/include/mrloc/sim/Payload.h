#pragma once
// What a method adds to a simulation: its sensors and its on-board logic. The simulator
// runs only generic parts (time, robots, odometry, ground truth); at every step it calls
// the payload in a fixed order, so that the same seed still gives a byte-identical rawlog:
//
//   command(step)   before the robots move: steer them (waypoints, stop, go, turn, drive)
//   (robots move; odometry is read and written)
//   sense(step)     after the robots moved: simulate the method's sensors, emit()
//   onObservation   every observation written, odometry included: the on-board part
//   finish(rawlog)  after the last step: side files beside the rawlog (atomically)
#include <mrloc/sim/Robot.h>
#include <mrloc/sim/World.h>
#include <mrpt/obs/CObservation.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt/system/datetime.h>

#include <functional>
#include <string>
#include <vector>

namespace mrloc::sim {

/** The robots of a run, as the payload sees them. */
class Fleet {
 public:
    explicit Fleet(const std::vector<RobotOptions>& robots);
    size_t size() const { return robots_.size(); }
    Robot& robot(size_t i) { return robots_.at(i); }
    const Robot& robot(size_t i) const { return robots_.at(i); }
    /** Index of the robot with this name; throws mrloc::Error naming it if there is none. */
    size_t indexOf(const std::string& name) const;
    /** The true poses now, in robot order. */
    std::vector<mrpt::poses::CPose2D> poses() const;
    /** Where robot i was before this step's motion. */
    const mrpt::poses::CPose2D& previousPose(size_t i) const { return previous_.at(i); }
    /** Robot i's speed from its last two odometry readings (m/s; 0 before two). */
    double odometrySpeed(size_t i) const { return speed_.at(i); }

 private:
    friend class Simulator;
    std::vector<Robot> robots_;
    std::vector<mrpt::poses::CPose2D> previous_;
    std::vector<double> speed_;
};

/** One simulation step as the payload sees it. */
struct Step {
    long index = 0;                 ///< step number, 0 at the start
    double t = 0;                   ///< s since the start
    double dt = 0;                  ///< step length (s)
    double startTime = 0;           ///< time stamp of t = 0 (s since 1970)
    mrpt::Clock::time_point stamp;  ///< of t
    Fleet& fleet;
    const World& world;
    mrpt::random::CRandomGenerator& rng;
    /** Writes an observation to the rawlog (labelled and stamped by the caller) and hands
     *  it to the on-board part. */
    const std::function<void(const mrpt::obs::CObservation::Ptr&)>& emit;
};

class Payload {
 public:
    virtual ~Payload() = default;
    virtual void command(Step& /*step*/) {}
    virtual void sense(Step& /*step*/) {}
    virtual void onObservation(const mrpt::obs::CObservation::Ptr& /*obs*/) {}
    /** Writes side files beside `rawlogPath` atomically; returns their paths. */
    virtual std::vector<std::string> finish(const std::string& /*rawlogPath*/) { return {}; }
};

}  // namespace mrloc::sim
