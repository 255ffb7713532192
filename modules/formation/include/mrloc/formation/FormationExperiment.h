#pragma once
// Seed 003 sec. 5 in error-model mode: Table 1 (the error at the destination, formation
// against dead reckoning, both routes, both wheel speeds, mean of the runs), fig. 14 (the
// mean error against time), fig. 15 (against the number of robots), and fig. 11's per-step
// errors: the paper's, the error model's draws, and Algorithm 1 from rendered frames.
#include <mrloc/formation/FormationConfig.h>
#include <mrloc/formation/FormationFiles.h>
#include <mrloc/formation/FormationLocalizer.h>
#include <mrloc/method/Registry.h>

namespace mrloc::formation {

/** The whole experiment from [formation]'s keys (runs, experiment_*, camera_starts); the
 *  same seed gives the same file. */
FormationExperimentFile runFormationExperiment(const FormationConfig& config,
                                               const common::Log& log = common::silentLog());

/** The work the configuration asks (method/Work.h; FormationWork.cpp): the pixel mode's
 *  frames, the experiment's marches and dead-reckoned drives, and the pixel experiment. */
std::vector<method::WorkItem> formationWork(const FormationLocalizer& localizer,
                                            const sim::ScenarioConfig* scenario);

/** The registered experiment step: runs it when runs > 0 and writes
 *  formation.experiment.txt. */
std::vector<std::string> formationExperiment(const method::ExperimentOf<FormationLocalizer>& in);

/** One run of Table 1 (`mrloc trial`): every route at every speed, formation and dead
 *  reckoning, drawn from the trial's seed. Run r of the experiment is seed experiment_seed +
 *  r ([formation] experiment_seed, else [scenario] seed): a batch over those seeds gives
 *  Table 1's means. */
common::Headline formationTrial(const method::TrialOf<FormationLocalizer>& in);

}  // namespace mrloc::formation
