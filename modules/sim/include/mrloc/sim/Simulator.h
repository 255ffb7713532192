#pragma once
// Runs a scenario: steps every robot, samples its sensors at their rates and writes each
// observation, in time order, to a rawlog; records the true poses as ground truth.
#include <mrloc/common/Progress.h>
#include <mrloc/common/Rawlog.h>
#include <mrloc/common/Trajectory.h>
#include <mrloc/sim/Scenario.h>

#include <map>

namespace mrloc::sim {

struct SimulationResult {
    std::map<std::string, common::Trajectory> groundTruth;  ///< per robot
    size_t observations = 0;
};

class Simulator {
 public:
    explicit Simulator(ScenarioConfig config);
    const ScenarioConfig& config() const { return config_; }
    const World& world() const { return world_; }

    /** Simulates the whole duration. Deterministic for a given configuration and seed. */
    SimulationResult run(common::RawlogWriter& out, common::Progress* progress = nullptr);

 private:
    ScenarioConfig config_;
    World world_;
};

/** Writes `<dir>/<name>.rawlog` and `<dir>/<name>.<robot>.gt.txt`; returns the rawlog path. */
std::string simulateToFiles(const ScenarioConfig& config, const std::string& dir, bool quiet);

}  // namespace mrloc::sim
