#pragma once
// Runs a scenario: steps every robot, reads its odometry and writes each observation, in
// time order, to a rawlog; records the true poses as ground truth. Everything a method
// adds (its sensors, its on-board estimator, how it steers the robots) comes in through
// its Payload, called in a fixed order at every step (Payload.h).
#include <mrloc/common/Progress.h>
#include <mrloc/common/Rawlog.h>
#include <mrloc/common/Trajectory.h>
#include <mrloc/sim/Payload.h>
#include <mrloc/sim/Scenario.h>

#include <functional>
#include <map>
#include <memory>

namespace mrloc::sim {

struct SimulationResult {
    std::map<std::string, common::Trajectory> groundTruth;  ///< per robot
    size_t observations = 0;
};

class Simulator {
 public:
    explicit Simulator(ScenarioConfig config);
    /** With a world already built from config.world (a Monte Carlo's runs share one). */
    Simulator(ScenarioConfig config, std::shared_ptr<const World> world);
    const ScenarioConfig& config() const { return config_; }
    const World& world() const { return *world_; }

    /** Simulates the whole duration. Deterministic for a given configuration and seed. */
    SimulationResult run(common::RawlogWriter& out, Payload* payload = nullptr,
                         common::Progress* progress = nullptr);
    /** The same, every observation handed to `write` instead of a rawlog (an experiment's
     *  runs, which keep no file). */
    SimulationResult run(const std::function<void(const mrpt::obs::CObservation&)>& write,
                         Payload* payload = nullptr, common::Progress* progress = nullptr);

 private:
    ScenarioConfig config_;
    std::shared_ptr<const World> world_;
};

/** The files a simulation wrote: the rawlog first, then ground truth and side files. */
struct SimulatedFiles {
    std::string rawlog;
    std::vector<std::string> all;
};

/** Writes `<dir>/<name>.rawlog`, `<dir>/<name>.<robot>.gt.txt` and the payload's side
 *  files. Nothing appears under a final name unless the whole simulation succeeded. */
SimulatedFiles simulateToFiles(const ScenarioConfig& config, const std::string& dir,
                               const common::Log& log, Payload* payload = nullptr);

}  // namespace mrloc::sim
