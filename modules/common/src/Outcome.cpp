#include <mrloc/common/Error.h>
#include <mrloc/common/Outcome.h>
#include <mrpt/core/format.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace mrloc::common {

nlohmann::json toJson(const ObservationUse& use) {
    nlohmann::json j = {{"kind", use.kind}, {"seen", use.seen}, {"used", use.used}};
    j["unmatched"] = nlohmann::json::object();
    for (const auto& [reason, count] : use.unmatched) j["unmatched"][reason] = count;
    return j;
}

nlohmann::json toJson(const Headline& h) {
    nlohmann::json j = {{"reached", h.reached && !h.failed}, {"status", h.status}};
    if (h.failed) j["failed"] = true;
    if (!h.mechanism.empty()) j["mechanism"] = h.mechanism;
    j["figures"] = nlohmann::json::array();
    for (const auto& f : h.figures) {
        nlohmann::json fj = {{"name", f.name}, {"unit", f.unit}, {"baseline", f.baseline}};
        fj["value"] = f.value ? nlohmann::json(*f.value) : nlohmann::json(nullptr);
        if (!f.paper.empty()) fj["paper"] = f.paper;
        if (!f.differs.empty()) fj["differs"] = f.differs;
        j["figures"].push_back(fj);
    }
    return j;
}

Headline headlineFromJson(const nlohmann::json& j, const std::string& where) {
    const auto text = [&](const nlohmann::json& o, const char* key) {
        if (!o.contains(key)) return std::string();
        if (!o[key].is_string()) throw Error(where + ": headline." + key + ": not a string");
        return o[key].get<std::string>();
    };
    const auto flag = [&](const nlohmann::json& o, const char* key) {
        if (!o.contains(key)) return false;
        if (!o[key].is_boolean()) throw Error(where + ": headline." + key + ": not true or false");
        return o[key].get<bool>();
    };
    if (!j.is_object() || !j.contains("reached") || !j["reached"].is_boolean() ||
        !j.contains("figures") || !j["figures"].is_array())
        throw Error(where + ": headline: not an object with 'reached' and 'figures'");
    Headline h;
    h.reached = j["reached"].get<bool>();
    h.failed = flag(j, "failed");
    h.status = text(j, "status");
    h.mechanism = text(j, "mechanism");
    for (const auto& fj : j["figures"]) {
        if (!fj.is_object()) throw Error(where + ": headline.figures: not an object");
        HeadlineFigure f;
        f.name = text(fj, "name");
        f.unit = text(fj, "unit");
        f.paper = text(fj, "paper");
        f.differs = text(fj, "differs");
        f.baseline = flag(fj, "baseline");
        if (fj.contains("value") && fj["value"].is_number()) f.value = fj["value"].get<double>();
        h.figures.push_back(std::move(f));
    }
    return h;
}

std::string valueText(const HeadlineFigure& f, const std::string& space) {
    if (!f.value) return "none";
    std::ostringstream s;
    s.precision(3);
    s << *f.value;
    if (!f.unit.empty()) s << (f.unit == "%" ? "" : space) << f.unit;
    return s.str();
}

std::string figureText(const HeadlineFigure& f) { return f.name + " " + valueText(f); }

std::string headlineLine(const std::string& method, const Headline& h) {
    std::string line = method + ": " + h.status;
    std::string own, baselines;
    for (const auto& f : h.figures)
        (f.baseline ? baselines : own) +=
            std::string((f.baseline ? baselines : own).empty() ? "" : ", ") + figureText(f);
    if (!own.empty()) line += ": " + own;
    if (!baselines.empty()) line += "; baseline: " + baselines;
    return line;
}

std::optional<double> numberAt(const nlohmann::json& j, const std::string& path) {
    const nlohmann::json* at = &j;
    std::istringstream parts(path);
    for (std::string key; std::getline(parts, key, '/');) {
        if (!at->is_object() || !at->contains(key)) return std::nullopt;
        at = &(*at)[key];
    }
    if (!at->is_number()) return std::nullopt;
    const double v = at->get<double>();
    return std::isfinite(v) ? std::optional<double>(v) : std::nullopt;
}

namespace {

/** The translation RMSE of a truth_timeline's RPE over a travelled distance, with its delta. */
std::pair<std::optional<double>, double> rpeOverDistance(const nlohmann::json& timeline) {
    if (timeline.is_object() && timeline.contains("rpe") && timeline["rpe"].is_array())
        for (const auto& r : timeline["rpe"])
            if (r.is_object() && r.value("unit", "") == "m")
                return {numberAt(r, "translation/rmse_m"), numberAt(r, "delta").value_or(1.0)};
    return {std::nullopt, 1.0};
}

}  // namespace

std::vector<HeadlineFigure> trajectoryFigures(const nlohmann::json& metrics) {
    // on the truth's timeline (doc/evaluation.md): every truth stamp the estimates cover,
    // and how many they do, so that a localizer that stops answering is not scored on less
    std::vector<HeadlineFigure> figures;
    const nlohmann::json none;
    const auto& timeline = metrics.contains("truth_timeline") ? metrics["truth_timeline"] : none;
    figures.push_back({"APE RMSE", numberAt(timeline, "ape/rmse_m"), "m", "", "", false});
    const auto share = numberAt(timeline, "share");
    figures.push_back({"truth stamps covered", share ? std::optional(100 * *share) : std::nullopt,
                       "%", "", "", false});
    const auto [rpe, delta] = rpeOverDistance(timeline);
    figures.push_back({mrpt::format("RPE over %g m RMSE", delta), rpe, "m", "", "", false});
    // odometry alone over every robot that has it, on its truth's timeline: the RMSE of the
    // pooled errors
    double sum2 = 0, worst = 0;
    size_t n = 0;
    if (metrics.contains("robots") && metrics["robots"].is_object())
        for (const auto& [robot, r] : metrics["robots"].items())
            if (const auto rmse = numberAt(r, "odometry/truth_timeline/ape/rmse_m"))
                if (const auto k = numberAt(r, "odometry/truth_timeline/ape/n"); k && *k > 0) {
                    sum2 += *rmse * *rmse * *k, n += size_t(*k);
                    worst = std::max(
                        worst, numberAt(r, "odometry/truth_timeline/ape/max_m").value_or(*rmse));
                }
    // robots on test points never move: their odometry is exact by construction, and a
    // baseline of 0 m says nothing about the method
    if (n)
        figures.push_back({worst > 0 ? "odometry alone APE RMSE"
                                     : "odometry alone APE RMSE (the robots stand still: nothing "
                                       "to drift)",
                           std::sqrt(sum2 / double(n)), "m", "", "", true});
    return figures;
}

}  // namespace mrloc::common
