#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/GroundTruthFile.h>
#include <mrloc/common/Names.h>
#include <mrloc/common/Rawlog.h>
#include <mrloc/common/Trajectory.h>
#include <mrloc/polymap/PolymapFiles.h>
#include <mrloc/polymap/PolymapLocalizer.h>
#include <mrloc/sim/Robot.h>
#include <mrloc/sim/Scenario.h>
#include <mrpt/core/format.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/poses/CPose2D.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace mrloc::polymap {

void PolymapLocalizer::configure(const mrpt::config::CConfigFileBase& ini) {
    // MRPT's pf-localization INI, unchanged: its map_file, region and grid options
    if (!ini.sectionExists("polymap") && ini.sectionExists("LocalizationExperiment"))
        options_.loadFromMrptLocalizationIni(ini);
    else
        options_.loadFromConfigFile(ini, "polymap");
    results_.clear();
    odometry_.clear();
    scanRobots_.clear();
    scansSeen_ = scansUsed_ = 0;
    map_.reset();
    wallMap_.reset();
    grid_.reset();
    if (options_.scanMode) {
        configureScanMode();
    } else if (isMrptMapFile(options_.mapFile)) {
        // the exact pipeline on an MRPT grid: the free space around the start, as a polygon
        // with holes (GridTrace.h's traceFreeSpace)
        const auto grid = loadGridMap(options_.mapFile, options_.trace);
        const std::string what = "map " + options_.mapFile;
        GridTraceOptions trace = options_.trace;
        if (trace.simplify == 0) trace.simplify = kExactTraceSimplify;
        if (trace.open == 0) trace.open = kExactTraceOpen;
        map_ = std::make_unique<GeneratedMap>(GeneratedMap{
            common::Polygon::fromRings(traceFreeSpace(grid, trace, *options_.start, what), what),
            {},
            "the free space around the start in " + what + ", traced"});
    } else {
        map_ = std::make_unique<GeneratedMap>(options_.buildMap());
    }
    options_.trace.insertOptions = nullptr;  // the INI's lifetime ends with this call
    if (!map_) return;                       // a grid map: nothing to simulate, no exact pipeline
    // the simulator's step and the robot's speed, as checked by the scenario's loader (the
    // defaults of a log recorded elsewhere: no [scenario])
    std::string robot = "r1";
    if (const auto listed = ini.read_string("scenario", "robots", ""); !listed.empty())
        std::istringstream(listed) >> robot;
    probeRadius_ =
        probeRadius(ini.read_double("robot." + robot, "speed", sim::RobotOptions{}.speed),
                    ini.read_double("scenario", "dt", sim::ScenarioOptions{}.dt));
}

