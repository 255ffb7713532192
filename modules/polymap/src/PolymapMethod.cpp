#include <mrloc/common/Error.h>
#include <mrloc/common/IniSection.h>
#include <mrloc/polymap/PaperTables.h>
#include <mrloc/polymap/PolygonView.h>
#include <mrloc/polymap/PolymapFiles.h>
#include <mrloc/polymap/PolymapLocalizer.h>
#include <mrloc/polymap/PolymapMethod.h>
#include <mrloc/report/Plots.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/obs/CObservation2DRangeScan.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
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
        auto r = hypothesesFromScan(options_, plan_.polygon, *scan);
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
        case Phase::Scan:
        case Phase::Done:
            if (phase_ == Phase::Start) robot.stop();  // stand until the first scan
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
                std::max(0.02, robot.options().speed * step.dt))
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
                              const common::Localizer& localizer) {
    const auto& polymap = dynamic_cast<const PolymapLocalizer&>(localizer);
    const PolymapOptions& o = polymap.options();
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
        sim::FloorPlan{map.polygon, {o.scanRays, o.scanRangeSigma, o.scanMaxRange, o.scanRate}},
        o);
    return s;
}

/** The algorithms of `elimination`, randomized once per X, as experiment columns. */
std::vector<std::pair<std::string, EliminationOptions>> experimentColumns(const PolymapOptions& o,
                                                                          double tolerance) {
    std::vector<std::pair<std::string, EliminationOptions>> out;
    for (const ProbeStrategy strategy : o.elimination) {
        const std::vector<int> xs =
            strategy == ProbeStrategy::Randomized ? o.randomPoints : std::vector<int>{0};
        for (const int x : xs) {
            EliminationOptions eo;
            eo.strategy = strategy;
            if (x > 0) eo.randomPoints = x;
            eo.seed = (uint32_t)o.eliminationSeed;
            eo.tolerance = tolerance;  // the generation's: see doc/polymap.md
            eo.clearance = o.clearance;
            out.push_back({strategyName(strategy) + (x > 0 ? ":" + std::to_string(x) : ""), eo});
        }
    }
    return out;
}

/** One localization from `start`, timed. */
std::pair<EliminationRun, double> timedElimination(const Eliminator& eliminator, size_t start) {
    const auto t0 = std::chrono::steady_clock::now();
    auto run = eliminateExactly(eliminator, start);
    return {std::move(run),
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()};
}

/** Seed 002 Figs. 6-7: steps maps of each `sweep_steps`, their sites the hypotheses, at most
 *  `sweep_starts` starts each, evenly spread. */
EliminationSweepFile eliminationSweep(const PolymapOptions& o, double tolerance) {
    EliminationSweepFile sweep;
    for (const int steps : o.sweepSteps) {
        StepsMapOptions so = o.steps;
        so.steps = steps;
        const auto map = stepsMap(so);
        const size_t k = map.sites.size();
        const size_t count = std::min(k, (size_t)o.sweepStarts);
        for (const auto& [name, eo] : experimentColumns(o, tolerance)) {
            const Eliminator eliminator(map.polygon, map.sites, eo);
            EliminationSweepFile::Row row{(int)map.polygon.size(), (int)k, (int)count, name};
            for (size_t s = 0; s < count; ++s) {
                const auto [run, seconds] = timedElimination(eliminator, s * k / count);
                row.meanTravel += run.travel / double(count);
                row.meanSeconds += seconds / double(count);
                row.notLocalized += run.survivors.size() != 1;
            }
            sweep.rows.push_back(row);
        }
    }
    return sweep;
}

/** Seed 002's experiment (Tables 1-2) on the run's hypotheses: every hypothesis in turn the
 *  truth, every configured algorithm, closed loop with exact views, deciding with the
 *  tolerance the hypotheses were generated with; then the sweep over n, if asked. */
