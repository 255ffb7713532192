#pragma once
// `mrloc batch --collect`: a batch folder's trial records merged into one summary per grid
// point (count, mean, median, 95th percentile, spread), every failed or missing trial
// listed by point and seed; `mrloc report` on the folder renders it with plots.
#include <optional>
#include <string>
#include <vector>

#include "BatchPlan.h"

namespace mrloc::app {

/** One figure over a point's trials. */
struct FigureStats {
    std::string name, unit;
    bool baseline = false;
    size_t count = 0;  ///< trials that gave a value
    double mean = 0, median = 0, p95 = 0;
    double sd = 0;  ///< sample standard deviation (n - 1); 0 for one value
    double min = 0, max = 0;
    std::vector<size_t> histogram;  ///< 20 bins over [min, max]
};

struct PointSummary {
    size_t index = 0;
    std::string name;  ///< "framesync.sonar_sigma=0.02", "all"
    std::vector<KeyOverride> keys;
    size_t done = 0, reached = 0;
    std::vector<FigureStats> figures;
};

struct TrialProblem {
    size_t point = 0;
    unsigned long seed = 0;
    std::string why;  ///< the trial's error, parallel's exit status, or "not run"
};

struct BatchSummary {
    BatchPlan plan;
    std::string method;
    size_t trials = 0;
    std::vector<PointSummary> points;
    std::vector<TrialProblem> failed, missing;
    /** Trials the job log shows done more than once (a resume that ran one again). */
    size_t rerun = 0;
};

/** Reads batch.json, every trial record and the job log (when there is one). */
BatchSummary collectBatch(const std::string& dir);
/** summary.json read back and checked (readJsonFile's bounds, then every field's type and
 *  range); throws mrloc::Error naming the file. */
BatchSummary readSummary(const std::string& path);
/** summary.json and summary.txt, atomically. */
void writeSummary(const std::string& dir, const BatchSummary& s);
/** The summary as summary.txt holds it: one table per point, then the problems. */
std::string summaryText(const BatchSummary& s);

/** `mrloc report` on a batch folder: report.html and one plot per figure, from
 *  summary.json; returns the page's path. */
std::string renderBatchReport(const std::string& dir);

}  // namespace mrloc::app
