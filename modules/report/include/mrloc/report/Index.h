#pragma once
// index.html of a folder of runs (the tour of ./run.sh): one row per headline figure of each
// run, the method's own beside the paper's and the baselines marked, and a link to each
// run's report. Built with report::Html, so nothing read from the runs becomes markup.
#include <string>

namespace mrloc::report {

/** Writes `folder`/index.html over the run folders directly inside it (those holding a
 *  metrics.json, in name order) and returns its path. Throws mrloc::Error when none does,
 *  or when a run's metrics.json is malformed (naming it). An empty `title` says what the
 *  folder holds: "mrloc: 3 runs in out (beacons, polymap)". */
std::string makeIndex(const std::string& folder, std::string title = "");

}  // namespace mrloc::report
