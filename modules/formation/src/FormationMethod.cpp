#include <mrloc/common/Error.h>
#include <mrloc/common/IniSection.h>
#include <mrloc/formation/FormationExperiment.h>
#include <mrloc/formation/FormationFiles.h>
#include <mrloc/formation/FormationLocalizer.h>
#include <mrloc/formation/FormationMethod.h>
#include <mrloc/formation/FormationPayload.h>
#include <mrloc/formation/PaperValues.h>
#include <mrloc/report/Plots.h>
#include <mrloc/sim/World.h>
#include <mrpt/core/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

namespace mrloc::formation {

namespace {

/** Robots f1 .. fN on the strip facing east, and dr at the route's start, from [formation];
 *  [scenario] robots must not name any. */
method::Scenario loadScenario(const mrpt::config::CConfigFileBase& ini,
                              const FormationLocalizer& localizer) {
    const FormationConfig& c = localizer.config();
    method::Scenario s;
    s.config = sim::ScenarioConfig::loadWithoutRobots(ini);
    std::vector<sim::RobotOptions> robots;
    const auto names = formationRobotNames(c.robots);
    const auto strip = c.worldStrip();
    const auto route = c.worldRoute();
    for (size_t i = 0; i <= names.size(); ++i) {
        sim::RobotOptions r;
        r.name = i < names.size() ? names[i] : kDeadReckoningRobot;
        const TPoint2D p = i < names.size() ? strip[i] : route.front();
        r.start = mrpt::poses::CPose2D(p.x, p.y, 0);  // seed 003 sec. 5: all face east
        r.speed = c.speed();
        r.maxTurnRate = c.maxTurnRate;
        r.odometryRate = 10;
        r.startInSection = false;
        robots.push_back(r);
    }
    for (const auto& p : route)
        if (!s.config.world.contains({p.x, p.y, 0.1}, c.formation.side))
            throw Error(common::configOrigin(ini) +
                        mrpt::format(": [formation] the route point (%g %g) (world frame: "
                                     "origin + waypoint) is not %g m inside [world]'s room",
                                     p.x, p.y, c.formation.side));
    s.config.addGeneratedRobots(ini, robots);
    s.payload = std::make_unique<FormationPayload>(c, s.config.scenario.dt);
    return s;
}

/** A route's name for a picture: "many_turns" -> "many turns". */
std::string routeTitle(std::string name) {
    std::replace(name.begin(), name.end(), '_', ' ');
    return name;
}

std::string mm(double metres) { return mrpt::format("%.1f", 1e3 * metres); }

/** The run's picture (seed 003 figs. 12-13): the route, the formation's vertices (believed
 *  and true), the dead-reckoning robot's estimate and truth, the obstacles found. */
report::Html runPicture(const report::RunView& run, const FormationRunFile& f) {
    std::vector<std::pair<double, double>> route, believed, truth, obstacles, drEst, drTrue, start;
    for (const auto& p : f.route) route.emplace_back(p.x, p.y);
    for (const auto& p : f.start) start.emplace_back(p.x, p.y);
    for (const auto& m : f.moves) {
        believed.emplace_back(m.believed.x, m.believed.y);
        if (std::isfinite(m.truth.x)) truth.emplace_back(m.truth.x, m.truth.y);
    }
    for (const auto& o : f.obstacles) obstacles.emplace_back(o.centre.x, o.centre.y);
    if (const auto e = run.estimates.find(kDeadReckoningRobot); e != run.estimates.end())
        for (const auto& p : e->second) drEst.emplace_back(p.pose.x(), p.pose.y());
    if (const auto t = run.truth.find(kDeadReckoningRobot); t != run.truth.end())
        for (const auto& p : t->second) drTrue.emplace_back(p.pose.x(), p.pose.y());
    std::string body = report::dataBlock("route", route) + report::dataBlock("believed", believed) +
                       report::dataBlock("truth", truth) + report::dataBlock("obst", obstacles) +
                       report::dataBlock("drEst", drEst) + report::dataBlock("drTrue", drTrue) +
                       report::dataBlock("start", start);
    body +=
        "set xlabel 'x (m)'\nset ylabel 'y (m)'\nset size ratio -1\n"
        "set key outside below center horizontal\n"
        "plot $route using 1:2 with linespoints lw 2 lc rgb pal_green pt 7 ps 0.6 title 'route', "
        "$believed using 1:2 with points pt 1 ps 0.8 lc rgb 'black' title 'vertices (believed)', "
        "$truth using 1:2 with points pt 6 ps 0.6 lc rgb pal_blue title 'vertices (true)', "
        "$start using 1:2 with points pt 5 ps 0.8 lc rgb 'black' title 'strip (start)', "
        "$drTrue using 1:2 with lines lw 1 lc rgb pal_grey title 'dead-reckoning robot (true)', "
        "$drEst using 1:2 with lines lw 2 lc rgb pal_vermillion title 'dead reckoning (estimate)'";
    if (!obstacles.empty())
        body +=
            ", $obst using 1:2 with points pt 7 ps 0.3 lc rgb pal_orange title 'obstacles found'";
    body += "\n";
    // the world's obstacles (effective.ini [world]) as boxes under everything else
    if (run.effective && run.effective->sectionExists("world")) {
        sim::WorldOptions world;
        world.loadFromConfigFile(*run.effective, "world");
        std::string boxes;
        int id = 1;
        for (const auto& b : world.obstacles)
            boxes += mrpt::format(
                "set object %d rect from %.17g,%.17g to %.17g,%.17g back fc rgb pal_lightgrey "
                "fs solid 0.6 noborder\n",
                id++, b.min.x, b.min.y, b.max.x, b.max.y);
        body = boxes + body;
    }
    // a picture as tall as the route's extent asks for (the plot about 900 px wide, the
    // axes and the legend below it about 180 px)
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    for (const auto* set : {&route, &believed, &start, &drEst})
        for (const auto& [x, y] : *set)
            x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    const double aspect = (y1 - y0 + 2) / std::max(x1 - x0 + 2, 1.0);
    const int height = std::clamp(int(std::lround(900 * aspect)) + 180, 360, 1000);
    report::runGnuplot(body, run.dir + "/formation.run.png", mrpt::format("1000,%d", height));
    return report::Figure{"formation.run.png",
                          "the formation's believed vertices (+) should sit on the true ones (o); "
                          "dead reckoning drifts from its truth"}
        .html();
}

/** Seed 003 fig. 14 for one route: the mean error against time, both speeds. */
report::Html figureFourteen(const std::string& dir, const FormationExperimentFile& e,
                            const std::string& route) {
    std::set<double> speeds;
    for (const auto& c : e.curves)
        if (c.route == route) speeds.insert(c.wheelSpeed);
    std::string body, plot;
    int k = 0;
    const char* colours[] = {"pal_vermillion", "pal_blue", "pal_purple", "pal_black"};
    for (auto it = speeds.rbegin(); it != speeds.rend(); ++it, ++k) {
        std::vector<std::pair<double, double>> dr, f;
        for (const auto& c : e.curves)
            if (c.route == route && c.wheelSpeed == *it)
                (c.kind == "dr" ? dr : f).emplace_back(c.time, c.error);
        const std::string n = std::to_string(k), colour = colours[k % 4];
        body += report::dataBlock("dr" + n, dr) + report::dataBlock("f" + n, f);
        plot += std::string(plot.empty() ? "plot " : ", ") + "$dr" + n +
                " using 1:2 with lines lw 2 dt " + std::to_string(k + 1) + " lc rgb " + colour +
                " title 'dead reckoning, " + mrpt::format("%g", *it) + " rad/s', $f" + n +
                " using 1:2 with points pt " + std::to_string(7 + 2 * k) + " ps 0.5 lc rgb " +
                colour + " title 'formation, " + mrpt::format("%g", *it) + " rad/s'";
    }
    const std::string png = "formation.fig14." + route + ".png";
    report::runGnuplot(
        body +
            "set xlabel 'time (s)'\nset ylabel 'mean position error (m)'\n"
            "set key outside right top\nset yrange [0:*]\nset offsets 0, 0, graph 0.1, 0\n" +
            plot + "\n",
        dir + "/" + png);
    return report::Figure{png, "error against time, " + routeTitle(route) +
                                   ": the formation's should stay below dead reckoning's"}
        .html();
}

/** A table of per-step vertex errors (seed 003 fig. 11's measure), in mm. */
report::Table stepErrorTable() {
    return report::Table({"source", "steps", "lateral mean (mm)", "lateral sd (mm)",
                          "longitudinal mean (mm)", "longitudinal sd (mm)"});
}

void addStepErrors(report::Table& t, const std::string& source, size_t steps, double lateralMean,
                   double lateralSd, double longitudinalMean, double longitudinalSd) {
    t.row({source, std::to_string(steps), mm(lateralMean), mm(lateralSd), mm(longitudinalMean),
           mm(longitudinalSd)});
}

report::Html experimentSection(const std::string& dir) {
    using report::heading, report::paragraph;
    const auto e = FormationExperimentFile::read(dir);
    report::Html out =
        heading(3, "Paper 003 Table 1: error at the destination") +
        paragraph(
            "Mean over the runs, in the error-model mode. The formation's error is the last "
            "moving robot's, against the vertex that perfect triangles give; dead reckoning's "
            "is its estimate's at the destination. The paper's table was lost in extraction; "
            "its text: dead reckoning's error \"increased significantly\" (about twice, fig. "
            "14) when the wheel speed halved, the formation's \"did not change "
            "meaningfully\".");
    report::Table table({"route", "wheel speed (rad/s)", "runs", "moves", "formation (m)",
                         "dead reckoning (m)", "time, formation (s)", "time, dead reckoning (s)"});
    for (const auto& r : e.table)
        table.row({r.route, mrpt::format("%g", r.wheelSpeed), std::to_string(r.runs),
                   std::to_string(r.moves), mrpt::format("%.3f", r.formation),
                   mrpt::format("%.3f", r.deadReckoning), mrpt::format("%.0f", r.formationTime),
                   mrpt::format("%.0f", r.deadReckoningTime)});
    out += table.html();
    if (!e.pixel.empty()) {
        out += heading(3, "Table 1 from pixels") +
               paragraph(
                   "Each move steered by the moving robot's cameras alone: frames rendered, seen "
                   "through the camera model and searched by AprilTag 3 (pixel_runs marches per "
                   "route and speed, four robots unless [formation] robots says otherwise), each "
                   "beside a dead-reckoned drive. Rotation: the formation's heading error at the "
                   "end, which no rule that sees only the formation can observe "
                   "(doc/formation.md).");
        report::Table pixel({"route", "wheel speed (rad/s)", "runs", "arrived",
                             "formation mean (m)", "sd (m)", "worst (m)", "dead reckoning (m)",
                             "lost moves", "frames", "rotation (deg)"});
        for (const auto& r : e.pixel)
            pixel.row({r.route, mrpt::format("%g", r.wheelSpeed), std::to_string(r.runs),
                       std::to_string(r.arrived), mrpt::format("%.3f", r.formation),
                       mrpt::format("%.3f", r.formationSd), mrpt::format("%.3f", r.formationMax),
                       mrpt::format("%.3f", r.deadReckoning), mrpt::format("%.2f", r.lostMoves),
                       mrpt::format("%.0f", r.frames),
                       mrpt::format("%.2f", r.rotation * 180 / M_PI)});
        out += pixel.html();
    }
    // the speed ratios, the paper's finding
    for (const auto& a : e.table)
        for (const auto& b : e.table)
            if (a.route == b.route && b.wheelSpeed < a.wheelSpeed)
                out += paragraph(
                    a.route +
                    mrpt::format(", %g rad/s against %g rad/s: dead reckoning's error x %.2f (the "
                                 "paper: about x 2), the formation's x %.2f (the paper: "
                                 "unchanged).",
                                 b.wheelSpeed, a.wheelSpeed, b.deadReckoning / a.deadReckoning,
                                 b.formation / a.formation));
    std::set<std::string> routes;
    for (const auto& r : e.table) routes.insert(r.route);
    out += heading(3, "Paper 003 fig. 14: error against time") +
           paragraph(
               "Dead reckoning's mean error grows with time; the formation's is known only when "
               "a triangle is built (dots), and depends on the number of triangles, not on the "
               "speed.");
    for (const auto& r : routes) out += figureFourteen(dir, e, r);
    if (!e.robots.empty() && !e.table.empty()) {
        std::vector<std::pair<double, double>> xy;
        for (const auto& r : e.robots) xy.emplace_back(double(r.robots), r.error);
        report::runGnuplot(report::dataBlock("n", xy) +
                               "set xlabel 'number of robots N'\nset ylabel 'mean error at the "
                               "destination (m)'\nset yrange [0:*]\nset xtics 1\nset key outside "
                               "below center\nplot $n using 1:2 with linespoints lw 2 pt 7 lc rgb "
                               "pal_blue title " +
                               report::gnuplotString("formation, " +
                                                     routeTitle(e.table.front().route) + " route") +
                               " noenhanced\n",
                           dir + "/formation.fig15.png", "800,450");
        std::vector<report::Html> ns, errors;
        for (const auto& r : e.robots) {
            ns.push_back(std::to_string(r.robots));
            errors.push_back(mrpt::format("%.3f", r.error));
        }
        out += heading(3, "Paper 003 fig. 15: error against the number of robots") +
               paragraph(
                   "The paper: \"the localization error remains consistent despite an increase "
                   "in the number of robots\".") +
               report::Figure{"formation.fig15.png",
                              "error against the number of robots: paper 003 says it stays level"}
                   .html() +
               report::Table().headedRow("N", ns).headedRow("error (m)", errors).html();
    }
    out +=
        heading(3, "Paper 003 fig. 11: per-step vertex errors") +
        paragraph(
            "Mean absolute error and standard deviation along the new triangle's base "
            "(lateral) and across it (longitudinal). " +
            report::emphasis("model") + ": the error model's draws, which the marches above use; " +
            report::emphasis("camera") +
            ": Algorithm 1 from rendered frames (AprilTag 3, the pixel mode's camera and camera "
            "model), from a grid of starts around the vertex; " +
            report::emphasis("pixel_march") + ": every step of Table 1's pixel marches.");
    auto steps = stepErrorTable();
    for (const auto& s : e.steps)
        addStepErrors(steps, s.source, s.count, s.lateralMean, s.lateralSd, s.longitudinalMean,
                      s.longitudinalSd);
    return out + steps.html();
}

report::Html formationSection(const report::RunView& run) {
    report::Html out = report::heading(2, "Formation (paper 003)");
    const auto f = FormationRunFile::read(run.dir);
    const auto m = run.metrics.value("formation", nlohmann::json::object());
    const double last = f.moves.empty() ? NAN : f.moves.back().error();
    const std::string state = m.contains("state") && m["state"].is_string()
                                  ? m["state"].get<std::string>()
                                  : std::string("?");
    const bool arrived = state == "arrived";
    out += report::paragraph(mrpt::format(
        "%zu moves; the team %s. The last moving robot's error %s: %s m "
        "(paper 003 Table 1's measure); the dead-reckoning robot's: %s m.",
        f.moves.size(), arrived ? "reached the destination" : ("ended " + state).c_str(),
        arrived ? "at the destination" : "at its last move (the destination was never reached)",
        std::isfinite(last) ? mrpt::format("%.3f", last).c_str() : "none",
        std::isfinite(f.deadReckoningFinalError)
            ? mrpt::format("%.3f", f.deadReckoningFinalError).c_str()
            : "none"));
    out += runPicture(run, f);
    // the run's own per-step errors (seed 003 fig. 11's measure), beside the paper's
    std::vector<double> lat, lon;
    for (const auto& mv : f.moves)
        if (std::isfinite(mv.lateral)) lat.push_back(mv.lateral), lon.push_back(mv.longitudinal);
    if (!lat.empty()) {
        const auto [lm, ls] = absMoments(lat);
        const auto [om, os] = absMoments(lon);
        const std::string mode =
            run.effective && run.effective->read_string("formation", "mode", "") == "pixel"
                ? "this run's moves, steered by the cameras (pixel mode)"
                : "this run's moves (error-model mode)";
        auto steps = stepErrorTable();
        addStepErrors(steps,
                      "paper 003 fig. 11 (" + std::to_string(paper::kFig11Runs) + " lab runs)",
                      paper::kFig11Runs, paper::kLateralMean, paper::kLateralSd,
                      paper::kLongitudinalMean, paper::kLongitudinalSd);
        addStepErrors(steps, mode, lat.size(), lm, ls, om, os);
        out += report::paragraph(
                   "Per-step errors: each move's true end against the true anchor reflected "
                   "across the true base (a perfect triangle on the real beacons), along the "
                   "base (lateral) and across it (longitudinal); mean absolute value and "
                   "standard deviation.") +
               steps.html();
    }
    if (std::filesystem::exists(FormationExperimentFile::path(run.dir)))
        out += experimentSection(run.dir);
    return out;
}

/** Where the formation ends against the destination, beside dead reckoning's (seed 003's
 *  claim: the formation far better as travel grows); a march that stopped short says so. */
common::Headline formationHeadline(const method::HeadlineOf<FormationLocalizer>& in) {
    common::Headline h;
    const auto moves = common::numberAt(in.metrics, "formation/moves");
    const std::string state =
        in.metrics.value("formation", nlohmann::json::object()).value("state", std::string("?"));
    h.reached = state == "arrived";
    // doc/formation.md, "The paper's mechanism: as stated, as shipped"
    const auto& config = in.localizer.config();
    if (config.mode == FormationConfig::Mode::Pixel)
        h.mechanism =
            config.lateral == AlgorithmOneOptions::Lateral::Midpoint
                ? "Algorithm 1 from pixels with mrloc's lateral rule (algorithm_one = midpoint: "
                  "the anchor in line with the base's midpoint; the paper's is "
                  "algorithm_one = paper)"
                : "Algorithm 1 from pixels with paper 003's lateral rule (algorithm_one = paper)";
    else
        h.mechanism = std::string(
                          "the error model: paper 003's mean errors read as mean "
                          "absolute errors (gamma, random sign), carried over by ") +
                      (config.carry == MarchOptions::Carry::Base         ? "the base's offset"
                       : config.carry == MarchOptions::Carry::Reflection ? "the reflection"
                                                                         : "Algorithm 1") +
                      " (carry; mrloc's reading)";
    h.status = h.reached ? "at the destination"
                         : mrpt::format(
                               "ended before the destination: after move %.0f, "
                               "state '%s'",
                               moves.value_or(0), state.c_str());
    // pixel mode: a move whose beacons the cameras lost was finished blind; the march is
    // then not what the method did, and the headline says so
    const auto lost = common::numberAt(in.metrics, "formation/camera_lost_moves");
    if (lost && *lost > 0)
        h.status += mrpt::format("; %.0f move%s lost the beacons and went on blind", *lost,
                                 *lost == 1 ? "" : "s");
    std::string differs;
    const auto& c = in.localizer.config();
    if (!in.scenario)
        differs = "a log recorded elsewhere";
    else if (c.mode == FormationConfig::Mode::Pixel)
        differs = c.lens.ideal() ? "rendered frames of an ideal camera; the paper's are the lab "
                                   "robots' cameras"
                                 : "rendered frames through a camera model; the paper's are "
                                   "the lab robots' cameras";
    else if (c.routeName == "custom")
        differs = "a route of this INI's; the paper's are its figs. 12-13";
    const std::string claim =
        "below dead reckoning's, the gap growing with travel (paper 003 "
        "Table 1)";
    const auto own = common::numberAt(in.metrics, "formation/final_error_m");
    const auto dr = common::numberAt(in.metrics, "formation/dead_reckoning_final_error_m");
    if (own && dr && *dr < *own)
        // the paper's claim does not hold on this run: said beside the figure, not left to
        // the reader to spot
        differs += mrpt::format(
            "%sdead reckoning ends closer here (%.3f m against %.3f m), "
            "against the paper's claim",
            differs.empty() ? "" : "; ", *dr, *own);
    h.figures.push_back({h.reached ? "error at the destination" : "error at the last move", own,
                         "m", claim, differs, false});
    h.figures.push_back({"dead reckoning", dr, "m", "", "", true});
    // along the march, on the truth's timeline: every robot's estimate at every truth stamp
    for (auto f : common::trajectoryFigures(in.metrics)) {
        f.name = "along the march: " + f.name;
        h.figures.push_back(std::move(f));
    }
    return h;
}

}  // namespace

void registerMethod(method::Registry& registry) {
    method::MethodUnit<FormationLocalizer> m;
    m.name = "formation";
    m.sections = {"formation"};
    m.keys = {FormationConfig::keys().docs()};
    m.reads = {"CObservationComment"};
    m.exampleConfig = "config/formation_many_turns.ini";
    m.headline = formationHeadline;
    m.scenario = loadScenario;
    m.experiment = formationExperiment;  // seed 003 Table 1, figs. 11, 14, 15
    m.trial = formationTrial;            // one run of Table 1 (mrloc trial, mrloc batch)
    m.work = formationWork;
    m.report.subject = "swarm localization by triangle formations (paper 003)";
    m.report.html = formationSection;  // its own picture: no world top view
    registry.add(std::move(m));
}

}  // namespace mrloc::formation
