#pragma once
// The report's part and the headline of a run of the scan localizer ([polymap] localizer =
// scan): the traced map, the hypotheses from the first scan, the passive elimination, and the
// path beside a reference (MRPT's pf-localization or icp-slam on a log without ground truth).
#include <mrloc/common/Outcome.h>
#include <mrloc/report/Report.h>

namespace mrloc::polymap {

/** True if the run's metrics are the scan localizer's. */
bool isScanRun(const nlohmann::json& metrics);

report::Html scanSection(const report::RunView& run);

/** Localized or not (one hypothesis left), the first scan's hypotheses, the distance and
 *  time until one was left, the error against the reference. */
common::Headline scanHeadline(const nlohmann::json& polymapMetrics);

}  // namespace mrloc::polymap
