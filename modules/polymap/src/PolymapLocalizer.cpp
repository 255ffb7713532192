#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/Rawlog.h>
#include <mrloc/polymap/PolymapFiles.h>
#include <mrloc/polymap/PolymapLocalizer.h>
#include <mrpt/core/format.h>
#include <mrpt/obs/CObservation2DRangeScan.h>

#include <cmath>

namespace mrloc::polymap {

void PolymapLocalizer::configure(const mrpt::config::CConfigFileBase& ini) {
    options_.loadFromConfigFile(ini, "polymap");
    map_ = std::make_unique<GeneratedMap>(options_.buildMap());
    results_.clear();
}

void PolymapLocalizer::saveConfig(mrpt::config::CConfigFileBase& target) const {
    options_.saveToConfigFile(target, "polymap");
}

void PolymapLocalizer::process(const mrpt::obs::CObservation::Ptr& obs) {
    const auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservation2DRangeScan>(obs);
    if (!scan) return;
    const std::string robot = common::robotOfLabel(scan->sensorLabel);
    if (results_.count(robot)) return;  // hypotheses come from the first scan
    ScanPolygonOptions so;
    so.rangeSigma = options_.scanRangeSigma;
    so.breakAngle = options_.breakAngle * M_PI / 180;
    RobotHypotheses r;
    r.time = mrpt::Clock::toDouble(scan->timestamp);
    r.sensed = visibilityFromScan(*scan, options_.heading * M_PI / 180, so);
    double rMax = 0;
    for (const auto& v : r.sensed.vertices) rMax = std::max(rMax, v.norm());
    r.tolerance = options_.toleranceFor(rMax);
    const HypothesisGenerator gen(map_->polygon,
                                  {r.tolerance, options_.angleTolerance * M_PI / 180});
    r.hypotheses = gen.generate(r.sensed, &r.stats);
    results_[robot] = std::move(r);
}

std::map<std::string, common::Trajectory> PolymapLocalizer::estimates() const {
    std::map<std::string, common::Trajectory> out;
    for (const auto& [robot, r] : results_) {
        auto& traj = out[robot];
        if (r.hypotheses.size() == 1) {
            const auto& p = r.hypotheses[0].point;
            traj.push_back(
                {r.time, mrpt::poses::CPose3D(p.x, p.y, 0, options_.heading * M_PI / 180, 0, 0)});
        }
    }
    return out;
}

nlohmann::json PolymapLocalizer::methodMetrics() const {
    nlohmann::json j;
    j["map_vertices"] = map_->polygon.size();
    j["map"] = map_->description;
    for (const auto& [robot, r] : results_) {
        nlohmann::json rj;
        rj["hypotheses"] = r.hypotheses.size();
        rj["localized"] = r.hypotheses.size() == 1;
        rj["tolerance_m"] = r.tolerance;
        rj["sensed_vertices"] = r.sensed.size();
        rj["features"] = r.stats.features;
        rj["proposed"] = r.stats.proposed;
        rj["verified"] = r.stats.verified;
        for (const auto& h : r.hypotheses)
            rj["points"].push_back({h.point.x, h.point.y, h.mismatch});
        j["robots"][robot] = rj;
    }
    return j;
}

nlohmann::json PolymapLocalizer::groundTruthMetrics(const std::string& robot,
                                                    const common::Trajectory& gt) const {
    const auto it = results_.find(robot);
    if (it == results_.end() || gt.empty()) return {};
    const auto& r = it->second;
    const auto truth = common::interpolate(gt, r.time);
    if (!truth) return {};
    const TPoint2D p{truth->x(), truth->y()};
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& h : r.hypotheses) nearest = std::min(nearest, (h.point - p).norm());
    nlohmann::json j;
    j["truth_in_hypotheses"] = nearest <= r.tolerance;
    j["nearest_hypothesis_m"] = std::isfinite(nearest) ? nearest : -1.0;
    return j;
}

void PolymapLocalizer::writeOutputs(const std::string& outDir,
                                    const common::Trajectories& /*truth*/) const {
    map_->polygon.save(mapFilePath(outDir), map_->description);
    for (const auto& [robot, r] : results_)
        HypothesesFile{r.time, r.sensed.vertices, r.hypotheses}.write(outDir, robot);
}

}  // namespace mrloc::polymap