std::vector<std::string> eliminationExperiment(const method::ExperimentInput& in) {
    const auto& loc = dynamic_cast<const PolymapLocalizer&>(in.localizer);
    const PolymapOptions& o = loc.options();
    if (o.elimination.empty()) return {};
    if (loc.results().empty())
        throw Error("[polymap] elimination: the rawlog gave no scan to generate hypotheses from");
    const auto& [robot, r] = *loc.results().begin();
    std::vector<TPoint2D> positions;
    for (const auto& h : r.hypotheses) positions.push_back(h.point);
    if (positions.empty()) throw Error("[polymap] elimination: no hypotheses to eliminate");
    // The run's true start: the hypothesis nearest the truth (or the configured start).
    TPoint2D truth = o.startIn(loc.generatedMap());
    if (const auto gt = in.truth.find(robot); gt != in.truth.end())
        if (const auto p = common::interpolate(gt->second, r.time)) truth = {p->x(), p->y()};
    EliminationFile file;
    for (size_t i = 1; i < positions.size(); ++i)
        if ((positions[i] - truth).norm() < (positions[file.trueStart] - truth).norm())
            file.trueStart = i;
    EliminationTimes times;
    const auto& P = loc.generatedMap().polygon;
    const auto columns = experimentColumns(o, r.tolerance);
    if (positions.size() > 1) {  // the same for every start: all hypotheses are live
        std::vector<size_t> live(positions.size());
        for (size_t i = 0; i < live.size(); ++i) live[i] = i;
        if (const auto d = Eliminator(P, positions, columns.front().second)
                               .firstSeparation(live, {0, 0}))
            file.bound = *d;
    }
    std::vector<size_t> all(positions.size());
    for (size_t i = 0; i < all.size(); ++i) all[i] = i;
    const TPoint2D at = positions[file.trueStart];
    for (const auto& [name, eo] : columns) {
        const Eliminator eliminator(P, positions, eo);
        EliminationFile::Column col;
        col.name = name;
        if (positions.size() > 1) {  // what the first step chose from, for the picture
            const auto [candidates, oi] = eliminator.candidatesAndRegion(all);
            for (const auto& c : candidates) col.candidates.push_back(at + c);
            if (file.overlay.empty())
                for (const auto& v : oi.outer) file.overlay.push_back(at + v);
        }
        times.seconds.emplace_back();
        for (size_t start = 0; start < positions.size(); ++start) {
            const auto [run, seconds] = timedElimination(eliminator, start);
            times.seconds.back().push_back(seconds);
            col.travel.push_back(run.travel);
            col.probes.push_back((int)run.probes.size());
            col.survivors.push_back((int)run.survivors.size());
            if (start != file.trueStart) continue;
            col.route.push_back(positions[start]);
            for (const auto& probe : run.probes) {
                for (size_t k = 1; k < probe.path.points.size(); ++k)
                    col.route.push_back(positions[start] + probe.path.points[k]);
                col.stops.push_back(positions[start] + probe.at);
            }
        }
        file.columns.push_back(std::move(col));
    }
    file.write(in.outDir);
    times.write(in.outDir);
    std::vector<std::string> written{EliminationFile::path(in.outDir),
                                     EliminationTimes::path(in.outDir)};
    if (!o.sweepSteps.empty()) {
        eliminationSweep(o, r.tolerance).write(in.outDir);
        written.push_back(EliminationSweepFile::path(in.outDir));
    }
    return written;
}

/** Figs. 6-7: mean path and mean time against n, one line per algorithm. */
void plotSweep(const EliminationSweepFile& sweep, const std::string& dir) {
    std::vector<std::string> columns;
    for (const auto& r : sweep.rows)
        if (std::find(columns.begin(), columns.end(), r.column) == columns.end())
            columns.push_back(r.column);
    for (const bool travel : {true, false}) {
        std::string body, plot;
        for (size_t c = 0; c < columns.size(); ++c) {
            std::vector<std::pair<double, double>> xy;
            for (const auto& r : sweep.rows)
                if (r.column == columns[c])
                    xy.emplace_back(r.n, travel ? r.meanTravel : 1e3 * r.meanSeconds);
            body += report::dataBlock("c" + std::to_string(c), xy);
            plot += std::string(plot.empty() ? "plot " : ", ") + "$c" + std::to_string(c) +
                    " using 1:2 with linespoints lw 2 title '" + columns[c] + "'";
        }
        body += std::string("set xlabel 'map vertices n'\n") +
                (travel ? "set ylabel 'mean path d (m)'\nset key bottom right\n"
                        : "set ylabel 'mean time t per localization (ms)'\nset logscale y\n") +
                plot + "\n";
        report::runGnuplot(body, dir + (travel ? "/elimination.fig6.png" : "/elimination.fig7.png"));
    }
}

