#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/Rawlog.h>
#include <mrloc/common/Trajectory.h>
#include <mrloc/polymap/PolymapFiles.h>
#include <mrloc/polymap/PolymapLocalizer.h>
#include <mrloc/sim/Robot.h>
#include <mrloc/sim/Scenario.h>
#include <mrpt/core/format.h>
#include <mrpt/obs/CObservation2DRangeScan.h>

#include <cmath>
#include <sstream>

namespace mrloc::polymap {

void PolymapLocalizer::configure(const mrpt::config::CConfigFileBase& ini) {
    options_.loadFromConfigFile(ini, "polymap");
    map_ = std::make_unique<GeneratedMap>(options_.buildMap());
    // the simulator's step and the robot's speed, as checked by the scenario's loader (the
    // defaults of a log recorded elsewhere: no [scenario])
    std::string robot = "r1";
    if (const auto listed = ini.read_string("scenario", "robots", ""); !listed.empty())
        std::istringstream(listed) >> robot;
    probeRadius_ =
        probeRadius(ini.read_double("robot." + robot, "speed", sim::RobotOptions{}.speed),
                    ini.read_double("scenario", "dt", sim::ScenarioOptions{}.dt));
    results_.clear();
}

void PolymapLocalizer::saveConfig(mrpt::config::CConfigFileBase& target) const {
    options_.saveToConfigFile(target, "polymap");
}

double probeRadius(double speed, double dt) {
    return sim::arrivalRadius(speed, dt) + kArrivalMargin;
}

RobotHypotheses hypothesesFromScan(const PolymapOptions& options, const common::Polygon& map,
                                   const mrpt::obs::CObservation2DRangeScan& scan,
                                   double arrivalRadius) {
    ScanPolygonOptions so;
    so.rangeSigma = options.scanRangeSigma;
    so.breakAngle = options.breakAngle * M_PI / 180;
    RobotHypotheses r;
    r.time = mrpt::Clock::toDouble(scan.timestamp);
    r.sensed = visibilityFromScan(scan, options.heading * M_PI / 180, so);
    double rMax = 0;
    for (const auto& v : r.sensed.vertices) rMax = std::max(rMax, v.norm());
    r.tolerance = options.toleranceFor(rMax);
    const HypothesisGenerator gen(map, {r.tolerance, options.angleTolerance * M_PI / 180});
    r.hypotheses = gen.generate(r.sensed, &r.stats);
    if (options.drive && r.hypotheses.size() > 1) {
        std::vector<TPoint2D> positions;
        for (const auto& h : r.hypotheses) positions.push_back(h.point);
        r.session =
            std::make_shared<EliminationSession>(map, positions, options.driveOptions(r.tolerance),
                                                 options.heading * M_PI / 180, arrivalRadius);
    }
    return r;
}

void PolymapLocalizer::process(const mrpt::obs::CObservation::Ptr& obs) {
    const auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservation2DRangeScan>(obs);
    if (!scan) return;
    ++scansSeen_;
    const std::string robot = common::robotOfLabel(scan->sensorLabel);
    if (const auto it = results_.find(robot); it != results_.end()) {
        // A later scan: at the probe the elimination planned (the robot drove there).
        auto& r = it->second;
        if (r.session && r.session->plan()) {
            r.session->observe(*scan);
            r.probeTimes.push_back(mrpt::Clock::toDouble(scan->timestamp));
            ++scansUsed_;
        }
        return;
    }
    ++scansUsed_;
    results_[robot] = hypothesesFromScan(options_, map_->polygon, *scan, probeRadius_);
}

std::map<std::string, common::Trajectory> PolymapLocalizer::estimates() const {
    std::map<std::string, common::Trajectory> out;
    const double heading = options_.heading * M_PI / 180;
    const auto at = [heading](double t, const TPoint2D& p) {
        return common::StampedPose{t, mrpt::poses::CPose3D(p.x, p.y, 0, heading, 0, 0)};
    };
    for (const auto& [robot, r] : results_) {
        auto& traj = out[robot];
        if (r.hypotheses.size() == 1) {
            traj.push_back(at(r.time, r.hypotheses[0].point));
        } else if (r.session && r.session->live().size() == 1) {
            // Localized by elimination: the start, and every probe the robot scanned at.
            const size_t s = r.session->live().front();
            const TPoint2D p = r.hypotheses[s].point;
            traj.push_back(at(r.time, p));
            for (size_t k = 0; k < r.probeTimes.size(); ++k)
                traj.push_back(at(r.probeTimes[k], p + r.session->stoppedAt(k, s)));
        }
    }
    return out;
}

common::ObservationUse PolymapLocalizer::observationUse() const {
    common::ObservationUse use;
    use.kind = "2-D range scans (CObservation2DRangeScan)";
    use.seen = scansSeen_;
    use.used = scansUsed_;
    // later scans with no probe planned are expected (the robot localized, or waits): not
    // a mismatch with the map, so not a warning
    return use;
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
        if (r.session) {
            nlohmann::json d;
            d["strategy"] = strategyName(options_.drive.value());
            d["probes"] = r.session->visited().size();
            double travel = 0;
            for (const auto& p : r.session->visited()) {
                travel += p.path.length;
                d["probe_points"].push_back({p.at.x, p.at.y});
            }
            d["travel_m"] = travel;
            d["left"] = r.session->live().size();
            d["localized"] = r.session->live().size() == 1;
            rj["elimination"] = d;
            rj["localized"] = r.session->live().size() == 1;
        }
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