void PolymapLocalizer::configureScanMode() {
    reference_.clear();
    referenceNotes_ = nlohmann::json::array();
    if (!options_.referenceFile.empty()) {
        // TUM or "step x y phi": MRPT's apps' paths, told by their columns
        const auto format = common::groundTruthFormatOf(options_.referenceFile);
        if (format != "tum" && format != "index_x_y_phi")
            throw Error(options_.referenceFile +
                        ": a reference path is TUM (8 columns) or \"step x y phi\" (4)");
        common::GroundTruthSource source;
        source.path = options_.referenceFile;
        source.format = *format;
        referenceByStep_ = *format == "index_x_y_phi";
        // a step's time is known only once the log is read (referencePath): until then each
        // row keeps its step number as its time
        std::vector<double> steps(referenceByStep_ ? 1000000 : 0);
        for (size_t i = 0; i < steps.size(); ++i) steps[i] = double(i);
        reference_ = common::loadGroundTruth(source, steps);
        // its own comment lines (who made it, how), for the report: at most 12 of 300 bytes
        std::ifstream in(options_.referenceFile);
        for (std::string line; referenceNotes_.size() < 12 && std::getline(in, line);) {
            if (line.empty() || (line[0] != '%' && line[0] != '#')) continue;
            const auto text = line.find_first_not_of("%# \t");
            if (text != std::string::npos)
                referenceNotes_.push_back(common::printable(line.substr(text, 300)));
        }
    }
    const std::string& file = options_.mapFile;
    const double freeResolution = 0.05;  // where the scanner may stand, for a .poly map
    if (isMrptMapFile(file)) {
        grid_ =
            std::make_shared<mrpt::maps::COccupancyGridMap2D>(loadGridMap(file, options_.trace));
        wallMap_ = std::make_unique<WallMap>(
            traceGrid(*grid_, options_.trace, "map " + file, &traceStats_));
        return;
    }
    std::vector<std::vector<TPoint2D>> rings;
    if (!file.empty()) {
        rings = loadPolyRings(file);
        // the scan localizer takes rings up to kMaxWallVertices in all; the polygon the
        // simulator casts in (O(n) a beam) only within common::Polygon's bound
        size_t vertices = 0;
        for (const auto& r : rings) vertices += r.size();
        if (vertices <= common::Polygon::kMaxVertices)
            map_ = std::make_unique<GeneratedMap>(
                GeneratedMap{common::Polygon::fromRings(rings, file), {}, "map " + file});
    } else {
        map_ = std::make_unique<GeneratedMap>(options_.buildMap());
        for (size_t r = 0; r < map_->polygon.ringCount(); ++r)
            rings.push_back(map_->polygon.ringVertices(r));
    }
    wallMap_ = std::make_unique<WallMap>(wallMapOfRings(std::move(rings), freeResolution,
                                                        options_.trace.clearance,
                                                        map_ ? map_->description : "map " + file));
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
    // A place is kept if its exact view is within the tolerance of V's boundary, or else of
    // 99 % of the scan's beams: a traced building's view has slits narrower than a beam step that
    // the boundary distance counts in full and the beams pass between (doc/polymap.md).
    // (the beams read only if a place needs them: most views pass on their boundary)
    std::optional<ScanBeams> beams;
    const auto byBeams = [&](const TPoint2D&,
                             const VisibilityPolygon& Vp) -> std::optional<double> {
        if (!beams) beams = beamsOf(scan, options.heading * M_PI / 180);
        const double mismatch = beamMismatch(*beams, Vp, kBeamsThatMustAgree);
        return mismatch <= r.tolerance ? std::optional(mismatch) : std::nullopt;
    };
    r.hypotheses = gen.generate(r.sensed, &r.stats, byBeams);
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
    if (options_.scanMode) return processScanMode(obs);
    if (const auto odo = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(obs)) {
        if (odo->timestamp == INVALID_TIMESTAMP) return;
        // on the scans' clock (r.time, probeTimes): what the start is carried from
        const double t = mrpt::Clock::toDouble(odo->timestamp);
        odometry_[common::robotOfLabel(odo->sensorLabel)].push_back(
            {t, mrpt::poses::CPose3D(odo->odometry)});
        return;
    }
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

void PolymapLocalizer::processScanMode(const mrpt::obs::CObservation::Ptr& obs) {
    if (const auto odo = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(obs)) {
        auto& r = scanRobots_[common::robotOfLabel(odo->sensorLabel)];
        const mrpt::math::TPose2D p = odo->odometry.asTPose();
        if (r.odometry && r.elimination)
            r.travelled += std::hypot(p.x - r.odometry->x, p.y - r.odometry->y);
        r.odometry = p;
        ++r.stepsWaiting;
        return;
    }
    const auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservation2DRangeScan>(obs);
    if (!scan) return;
    ++scansSeen_;
    auto& r = scanRobots_[common::robotOfLabel(scan->sensorLabel)];
    const ScanBeamSet beams = beamSetOf(*scan);
    for (; r.stepsWaiting > 0; --r.stepsWaiting) r.stepTimes.push_back(beams.time);
    if (!r.elimination) {
        // seed 002's hypothesis generation, from a real scan
        auto o = options_.scan;
        r.tolerance = options_.beamTolerance > 0
                          ? options_.beamTolerance
                          : 3 * beams.sigma + 2 * wallMap_->freeCells.resolution + 0.05;
        o.tolerance = r.tolerance;
        if (options_.headingKnown) o.heading = options_.heading * M_PI / 180;
        r.first = globalHypotheses(*wallMap_, beams, o, &r.stats);
        r.firstTime = beams.time;
        r.elimination = std::make_shared<PassiveElimination>(*wallMap_, o, r.first, beams.time);
        r.odometryAtScan = r.odometry;
        ++scansUsed_;
        return;
    }
    // the motion since the last scan, by odometry (none logged: the robot is taken to stand,
    // and the refinement's first steps absorb what it moved)
    mrpt::math::TPose2D motion{0, 0, 0};
    if (r.odometry && r.odometryAtScan)
        motion =
            (mrpt::poses::CPose2D(*r.odometry) - mrpt::poses::CPose2D(*r.odometryAtScan)).asTPose();
    r.odometryAtScan = r.odometry;
    r.elimination->update(motion, r.travelled, beams);
    ++scansUsed_;
}

std::map<std::string, common::Trajectory> PolymapLocalizer::scanEstimates() const {
    std::map<std::string, common::Trajectory> out;
    for (const auto& [robot, r] : scanRobots_) {
        if (!r.elimination || r.elimination->live().size() != 1) continue;
        // the one left, from the first scan on: where it was at every scan it lived
        auto& traj = out[robot];
        for (const auto& [t, p] : r.elimination->live().front().path)
            traj.push_back({t, mrpt::poses::CPose3D(p.x, p.y, 0, p.phi, 0, 0)});
    }
    return out;
}

std::map<std::string, common::Trajectory> PolymapLocalizer::estimates() const {
    if (options_.scanMode) return scanEstimates();
    std::map<std::string, common::Trajectory> out;
    const double heading = options_.heading * M_PI / 180;
    const auto at = [heading](double t, const TPoint2D& p) {
        return common::StampedPose{t, mrpt::poses::CPose3D(p.x, p.y, 0, heading, 0, 0)};
    };
    for (const auto& [robot, r] : results_) {
        auto& traj = out[robot];
        std::optional<size_t> left;  // the hypothesis left: the start
        if (r.hypotheses.size() == 1)
            left = 0;
        else if (r.session && r.session->live().size() == 1)
            left = r.session->live().front();
        if (!left) continue;
        const TPoint2D start = r.hypotheses[*left].point;
        // the start carried by the robot's odometry to each of its readings
        const auto odometry = odometry_.find(robot);
        const common::Trajectory none;
        const auto& readings = odometry == odometry_.end() ? none : odometry->second;
        traj = common::carriedByOdometry(at(r.time, start).pose, r.time, readings);
        if (!common::interpolate(readings, r.time) && r.session)
            // no odometry to carry it: the start, and every probe the robot scanned at
            for (size_t k = 0; k < r.probeTimes.size(); ++k)
                traj.push_back(at(r.probeTimes[k], start + r.session->stoppedAt(k, *left)));
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

common::Trajectory PolymapLocalizer::referencePath(const std::string& robot) const {
    if (!referenceByStep_) return reference_;
    common::Trajectory out;
    const auto it = scanRobots_.find(robot);
    if (it == scanRobots_.end()) return out;
    const auto& times = it->second.stepTimes;
    for (const auto& row : reference_)
        if (size_t(row.t) < times.size()) out.push_back({times[size_t(row.t)], row.pose});
    return out;
}

std::optional<ReferenceComparison> PolymapLocalizer::compareWithReference(
    const std::string& robot) const {
    const auto ref = referencePath(robot);
    const auto estimates = scanEstimates();
    const auto it = estimates.find(robot);
    if (ref.empty() || it == estimates.end()) return std::nullopt;
    ReferenceComparison c;
    std::vector<double> errors;
    double headingSum = 0;
    for (const auto& e : it->second) {
        if (e.t < ref.front().t - 1e-6 || e.t > ref.back().t + 1e-6) continue;
        const auto r = common::interpolate(ref, e.t);
        if (!r) continue;
        const double d = std::hypot(e.pose.x() - r->x(), e.pose.y() - r->y());
        const double h = std::abs(mrpt::math::wrapToPi(e.pose.yaw() - r->yaw())) * 180 / M_PI;
        if (errors.empty()) c.from = e.t - scanRobots_.at(robot).firstTime;
        errors.push_back(d);
        headingSum += h;
        c.headingMax = std::max(c.headingMax, h);
        c.max = std::max(c.max, d);
        c.last = d;
    }
    if (errors.empty()) return std::nullopt;
    c.n = errors.size();
    for (const double d : errors) c.mean += d / double(c.n);
    c.headingMean = headingSum / double(c.n);
    std::nth_element(errors.begin(), errors.begin() + long(c.n / 2), errors.end());
    c.median = errors[c.n / 2];
    return c;
}

nlohmann::json PolymapLocalizer::scanMetrics() const {
    nlohmann::json j;
    j["localizer"] = "scan";
    j["map"] = wallMap_->description;
    j["map_rings"] = wallMap_->rings.size();
    size_t vertices = 0;
    for (const auto& ring : wallMap_->rings) vertices += ring.size();
    j["map_vertices"] = vertices;
    j["free_cells"] = wallMap_->freeCells.count();
    if (grid_) {
        j["grid"] = {{"width", traceStats_.gridWidth},
                     {"height", traceStats_.gridHeight},
                     {"resolution_m", traceStats_.resolution},
                     {"specks_dropped", traceStats_.specksDropped},
                     {"contour_points", traceStats_.contourPoints},
                     {"simplify_m", traceStats_.simplify}};
    }
    for (const auto& [robot, r] : scanRobots_) {
        if (!r.elimination) continue;
        nlohmann::json rj;
        const auto& e = *r.elimination;
        rj["hypotheses"] = r.first.size();
        rj["tolerance_m"] = r.tolerance;
        rj["heading_known"] = options_.headingKnown;
        rj["positions_searched"] = r.stats.positions;
        rj["search_step_m"] = r.stats.positionStep;
        rj["poses_scored"] = r.stats.poses;
        rj["refined"] = r.stats.refined;
        for (const auto& h : r.first)
            rj["points"].push_back({h.pose.x, h.pose.y, h.pose.phi, h.score.agreement(),
                                    h.score.throughFraction(), h.score.clutterFraction()});
        rj["scans"] = e.scans;
        rj["left"] = e.live().size();
        rj["localized"] = e.live().size() == 1;
        rj["unique_after_s"] = e.uniqueTime ? nlohmann::json(*e.uniqueTime) : nlohmann::json();
        rj["unique_after_m"] =
            e.uniqueDistance ? nlohmann::json(*e.uniqueDistance) : nlohmann::json();
        rj["travelled_m"] = r.travelled;
        rj["runner_up_agreement"] = r.stats.runnerUp;
        if (const auto c = compareWithReference(robot)) {
            rj["reference"] = {{"notes", referenceNotes_},
                               {"name", options_.referenceName},
                               {"file", options_.referenceFile},
                               {"compared", c->n},
                               {"from_s", c->from},
                               {"mean_m", c->mean},
                               {"median_m", c->median},
                               {"max_m", c->max},
                               {"last_m", c->last},
                               {"heading_mean_deg", c->headingMean},
                               {"heading_max_deg", c->headingMax}};
        }
        if (!e.live().empty()) {
            const auto& best = e.live().front();
            rj["survivor_rank"] = best.rank;
            rj["final_pose"] = {best.pose.x, best.pose.y, best.pose.phi};
            rj["final_agreement"] = best.score.agreement();
        }
        j["robots"][robot] = rj;
    }
    return j;
}

nlohmann::json PolymapLocalizer::methodMetrics() const {
    if (options_.scanMode) return scanMetrics();
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
            size_t fallbacks = 0;
            for (const auto& p : r.session->visited()) {
                travel += p.path.length;
                d["probe_points"].push_back({p.at.x, p.at.y});
                d["probe_sources"].push_back(probeSourceName(p.source));
                fallbacks += p.source != ProbeSource::Own;
            }
            d["travel_m"] = travel;
            d["fallbacks"] = fallbacks;  // probes beyond the algorithm's own candidates
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
    if (options_.scanMode) {
        savePolyRings(outDir + "/map.traced.poly", wallMap_->rings,
                      wallMap_->description + (grid_ ? ": the walls traced from the grid, each "
                                                       "ring a wall's boundary"
                                                     : ""));
        if (grid_)
            renderMap(grid_.get(), *wallMap_, {}, outDir + "/" + kTracePicture,
                      "Traced map: " + std::to_string(wallMap_->rings.size()) +
                          " rings over the occupancy grid");
        const auto estimates = scanEstimates();
        for (const auto& [robot, r] : scanRobots_) {
            MapOverlay overlay;
            for (const auto& h : r.first) overlay.hypotheses.push_back(h.pose);
            if (const auto e = estimates.find(robot); e != estimates.end()) {
                auto& path = overlay.paths.emplace_back();
                path.label = "mrloc (the hypothesis left)";
                for (const auto& p : e->second) path.points.push_back({p.pose.x(), p.pose.y()});
            }
            if (const auto ref = referencePath(robot); !ref.empty()) {
                auto& path = overlay.paths.emplace_back();
                path.label = options_.referenceName;
                for (const auto& p : ref) path.points.push_back({p.pose.x(), p.pose.y()});
            }
            overlay.cropToOverlay = true;
            renderMap(grid_.get(), *wallMap_, overlay, outDir + "/" + scanPicture(robot),
                      "Robot " + robot + ": hypotheses from the first scan and the path");
        }
        return;
    }
    map_->polygon.save(mapFilePath(outDir), map_->description);
    for (const auto& [robot, r] : results_)
        HypothesesFile{r.time, r.sensed.vertices, r.hypotheses}.write(outDir, robot);
}

}  // namespace mrloc::polymap