/** The experiment's tables, ours beside the paper's where the run is the paper's case. */
std::string eliminationTables(const EliminationFile& file, const EliminationTimes& times) {
    const size_t starts = file.columns.front().travel.size();
    std::vector<int> paperColumn;  // ours -> the paper's, -1 if it has none
    for (const auto& c : file.columns) {
        int match = -1;
        for (int k = 0; k < paper::kColumns; ++k)
            if (c.name == paper::kColumnNames[k]) match = k;
        paperColumn.push_back(starts == (size_t)paper::kStarts ? match : -1);
    }
    const auto mean = [](const std::vector<double>& v) {
        double s = 0;
        for (double x : v) s += x;
        return v.empty() ? 0.0 : s / double(v.size());
    };
    const auto table = [&](bool travel) {
        std::string out = "<table><tr><th>start</th>";
        for (size_t c = 0; c < file.columns.size(); ++c)
            out += "<th>" + report::html(file.columns[c].name) +
                   (travel ? " d (m)" : " t (ms)") + "</th>" +
                   (paperColumn[c] >= 0 ? std::string(travel ? "<th>paper d</th>" : "<th>paper t (s)</th>")
                                        : std::string());
        out += "</tr>\n";
        for (size_t i = 0; i < starts; ++i) {
            out += "<tr><td>" + std::to_string(i + 1) + (i == file.trueStart ? " (run)" : "") +
                   "</td>";
            for (size_t c = 0; c < file.columns.size(); ++c) {
                const auto& col = file.columns[c];
                const std::string ok = col.survivors[i] == 1 ? "" : " (not localized)";
                out += travel ? mrpt::format("<td>%.2f%s</td>", col.travel[i], ok.c_str())
                              : mrpt::format("<td>%.2f</td>", 1e3 * times.seconds.at(c).at(i));
                if (paperColumn[c] >= 0)
                    out += mrpt::format("<td>%.1f</td>",
                                        (travel ? paper::kTravel : paper::kSeconds)[i][paperColumn[c]]);
            }
            out += "</tr>\n";
        }
        // Averages, and each average over the first column's (the paper's d_i/d_1, t_i/t_1).
        std::string avg = "<tr><td>mean</td>", ratio = "<tr><td>ratio to column 1</td>";
        const double first = travel ? mean(file.columns[0].travel) : mean(times.seconds.at(0));
        double paperFirst = 0;
        if (paperColumn[0] >= 0)
            for (int i = 0; i < paper::kStarts; ++i)
                paperFirst += (travel ? paper::kTravel : paper::kSeconds)[i][paperColumn[0]] / 12;
        for (size_t c = 0; c < file.columns.size(); ++c) {
            const double m = travel ? mean(file.columns[c].travel) : mean(times.seconds.at(c));
            avg += mrpt::format("<td>%.2f</td>", travel ? m : 1e3 * m);
            ratio += mrpt::format("<td>%.3f</td>", first > 0 ? m / first : 0.0);
            if (paperColumn[c] >= 0) {
                double pm = 0;
                for (int i = 0; i < paper::kStarts; ++i)
                    pm += (travel ? paper::kTravel : paper::kSeconds)[i][paperColumn[c]] / 12;
                avg += mrpt::format("<td>%.2f</td>", pm);
                ratio += paperFirst > 0 ? mrpt::format("<td>%.3f</td>", pm / paperFirst)
                                        : std::string("<td></td>");
            }
        }
        std::string toBound;
        if (travel && std::isfinite(file.bound) && file.bound > 0) {
            toBound = "<tr><td>mean d / bound</td>";
            for (size_t c = 0; c < file.columns.size(); ++c)
                toBound += mrpt::format("<td>%.2f</td>", mean(file.columns[c].travel) / file.bound) +
                           (paperColumn[c] >= 0 ? "<td></td>" : "");
            toBound += "</tr>\n";
        }
        return out + avg + "</tr>\n" + ratio + "</tr>\n" + toBound + "</table>\n";
    };
    return "<h3>Elimination: path length per start (seed 002 Table 1)</h3>\n"
           "<p>Every hypothesis in turn the truth; closed loop with exact views; d is the "
           "robot's travel in metres. The paper's map units are not stated: compare the "
           "ratios. Bound: the first-separation distance, " +
           (std::isfinite(file.bound) ? mrpt::format("%.2f m", file.bound) : std::string("none found")) +
           ", the shortest travel to any point where the hypotheses' views differ (see "
           "doc/polymap.md); no strategy travels less.</p>\n" +
           table(true) +
           "<h3>Elimination: run time per start (seed 002 Table 2)</h3>\n"
           "<p>One whole localization, this machine, one core, milliseconds; the paper's in "
           "seconds (Visual C++ 2010).</p>\n" +
           table(false);
}

