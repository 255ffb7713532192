#pragma once
// Runs a scenario: steps every robot, samples its sensors at their rates and writes each
// observation, in time order, to a rawlog; records the true poses as ground truth.
//
// Beacon ranging is closed-loop: when the ultrasonic channel is free, the robots that want
// a fix report their position (from their onboard estimator) and speed (from odometry) to
// a RangingController, which picks the next epoch; BeaconRanging fires it. Everything the
// robots sense is also fed to the onboard estimator, so a later `mrloc localize` on the
// rawlog reproduces the estimates the beacons were aimed with.
//
// In a floor-plan scenario each robot also scans the polygon (<robot>.scan) at the start and
// then at the scanner's rate.
#include <mrloc/common/Localizer.h>
#include <mrloc/common/Progress.h>
#include <mrloc/common/RangingController.h>
#include <mrloc/common/Rawlog.h>
#include <mrloc/common/Trajectory.h>
#include <mrloc/sim/Scenario.h>
#include <mrloc/sim/ShotLog.h>

#include <map>

namespace mrloc::sim {

/** The method's side of a closed-loop simulation; both may be null (no beacon ranging,
 *  robots report their configured start as their position). */
struct SimulationHooks {
    common::Localizer* onboard = nullptr;          ///< the robots' own estimator
    common::RangingController* ranging = nullptr;  ///< the RF beacon's decisions
};

struct SimulationResult {
    std::map<std::string, common::Trajectory> groundTruth;  ///< per robot
    ShotLog shots;
    size_t observations = 0;
};

class Simulator {
 public:
    explicit Simulator(ScenarioConfig config);
    const ScenarioConfig& config() const { return config_; }
    const World& world() const { return world_; }

    /** Simulates the whole duration. Deterministic for a given configuration and seed. */
    SimulationResult run(common::RawlogWriter& out, SimulationHooks hooks = {},
                         common::Progress* progress = nullptr);

 private:
    ScenarioConfig config_;
    World world_;
};

/** Writes `<dir>/<name>.rawlog`, `<dir>/<name>.<robot>.gt.txt` and `<dir>/<name>.shots.txt`;
 *  returns the rawlog path. */
std::string simulateToFiles(const ScenarioConfig& config, const std::string& dir, bool quiet,
                            SimulationHooks hooks = {});

}  // namespace mrloc::sim
