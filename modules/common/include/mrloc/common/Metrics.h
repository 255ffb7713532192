#pragma once
// Error statistics of estimates against ground truth, and the metrics.json they go to.
#include <mrloc/common/JsonFile.h>
#include <mrloc/common/Trajectory.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace mrloc::common {

struct ErrorStats {
    size_t n = 0;
    double rmse = 0, mean = 0, median = 0, p95 = 0, max = 0;
};

/** Percentile by linear interpolation between order statistics (p in [0, 100]). */
double percentile(std::vector<double> values, double p);
ErrorStats computeStats(const std::vector<double>& errors);

struct TimedError {
    double t;
    double error;  ///< horizontal (x, y) position error, metres
};

/** Horizontal position error of every estimate whose time lies inside the ground truth. */
std::vector<TimedError> positionErrors(const Trajectory& estimate, const Trajectory& truth);

/** The common keys of metrics.json: n, rmse_m, mean_m, median_m, p95_m, max_m (null when
 *  n = 0). */
nlohmann::json statsToJson(const ErrorStats& s);
/** The same keys for another unit: n, rmse_<unit>, ... each value times `scale` (a heading's
 *  radians as "deg", scale 180 / pi). */
nlohmann::json statsToJson(const ErrorStats& s, const std::string& unit, double scale = 1.0);

/** A run folder's metrics.json (readJsonFile), its keys that every reader uses (method,
 *  rawlog, robots, warnings, headline...) checked for their types: a file from elsewhere with
 *  a wrong type is refused naming the file and key. */
nlohmann::json readMetricsFile(const std::string& path);
/** A run folder's provenance.json, likewise (ini, seed, steps, outputs, simulated...). */
nlohmann::json readProvenanceFile(const std::string& path);

/** Pretty JSON text written atomically. */
void saveJson(const std::string& path, const nlohmann::json& j);

}  // namespace mrloc::common
