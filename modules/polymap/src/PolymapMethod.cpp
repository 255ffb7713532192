#include <mrloc/common/Error.h>
#include <mrloc/common/IniSection.h>
#include <mrloc/common/Metrics.h>
#include <mrloc/common/Outcome.h>
#include <mrloc/common/RunDirectory.h>
#include <mrloc/polymap/EliminationExperiment.h>
#include <mrloc/polymap/PolygonView.h>
#include <mrloc/polymap/PolymapFiles.h>
#include <mrloc/polymap/PolymapLocalizer.h>
#include <mrloc/polymap/PolymapMethod.h>
#include <mrloc/polymap/ScanReport.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/obs/CObservation2DRangeScan.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>

namespace mrloc::polymap {

void PolymapPayload::sense(sim::Step& step) {
    if (scanEvery_ < 0)
        scanEvery_ = plan_.scanner.rate > 0
                         ? std::max<long>(1, std::lround(1.0 / (plan_.scanner.rate * step.dt)))
                         : 0;
    const bool probe = phase_ == Phase::Scan;
    if (!probe && step.index != 0 && (scanEvery_ == 0 || step.index % scanEvery_ != 0)) return;
    if (probe) phase_ = Phase::Plan;  // the scan goes to onObservation, which eliminates
    for (size_t i = 0; i < step.fleet.size(); ++i) {
        const auto& robot = step.fleet.robot(i);
        auto scan = sim::scanFloorPlan(plan_.polygon, robot.pose(), plan_.scanner, step.rng);
        scan->sensorLabel = robot.options().name + ".scan";
        scan->timestamp = step.stamp;
        step.emit(scan);
    }
}

void PolymapPayload::onObservation(const mrpt::obs::CObservation::Ptr& obs) {
    if (!options_.drive) return;
    const auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservation2DRangeScan>(obs);
    if (!scan) return;
    if (!session_) {  // the first scan: hypotheses, then the first probe
        auto r = hypothesesFromScan(options_, plan_.polygon, *scan, probeRadius_);
        session_ = r.session;
        phase_ = session_ ? Phase::Plan : Phase::Done;
        return;
    }
    session_->observe(*scan);  // seed 002 step 9
}

void PolymapPayload::command(sim::Step& step) {
    if (!options_.drive || step.fleet.size() == 0) return;
    auto& robot = step.fleet.robot(0);
    const double heading = options_.heading * M_PI / 180;
    switch (phase_) {
        case Phase::Start:
            robot.stop();  // stand until the first scan
            return;
        case Phase::Scan:
        case Phase::Done:
            return;
        case Phase::Plan: {  // seed 002 step 8: drive the planned route
            if (!session_->plan()) {
                robot.stop();
                phase_ = Phase::Done;
                return;
            }
            const auto& start = robot.options().start;
            std::vector<mrpt::math::TPoint2D> route;
            for (const auto& p : session_->plan()->path.points)
                route.push_back({start.x() + p.x, start.y() + p.y});
            robot.setWaypoints(route, false);
            robot.go();
            phase_ = Phase::Driving;
            return;
        }
        case Phase::Driving: {
            const auto& goal = robot.options().waypoints.back();
            if (std::hypot(goal.x - robot.pose().x(), goal.y - robot.pose().y()) <=
                robot.arrivalRadius(step.dt))
                phase_ = Phase::Turning;
            return;
        }
        case Phase::Turning: {  // back to the known heading, then scan
            const double err = mrpt::math::wrapToPi(heading - robot.pose().phi());
            if (std::abs(err) < 1e-7) {  // the heading is known (seed 002): scan on it
                robot.stop();
                phase_ = Phase::Scan;
            } else {
                robot.turn(std::clamp(err / step.dt, -robot.options().maxTurnRate,
                                      robot.options().maxTurnRate));
            }
            return;
        }
    }
}

namespace {

/** One robot at the [polymap] start in the localizer's map (built once, when the localizer
 *  was configured); [robot.<name>] is optional and may not set a start. */
method::Scenario loadScenario(const mrpt::config::CConfigFileBase& ini,
                              const PolymapLocalizer& polymap) {
    const PolymapOptions& o = polymap.options();
    if (!polymap.hasPolygon())
        throw Error(common::configOrigin(ini) +
                    mrpt::format(": [polymap] map: mrloc's scanner simulates polygon maps (.poly, "
                                 "holes included) of up to %zu vertices; a grid map or a "
                                 "larger map is localized on a recorded log (mrloc localize "
                                 "<ini> <rawlog>)",
                                 common::Polygon::kMaxVertices));
    if (o.scanMode && o.drive)
        throw Error(common::configOrigin(ini) +
                    ": [polymap] drive: the driving robot eliminates with the exact views "
                    "(localizer = exact)");
    const GeneratedMap& map = polymap.generatedMap();
    const auto start = o.startIn(map);
    method::Scenario s;
    s.config = sim::ScenarioConfig::loadWithoutRobots(ini);
    auto& names = s.config.scenario.robots;
    if (names.empty()) names = {"r1"};
    if (names.size() != 1)
        throw Error(common::configOrigin(ini) +
                    ": [scenario] robots: a floor-plan scenario has one robot");
    sim::RobotOptions r;
    r.name = names[0];
    r.startInSection = false;  // [polymap] start has it
    if (ini.sectionExists("robot." + r.name)) r.loadFromConfigFile(ini, "robot." + r.name);
    r.start = mrpt::poses::CPose2D(start.x, start.y, mrpt::DEG2RAD(o.heading));
    if (!map.polygon.contains(start))
        throw Error(
            common::configOrigin(ini) +
            mrpt::format(": the start (%g %g) is outside the floor plan", start.x, start.y));
    s.config.robots.push_back(r);
    s.payload = std::make_unique<PolymapPayload>(
        sim::FloorPlan{map.polygon, {o.scanRays, o.scanRangeSigma, o.scanMaxRange, o.scanRate}}, o,
        probeRadius(r.speed, s.config.scenario.dt));
    return s;
}

report::Html polymapSection(const report::RunView& run) {
    if (isScanRun(run.metrics)) return scanSection(run);
    report::Html out = report::heading(2, "Polygon map: hypotheses") +
                       report::paragraph(
                           "The map P; the sensed visibility polygon V at the true start; V "
                           "placed at each hypothesis; the hypotheses (paper 002, hypothesis "
                           "generation). Colours are in the picture's legend.");
    const auto P = common::Polygon::load(mapFilePath(run.dir));
    for (const auto& [robot, r] : run.metrics["robots"].items()) {
        const auto file = HypothesesFile::read(run.dir, robot);
        PolygonViewContent view;
        view.map = P;
        view.sensed = file.sensed;
        for (const auto& h : file.hypotheses) view.hypotheses.push_back(h.point);
        if (const auto gt = run.truth.find(robot); gt != run.truth.end())
            if (const auto p = common::interpolate(gt->second, file.time))
                view.truth = common::TPoint2D{p->x(), p->y()};
        std::optional<EliminationFile> elimination;
        if (std::filesystem::exists(EliminationFile::path(run.dir))) {
            elimination = EliminationFile::read(run.dir);
            for (const auto& col : elimination->columns)
                view.routes.push_back({col.name, col.route, col.stops});
            if (!elimination->trueTour.empty())
                view.routes.push_back({"verification tour (least travel)",
                                       elimination->trueTourRoute, elimination->trueTour});
            view.overlay = elimination->overlay;
            if (!elimination->columns.empty())
                view.candidates = {elimination->columns.front().name,
                                   elimination->columns.front().candidates};
        }
        const std::string png = "polymap." + robot + ".png";
        renderPolygonView(view, run.dir + "/" + png);
        out += report::heading(3, "Robot " + robot + ": " + std::to_string(file.hypotheses.size()) +
                                      " hypotheses") +
               report::Figure{png,
                              "the map with V placed at each numbered hypothesis: the true start "
                              "(yellow) should be one of them"}
                   .html();
        // the headline: where the truth is among the hypotheses (# as in the table below)
        if (view.truth && !file.hypotheses.empty()) {
            size_t best = 0;
            for (size_t i = 1; i < file.hypotheses.size(); ++i)
                if ((file.hypotheses[i].point - *view.truth).norm() <
                    (file.hypotheses[best].point - *view.truth).norm())
                    best = i;
            out += report::paragraph(
                report::bold(mrpt::format("%zu hypotheses; the true start is hypothesis #%zu",
                                          file.hypotheses.size(), best + 1)) +
                mrpt::format(", %.3f m from it.",
                             (file.hypotheses[best].point - *view.truth).norm()));
        }
        const auto robots = run.metrics.value("polymap", nlohmann::json::object())
                                .value("robots", nlohmann::json::object());
        if (robots.contains(robot) && robots[robot].is_object() &&
            robots[robot].contains("elimination") && robots[robot]["elimination"].is_object()) {
            const auto& e = robots[robot]["elimination"];
            const auto value = [&](const char* key) {
                return report::cellText(e.value(key, nlohmann::json()));
            };
            const std::string travel = e.contains("travel_m") && e["travel_m"].is_number()
                                           ? mrpt::format("%.2f", e["travel_m"].get<double>())
                                           : std::string("none");
            out += report::paragraph(
                "The robot eliminated as it drove (" +
                report::code("drive = " + value("strategy")) + "): " + value("probes") +
                " probe(s)" +
                (e.value("fallbacks", 0) > 0
                     ? " (" + value("fallbacks") +
                           " beyond the algorithm's own candidates: doc/polymap.md#fall-backs)"
                     : std::string()) +
                ", " + travel + " m of travel, " +
                (e.value("localized", nlohmann::json()) == true
                     ? "localized: one hypothesis left, the errors above are its estimates."
                     : "not localized: " + value("left") + " hypotheses left."));
        }
        if (!view.routes.empty()) {  // a close-up of the routes from the true start
            TPoint2D lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
            for (const auto& route : view.routes)
                for (const auto& p : route.path)
                    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)},
                    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
            // the routes with a margin around them (the legend is beside the drawing)
            const double pad = 0.25 * std::max({hi.x - lo.x, hi.y - lo.y, 4.0});
            view.box = std::make_pair(lo - TPoint2D{pad, pad}, hi + TPoint2D{pad, pad});
            const std::string zoom = "polymap." + robot + ".routes.png";
            renderPolygonView(view, run.dir + "/" + zoom, 900, 700);
            out += report::paragraph(
                       "Close-up: the overlay region OI of all hypotheses at the true start, the "
                       "first algorithm's candidates for its first probe, and each algorithm's "
                       "route from the run's true start (paper 002 figs. 2-5), its probes as "
                       "dots.") +
                   report::Figure{zoom,
                                  "each algorithm's route from the true start until one hypothesis "
                                  "is left: shorter is better"}
                       .html();
        }
        report::Table table(
            {"#", "x (m)", "y (m)", "translation (m)", "mismatch (m)", "distance to truth (m)"});
        for (size_t i = 0; i < file.hypotheses.size(); ++i) {
            const auto& h = file.hypotheses[i];
            const std::string d =
                view.truth ? mrpt::format("%.3f", (h.point - *view.truth).norm()) : "none";
            table.row({std::to_string(i + 1), mrpt::format("%.3f", h.point.x),
                       mrpt::format("%.3f", h.point.y),
                       mrpt::format("%.3f %.3f", h.translation.x, h.translation.y),
                       mrpt::format("%.4f", h.mismatch), d});
        }
        out += table.html();
        if (elimination) out += eliminationSection(run.dir, *elimination);
    }
    return out;
}

