#pragma once
// Seed 002's experiment, run after localization and shown in the report: every hypothesis
// in turn the truth, every algorithm of [polymap] elimination in closed loop with exact
// views (Tables 1-2), and with sweep_steps the mean path and time against n (Figs. 6-7).
#include <mrloc/method/Registry.h>
#include <mrloc/polymap/PolymapFiles.h>
#include <mrloc/polymap/PolymapLocalizer.h>

#include <string>
#include <vector>

namespace mrloc::polymap {

/** The method's experiment step: writes elimination.txt, elimination.times.txt and, with a
 *  sweep, elimination.sweep.txt; nothing without [polymap] elimination. */
/** The work the configuration asks (method/Work.h): the simulated scans and the
 *  experiment's randomized columns (the other algorithms cost little beside them). */
std::vector<method::WorkItem> polymapWork(const PolymapLocalizer& localizer,
                                          const sim::ScenarioConfig* scenario);

std::vector<std::string> eliminationExperiment(const method::ExperimentOf<PolymapLocalizer>& in);

/** The report's part of it: Tables 1-2 beside the paper's values and, if the run swept,
 *  Figs. 6-7 (plotted into `dir`). */
report::Html eliminationSection(const std::string& dir, const EliminationFile& file);

}  // namespace mrloc::polymap