std::string polymapSection(const report::RunView& run) {
    std::string out =
        "<h2>Polygon map: hypotheses</h2>\n<p>The map P; the sensed visibility polygon V at "
        "the true start; V placed at each hypothesis; the hypotheses (seed 002, hypothesis "
        "generation). Colours are in the picture's legend.</p>\n";
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
            view.overlay = elimination->overlay;
            if (!elimination->columns.empty())
                view.candidates = {elimination->columns.front().name,
                                   elimination->columns.front().candidates};
        }
        const std::string png = "polymap." + robot + ".png";
        renderPolygonView(view, run.dir + "/" + png);
        out += "<h3>Robot " + report::html(robot) + ": " + std::to_string(file.hypotheses.size()) +
               " hypotheses</h3>\n<img src='" + png + "' alt='map, V and hypotheses'>\n";
        const auto robots = run.metrics.value("polymap", nlohmann::json::object())
                                .value("robots", nlohmann::json::object());
        if (robots.contains(robot) && robots[robot].contains("elimination")) {
            const auto& e = robots[robot]["elimination"];
            out += mrpt::format(
                "<p>The robot eliminated as it drove (<code>drive = %s</code>): %d probe(s), "
                "%.2f m of travel, %s.</p>\n",
                e.value("strategy", "?").c_str(), e.value("probes", 0), e.value("travel_m", 0.0),
                e.value("localized", false)
                    ? "localized: one hypothesis left, the errors above are its estimates"
                    : mrpt::format("not localized: %d hypotheses left", e.value("left", 0)).c_str());
        }
        if (!view.routes.empty()) {  // a close-up of the routes from the true start
            TPoint2D lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
            for (const auto& route : view.routes)
                for (const auto& p : route.path)
                    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)},
                    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
            // Routes on the left, room on the right for the legend (top right).
            const double pad = 0.25 * std::max({hi.x - lo.x, hi.y - lo.y, 4.0});
            const double wide = std::max(hi.x - lo.x + 2 * pad, 2 * (hi.y - lo.y + 2 * pad));
            view.box = std::make_pair(lo - TPoint2D{pad, pad},
                                      TPoint2D{lo.x - pad + 1.8 * wide, hi.y + pad});
            const std::string zoom = "polymap." + robot + ".routes.png";
            renderPolygonView(view, run.dir + "/" + zoom, 1200, 600);
            out += "<p>Close-up: the overlay region OI of all hypotheses at the true start, the "
                   "first algorithm's candidates for its first probe, and each algorithm's route "
                   "from the run's true start (seed 002 figs. 2-5), its probes as dots.</p>\n"
                   "<img src='" + zoom +
                   "' alt='elimination routes from the true start'>\n";
        }
        out +=
            "<table><tr><th>#</th><th>x (m)</th><th>y (m)</th><th>translation (m)</th>"
            "<th>mismatch (m)</th><th>distance to truth (m)</th></tr>\n";
        for (size_t i = 0; i < file.hypotheses.size(); ++i) {
            const auto& h = file.hypotheses[i];
            const std::string d =
                view.truth ? mrpt::format("%.3f", (h.point - *view.truth).norm()) : "none";
            out += mrpt::format(
                "<tr><td>%zu</td><td>%.3f</td><td>%.3f</td><td>%.3f %.3f</td>"
                "<td>%.4f</td><td>%s</td></tr>\n",
                i + 1, h.point.x, h.point.y, h.translation.x, h.translation.y, h.mismatch,
                d.c_str());
        }
        out += "</table>\n";
        if (elimination && !elimination->columns.empty())
            out += eliminationTables(*elimination, EliminationTimes::read(run.dir));
        if (std::filesystem::exists(EliminationSweepFile::path(run.dir))) {
            const auto sweep = EliminationSweepFile::read(run.dir);
            plotSweep(sweep, run.dir);
            out += "<h3>Elimination against map size (seed 002 Figs. 6-7)</h3>\n<p>Steps maps "
                   "of the run's shape, n vertices, their sites the hypotheses; mean over up "
                   "to " + std::to_string(sweep.rows.empty() ? 0 : sweep.rows.front().starts) +
                   " starts per map, evenly spread.</p>\n<img src='elimination.fig6.png' "
                   "alt='mean path against n'>\n<img src='elimination.fig7.png' alt='mean "
                   "time against n'>\n<table><tr><th>n</th><th>k</th><th>algorithm</th><th>mean "
                   "d (m)</th><th>mean t (ms)</th><th>not localized</th></tr>\n";
            for (const auto& r : sweep.rows)
                out += mrpt::format("<tr><td>%d</td><td>%d</td><td>%s</td><td>%.2f</td><td>%.2f</td>"
                                    "<td>%d</td></tr>\n",
                                    r.n, r.k, report::html(r.column).c_str(), r.meanTravel,
                                    1e3 * r.meanSeconds, r.notLocalized);
            out += "</table>\n";
        }
    }
    return out;
}

}  // namespace

void registerMethod(method::Registry& registry) {
    method::Method m;
    m.name = "polymap";
    m.sections = {"polymap"};
    m.localizer = [] { return std::make_unique<PolymapLocalizer>(); };
    m.scenario = loadScenario;
    m.experiment = eliminationExperiment;
    m.report.html = polymapSection;  // its own picture: no world top view
    registry.add(std::move(m));
}

}  // namespace mrloc::polymap