/** The error of each robot's start, the first estimate (the hypothesis left, at the time of
 *  the first scan), against the truth at that time; the worst of the robots. The later
 *  estimates (the probes, the start moved by the odometry) are the trajectory's figures, not
 *  the start's. None without a truth. */
std::optional<double> startError(const PolymapLocalizer& localizer, const std::string& outDir) {
    std::optional<double> worst;
    for (const auto& [robot, traj] : localizer.estimates()) {
        const std::string truthPath = common::run_dir::groundTruth(outDir, robot);
        if (traj.empty() || !std::filesystem::exists(truthPath)) continue;
        const auto e = common::positionErrors({traj.front()}, common::loadTum(truthPath));
        if (!e.empty()) worst = std::max(worst.value_or(0.0), e.front().error);
    }
    return worst;
}

/** Localized or not (one hypothesis left, per robot), with the hypotheses of the first
 *  scan, the travel the elimination needed and the start's error against the truth. */
common::Headline polymapHeadline(const method::HeadlineOf<PolymapLocalizer>& in) {
    if (in.localizer.scanMode()) {
        auto scan = scanHeadline(in.localizer.methodMetrics());
        // doc/polymap.md, "The paper's mechanism: as stated, as shipped"
        scan.mechanism =
            "the scan localizer (localizer = scan): a beam model of the real scans against the "
            "map, beyond paper 002's exact visibility polygons";
        return scan;
    }
    common::Headline h;
    std::string notLocalized;
    double hypotheses = 0, travel = 0;
    bool drove = false;
    std::string fellBack;  // probes beyond the algorithm's own candidates, per robot
    for (const auto& [robot, r] : in.localizer.results()) {
        hypotheses += double(r.hypotheses.size());
        const size_t left = r.session ? r.session->live().size() : r.hypotheses.size();
        // failed, not just short: the scan fits no place of the map, or the elimination has
        // hypotheses left and no probe that separates them
        if (r.hypotheses.empty() || (r.session && left > 1 && !r.session->plan())) h.failed = true;
        if (r.session && left > 1 && !r.session->plan())
            notLocalized += mrpt::format(
                "%srobot '%s': no probe separates the %zu hypotheses left (their views agree "
                "wherever the robot can go under all of them, the overlay region, %s)",
                notLocalized.empty() ? "" : "; ", robot.c_str(), left,
                r.session->fruitlessProbes() == 0
                    ? "at the algorithm's candidates"
                    : mrpt::format("but for %zu probe(s) whose scans could not tell them apart",
                                   r.session->fruitlessProbes())
                          .c_str());
        else if (left != 1)
            notLocalized += mrpt::format(
                "%srobot '%s': %zu hypotheses %s", notLocalized.empty() ? "" : "; ", robot.c_str(),
                left,
                r.hypotheses.empty()
                    // a map feature within the tolerance of another blurs into it in the scan
                    ? mrpt::format("fit the first scan (is this the robot's map? Its openings "
                                   "and walls must be wider than the scan's tolerance, %.3f m)",
                                   r.tolerance)
                          .c_str()
                    : r.session
                          ? "left, the log ending before the next probe (a longer [scenario] "
                            "duration drives on)"
                          : "from the first scan, no drive to eliminate them ([polymap] drive)");
        if (r.session) {
            drove = true;
            std::map<std::string, size_t> sources;
            for (const auto& p : r.session->visited()) {
                travel += p.path.length;
                if (p.source != ProbeSource::Own) ++sources[probeSourceName(p.source)];
            }
            for (const auto& [source, n] : sources)
                fellBack += mrpt::format("%s%zu of robot '%s''s %zu probes from %s candidates",
                                         fellBack.empty() ? "" : ", ", n, robot.c_str(),
                                         r.session->visited().size(), source.c_str());
        }
    }
    h.reached = notLocalized.empty();
    h.status = h.reached ? "localized" : "not localized: " + notLocalized;
    // doc/polymap.md, "The paper's mechanism: as stated, as shipped"
    const auto& options = in.localizer.options();
    h.mechanism = "paper 002's hypotheses from the exact visibility polygon";
    if (options.drive)
        h.mechanism += "; the robot drives paper 002's elimination with the " +
                       strategyName(*options.drive) + " algorithm (drive)";
    else if (!options.elimination.empty()) {
        std::string names;
        for (const auto s : options.elimination)
            names += (names.empty() ? "" : ", ") + strategyName(s);
        h.mechanism += "; paper 002's elimination replayed with " + names + " (elimination)";
    }
    if (!fellBack.empty())  // the algorithm's own candidates separated nothing (issue 55)
        h.status += " (the " + strategyName(in.localizer.options().drive.value()) +
                    " algorithm fell back: " + fellBack + ")";
    h.figures.push_back({"hypotheses from the first scan", hypotheses, "", "", "", false});
    if (drove) h.figures.push_back({"travel", travel, "m", "", "", false});
    // the bounds the travel is measured against, when the experiment computed them (seed 002
    // gives none): the first-separation distance no strategy beats, and the true start's
    // verification tour, the least travel that rules the others out with the truth known
    if (drove && std::filesystem::exists(EliminationFile::path(in.outDir))) {
        const auto file = EliminationFile::read(in.outDir);
        const auto finite = [](double d) {
            return std::isfinite(d) ? std::optional(d) : std::nullopt;
        };
        h.figures.push_back({"bound: first separation", finite(file.bound), "m", "", "",
                             false});  // seed 002 reports no bound
        if (file.trueStart < file.tour.size())
            h.figures.push_back({"bound: verification tour (least travel, truth known)",
                                 finite(file.tour[file.trueStart]), "m", "", "",
                                 false});  // seed 002 reports no bound
    }
    h.figures.push_back(
        {"start error (worst robot)", startError(in.localizer, in.outDir), "m", "", "", false});
    // on the truth's timeline: the start found, carried by each robot's odometry (doc/polymap.md)
    for (auto f : common::trajectoryFigures(in.metrics)) {
        if (!f.baseline) f.name = "from the start found, by odometry: " + f.name;
        h.figures.push_back(std::move(f));
    }
    return h;
}

}  // namespace

void registerMethod(method::Registry& registry) {
    method::MethodUnit<PolymapLocalizer> m;
    m.name = "polymap";
    m.sections = {"polymap"};
    m.keys = {PolymapOptions::keys().docs()};
    // MRPT's pf-localization INIs (a grid map to localize laser scans in) name no mrloc
    // section: their occupancy grid's creation options say they are this method's
    m.foreignSections = {"MetricMap_occupancyGrid_00_creationOpts"};
    m.reads = {"CObservation2DRangeScan"};
    m.exampleConfig =
        "config/polymap_file.ini (your map as a .poly in [polymap] map), or "
        "config/polymap_localization_demo.ini (a real laser log on an MRPT .simplemap or .gridmap)";
    m.headline = polymapHeadline;
    m.scenario = loadScenario;
    m.experiment = eliminationExperiment;  // seed 002 Tables 1-2, Figs. 6-7
    m.work = polymapWork;
    m.report.subject = "minimum-distance localization in a polygon map (paper 002)";
    m.report.html = polymapSection;  // its own picture: no world top view
    registry.add(std::move(m));
}

}  // namespace mrloc::polymap
