#pragma once
// Seed 004's experiment over many runs: the INI's scenario simulated again with other seeds
// (the paper's measure: the distance between the robots' estimates of the goal point, with
// and without the shared frame), then with other sonar noises and odometry drifts. Each
// run is the whole simulation (sonars in the OctoMap, drifting odometry, the on-board
// systems), sharing one world; runs are spread over the cores and deterministic per seed.
#include <mrloc/framesync/FramesyncConfig.h>
#include <mrloc/framesync/FramesyncFiles.h>
#include <mrloc/framesync/FramesyncLocalizer.h>
#include <mrloc/framesync/FramesyncPayload.h>
#include <mrloc/method/Registry.h>
#include <mrloc/sim/Scenario.h>

namespace mrloc::framesync {

/** One simulated run: the scenario with `seed`, sonar noise `sigma` (m) and every robot's
 *  systematic odometry errors multiplied by `drift`. */
ExperimentRun simulateRun(const sim::ScenarioConfig& scenario, const FramesyncConfig& config,
                          const std::shared_ptr<const sim::World>& world,
                          const std::shared_ptr<const FloorSlices>& slices, unsigned long seed,
                          double sigma, double drift);

/** The runs [framesync] asks for: experiment_seeds as given, then experiment_sweep_seeds
 *  for each experiment_noise and each experiment_drift. */
FramesyncExperimentFile runExperiment(const sim::ScenarioConfig& scenario,
                                      const FramesyncConfig& config,
                                      const common::Log& log = common::silentLog());

/** The registered experiment step: writes framesync.experiment.txt. */
/** The work the configuration asks (method/Work.h): the sonars' simulation and the
 *  experiment's runs. */
std::vector<method::WorkItem> framesyncWork(const FramesyncLocalizer& localizer,
                                            const sim::ScenarioConfig* scenario);

std::vector<std::string> framesyncExperiment(const method::ExperimentOf<FramesyncLocalizer>& in);

/** One run of the experiment (`mrloc trial`): the scenario with its seed, at [framesync]
 *  sonar_sigma ([scenario] odometry_error_scale standing for experiment_drift). A batch
 *  over seeds, sonar_sigma or odometry_error_scale gives runExperiment's runs exactly. */
common::Headline framesyncTrial(const method::TrialOf<FramesyncLocalizer>& in);

}  // namespace mrloc::framesync
