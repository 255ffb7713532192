#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/Metrics.h>

#include <algorithm>
#include <cmath>

namespace mrloc::common {

double percentile(std::vector<double> v, double p) {
    if (v.empty()) return 0.0;
    const double pos = std::clamp(p, 0.0, 100.0) / 100.0 * double(v.size() - 1);
    const size_t i = size_t(std::floor(pos));
    // the i-th and (i+1)-th smallest without sorting the whole (linear, not n log n: a
    // 10^6-stamp evaluation takes two of these per figure)
    const auto nth = v.begin() + std::ptrdiff_t(i);
    std::nth_element(v.begin(), nth, v.end());
    if (i + 1 >= v.size()) return *nth;
    const double next = *std::min_element(nth + 1, v.end());
    return *nth + (pos - double(i)) * (next - *nth);
}

ErrorStats computeStats(const std::vector<double>& e) {
    ErrorStats s;
    s.n = e.size();
    if (e.empty()) return s;
    double sum = 0, sum2 = 0;
    for (double x : e) {
        sum += x;
        sum2 += x * x;
        s.max = std::max(s.max, x);
    }
    s.mean = sum / double(s.n);
    s.rmse = std::sqrt(sum2 / double(s.n));
    s.median = percentile(e, 50);
    s.p95 = percentile(e, 95);
    return s;
}

std::vector<TimedError> positionErrors(const Trajectory& estimate, const Trajectory& truth) {
    std::vector<TimedError> out;
    for (const auto& e : estimate) {
        const auto gt = interpolate(truth, e.t);
        if (!gt) continue;
        out.push_back({e.t, std::hypot(e.pose.x() - gt->x(), e.pose.y() - gt->y())});
    }
    return out;
}

nlohmann::json statsToJson(const ErrorStats& s) { return statsToJson(s, "m"); }

nlohmann::json statsToJson(const ErrorStats& s, const std::string& unit, double scale) {
    // no error to summarise: null, never a zero that reads as perfect
    nlohmann::json j{{"n", s.n}};
    for (const auto& [name, v] : {std::pair<const char*, double>{"rmse", s.rmse},
                                  {"mean", s.mean},
                                  {"median", s.median},
                                  {"p95", s.p95},
                                  {"max", s.max}})
        j[std::string(name) + "_" + unit] = s.n ? nlohmann::json(v * scale) : nlohmann::json();
    return j;
}

void saveJson(const std::string& path, const nlohmann::json& j) {
    // Paths on Linux are bytes, not always UTF-8 (a file named in Latin-1, say): such a byte
    // is written as U+FFFD rather than throwing after other outputs were written.
    writeFileAtomically(path,
                        j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
}

nlohmann::json readMetricsFile(const std::string& path) {
    auto j = readJsonFile(path);
    using T = JsonType;
    checkJsonShape(j,
                   {{"/method", T::String},
                    {"/rawlog", T::String},
                    {"/rawlog_format", T::String},
                    {"/ground_truth_from", T::String},
                    {"/robots", T::Object},
                    {"/warnings", T::Array},
                    {"/headline", T::Object},
                    {"/headline/reached", T::Boolean},
                    {"/headline/failed", T::Boolean},
                    {"/headline/status", T::String},
                    {"/headline/figures", T::Array}},
                   path);
    if (j.contains("robots"))
        for (const auto& [robot, r] : j["robots"].items())
            if (!r.is_object())
                throw Error(path + ": /robots/" + robot + " is not an object (a robot's errors)");
    return j;
}

nlohmann::json readProvenanceFile(const std::string& path) {
    // mrloc's own is a few kB; its outputs list grows with a run's files (at most 100,000)
    auto j = readJsonFile(path, {16u << 20, JsonLimits{}.maxDepth});
    using T = JsonType;
    checkJsonShape(j,
                   {{"/ini", T::String},
                    {"/seed", T::Number},
                    {"/seed_overrides", T::String},
                    {"/version", T::String},
                    {"/steps", T::Object},
                    {"/outputs", T::Object},
                    {"/simulated", T::Boolean},
                    {"/rawlog", T::String},
                    {"/date_utc", T::String}},
                   path);
    return j;
}

}  // namespace mrloc::common
