#include <mrloc/common/RunDirectory.h>
#include <mrloc/common/Trajectory.h>
#include <mrloc/framesync/FramesyncExperiment.h>
#include <mrloc/framesync/FramesyncFiles.h>
#include <mrloc/framesync/FramesyncLocalizer.h>
#include <mrloc/framesync/FramesyncMethod.h>
#include <mrloc/framesync/FramesyncPayload.h>
#include <mrloc/report/Palette.h>
#include <mrloc/report/Plots.h>
#include <mrloc/report/TopView.h>
#include <mrloc/sim/World.h>
#include <mrpt/core/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

namespace mrloc::framesync {

namespace {

/** Robots from [scenario] robots and their [robot.<name>] sections. */
method::Scenario loadScenario(const mrpt::config::CConfigFileBase& ini,
                              const FramesyncLocalizer& localizer) {
    const auto& c = localizer.config();
    method::Scenario s;
    s.config = sim::ScenarioConfig::load(ini);
    s.payload = std::make_unique<FramesyncPayload>(c, s.config.scenario.dt);
    return s;
}

std::string colourOf(size_t i) { return "'" + report::palette::hex(report::robotColour(i)) + "'"; }

/** The robot's colour 60 % transparent (gnuplot's #AARRGGBB): the truth's wide band. */
std::string paleOf(size_t i) {
    return "'#99" + report::palette::hex(report::robotColour(i)).substr(1) + "'";
}

std::string cm(double metres) {
    return std::isfinite(metres) ? mrpt::format("%.1f", 100 * metres) : std::string("none");
}

/** The world's boxes and pillars (effective.ini [world]) under a picture, and its extent. */
std::string worldObjects(const report::RunView& run) {
    if (!run.effective || !run.effective->sectionExists("world")) return "";
    sim::WorldOptions world;
    world.loadFromConfigFile(*run.effective, "world");
    std::string out = mrpt::format(
        "set object 1 rect from 0,0 to %.17g,%.17g back fs empty border lc rgb pal_grey\n",
        world.sizeX, world.sizeY);
    int id = 2;
    for (const auto& b : world.obstacles)
        out += mrpt::format(
            "set object %d rect from %.17g,%.17g to %.17g,%.17g back fc rgb pal_lightgrey "
            "fs solid 0.7 noborder\n",
            id++, b.min.x, b.min.y, b.max.x, b.max.y);
    for (const auto& p : world.pillars)
        out += mrpt::format(
            "set object %d circle at %.17g,%.17g size %.17g back fc rgb pal_black fs solid 0.6 "
            "noborder\n",
            id++, p.x, p.y, p.radius);
    return out;
}

/** Seed 004 fig. 7: the robots' estimates without (top) and with (bottom) the shared
 *  frame, the truth, the walls found and the redefinitions. */
report::Html runPicture(const report::RunView& run, const FramesyncRunFile& f) {
    std::vector<std::string> robots;
    for (const auto& [name, traj] : run.estimates) robots.push_back(name);
    std::string data, odometryPlot, sharedPlot;
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    auto extend = [&](double x, double y) {
        x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    };
    for (size_t i = 0; i < robots.size(); ++i) {
        const std::string& r = robots[i];
        const std::string n = std::to_string(i), colour = colourOf(i), pale = paleOf(i);
        std::vector<std::pair<double, double>> est, odo, gt, walls;
        for (const auto& p : run.estimates.at(r)) est.emplace_back(p.pose.x(), p.pose.y());
        if (std::filesystem::exists(common::run_dir::odometry(run.dir, r)))
            for (const auto& p : common::loadTum(common::run_dir::odometry(run.dir, r)))
                odo.emplace_back(p.pose.x(), p.pose.y());
        if (const auto t = run.truth.find(r); t != run.truth.end())
            for (const auto& p : t->second) gt.emplace_back(p.pose.x(), p.pose.y());
        for (const auto* set : {&est, &odo, &gt})
            for (const auto& [x, y] : *set) extend(x, y);
        data += report::dataBlock("est" + n, est) + report::dataBlock("odo" + n, odo) +
                report::dataBlock("gt" + n, gt);
        std::string segments;
        for (const auto& w : f.walls)
            if (w.robot == r) {
                segments += mrpt::format("%.17g %.17g %.17g %.17g\n", w.wall.a.x, w.wall.a.y,
                                         w.wall.b.x - w.wall.a.x, w.wall.b.y - w.wall.a.y);
                // the axes hold every wall drawn, not only the paths
                extend(w.wall.a.x, w.wall.a.y), extend(w.wall.b.x, w.wall.b.y);
            }
        data += "$walls" + n + " << EOD\n" + segments + "EOD\n";
        const std::string truth = gt.empty()
                                      ? ""
                                      : "$gt" + n + " using 1:2 with lines lw 7 lc rgb " + pale +
                                            " title " + report::gnuplotString(r + " (true)") + ", ";
        odometryPlot += std::string(odometryPlot.empty() ? "plot " : ", ") + truth + "$odo" + n +
                        " using 1:2 with lines lw 2 dt 2 lc rgb " + colour + " title " +
                        report::gnuplotString(r + " (odometry)");
        sharedPlot += std::string(sharedPlot.empty() ? "plot " : ", ") + truth + "$est" + n +
                      " using 1:2 with lines lw 2 lc rgb " + colour + " title " +
                      report::gnuplotString(r + " (shared frame)");
        if (!segments.empty())
            sharedPlot += ", $walls" + n + " using 1:2:3:4 with vectors nohead lw 4 lc rgb " +
                          colour + " title " + report::gnuplotString(r + "'s walls");
    }
    const double margin = 1;
    const std::string ranges = mrpt::format("set xrange [%.17g:%.17g]\nset yrange [%.17g:%.17g]\n",
                                            x0 - margin, x1 + margin, y0 - margin, y1 + margin);
    const std::string body =
        data + worldObjects(run) + ranges +
        "set xlabel 'x (m)'\nset ylabel 'y (m)'\nset size ratio -1\nset key outside right top "
        "noenhanced\nset multiplot layout 2,1\nset title 'independent: each robot on its own "
        "odometry'\n" +
        odometryPlot + "\nset title 'with the shared frame (paper 004)'\n" + sharedPlot +
        "\nunset multiplot\n";
    report::runGnuplot(body, run.dir + "/framesync.run.png", "1100,900");
    return report::Figure{"framesync.run.png",
                          "each robot's own odometry (dashed) drifts from its truth (wide band); "
                          "in the shared frame the paths stay on it"}
        .html();
}

double percentile(std::vector<double> xs, double q) {
    if (xs.empty()) return NAN;
    std::sort(xs.begin(), xs.end());
    return xs[std::min(xs.size() - 1, size_t(std::floor(q * double(xs.size() - 1) + 0.5)))];
}

report::Html experimentSection(const std::string& dir) {
    using report::heading, report::paragraph;
    const auto e = FramesyncExperimentFile::read(dir);
    std::vector<double> shared, odometry;
    for (const auto& r : e.runs)
        if (r.kind == "paper" && std::isfinite(r.sharedError))
            shared.push_back(r.sharedError), odometry.push_back(r.odometryError);
    report::Html out;
    if (!shared.empty()) {
        report::Table table({"frames", "mean (cm)", "median (cm)", "90th percentile (cm)",
                             "max (cm)", "runs under 10 cm", "paper 004 (one run)"});
        auto row = [&](const char* name, const std::vector<double>& xs, const char* paper) {
            double mean = 0;
            size_t under = 0;
            for (const double x : xs) mean += x, under += x < 0.10;
            mean /= double(xs.size());
            table.row({name, cm(mean), cm(percentile(xs, 0.5)), cm(percentile(xs, 0.9)),
                       cm(percentile(xs, 1)),
                       mrpt::format("%.0f %%", 100.0 * double(under) / double(xs.size())), paper});
        };
        row("each robot's own odometry", odometry, "about 30 cm");
        row("shared (paper 004)", shared, "under 10 cm");
        out += heading(3, mrpt::format("Paper 004 sec. 5.2 over %zu seeds", shared.size())) +
               paragraph(
                   "At the end of each run, where each robot is as another sees it (its "
                   "position in the other's frame and heading), estimated against true, mean "
                   "over the pairs of robots. The paper's two robots end at one goal point: for "
                   "them this is the distance between their estimates of it. The INI's "
                   "scenario, simulated again with other seeds.") +
               table.html();
        std::vector<std::pair<double, double>> cs, co;
        auto sortedShared = shared, sortedOdometry = odometry;
        std::sort(sortedShared.begin(), sortedShared.end());
        std::sort(sortedOdometry.begin(), sortedOdometry.end());
        for (size_t i = 0; i < sortedShared.size(); ++i) {
            const double q = double(i + 1) / double(sortedShared.size());
            cs.emplace_back(100 * sortedShared[i], q), co.emplace_back(100 * sortedOdometry[i], q);
        }
        report::runGnuplot(
            report::dataBlock("s", cs) + report::dataBlock("o", co) +
                "set xlabel 'distance between the estimates at the end, against the truth (cm)'"
                "\nset ylabel 'fraction of runs'\nset yrange [0:1.05]\nset xrange [0:*]\n"
                "set key outside right top\nset arrow from 10, graph 0 to 10, graph 1 nohead dt 2 "
                "lc rgb pal_green\nset arrow from 30, graph 0 to 30, graph 1 nohead dt 2 lc "
                "rgb pal_vermillion\nset label 'paper 004: < 10 cm' at 10.5, graph 0.08 tc rgb "
                "pal_green\nset label 'paper 004: about 30 cm' at 30.5, graph 0.16 tc rgb "
                "pal_vermillion\nplot $o using 1:2 with steps lw 2 lc rgb pal_vermillion title "
                "'own "
                "odometry', $s using 1:2 with steps lw 2 lc rgb pal_blue title 'shared frame'\n",
            dir + "/framesync.seeds.png", "800,450");
        out += report::Figure{"framesync.seeds.png",
                              "the shared frame's end discrepancy over the seeds should lie left "
                              "of own odometry's"}
                   .html();
    }
    // the sweeps: mean over the seeds at each value
    for (const std::string kind : {"noise", "drift"}) {
        std::map<double, std::pair<std::vector<double>, std::vector<double>>> by;
        for (const auto& r : e.runs)
            if (r.kind == kind && std::isfinite(r.sharedError))
                by[r.value].first.push_back(r.sharedError),
                    by[r.value].second.push_back(r.odometryError);
        if (by.empty()) continue;
        const bool noise = kind == "noise";
        std::vector<std::pair<double, double>> s, o;
        report::Table table({noise ? "sonar noise, sd (cm)" : "odometry drift (x the INI's)",
                             "runs", "own odometry, mean (cm)", "shared frame, mean (cm)",
                             "shared, 90th percentile (cm)"});
        for (const auto& [value, xs] : by) {
            double ms = 0, mo = 0;
            for (const double x : xs.first) ms += x;
            for (const double x : xs.second) mo += x;
            ms /= double(xs.first.size()), mo /= double(xs.second.size());
            const double x = noise ? 100 * value : value;
            s.emplace_back(x, 100 * ms), o.emplace_back(x, 100 * mo);
            table.row({mrpt::format("%g", x), std::to_string(xs.first.size()), cm(mo), cm(ms),
                       cm(percentile(xs.first, 0.9))});
        }
        const std::string png = "framesync." + kind + ".png";
        report::runGnuplot(
            report::dataBlock("s", s) + report::dataBlock("o", o) + "set xlabel '" +
                (noise ? "sonar range noise, standard deviation (cm)"
                       : "odometry drift (factor on the INI''s systematic errors)") +
                "'\nset ylabel 'mean distance at the end, against the truth (cm)'\nset yrange "
                "[0:*]\nset offsets graph 0.04, graph 0.04, 0, 0\nset key outside right top\nplot "
                "$o using "
                "1:2 with linespoints lw 2 pt 7 lc rgb "
                "pal_vermillion title 'own odometry', $s using 1:2 with linespoints lw 2 pt 5 lc "
                "rgb "
                "pal_blue title 'shared frame'\n",
            dir + "/" + png, "800,400");
        out +=
            heading(3, noise ? "Against the sonar's range noise" : "Against the odometry's drift") +
            report::Figure{
                png, "as the " + kind + " grows, the shared frame should stay below own odometry"}
                .html() +
            table.html();
    }
    return out;
}

report::Html framesyncSection(const report::RunView& run) {
    report::Html out = report::heading(2, "Shared frame from walls (paper 004)");
    const auto f = FramesyncRunFile::read(run.dir);
    const auto m = run.metrics.value("framesync", nlohmann::json::object());
    const auto [shared, odometry] = meanPairErrors(f.pairs);
    if (!f.pairs.empty())
        out += report::paragraph(
            "At the end, where each robot is as another sees it, estimated against true (for "
            "two robots at one goal, the distance between their estimates of it), mean over "
            "the pairs: " +
            report::bold(cm(shared) + " cm with the shared frame, " + cm(odometry) +
                         " cm with each robot's own odometry") +
            mrpt::format(" (paper 004: under 10 cm and about 30 cm). %zu walls announced, %zu "
                         "redefinitions.",
                         f.walls.size(), f.events.size()));
    else
        out += report::paragraph(mrpt::format(
            "%zu walls announced, %zu redefinitions; no pair of robots with ground truth to "
            "compare.",
            f.walls.size(), f.events.size()));
    out += runPicture(run, f);
    report::Table counts({"robot", "walls", "redefinitions", "ERPs", "pairs with no wall",
                          "groups too short", "groups off the line", "groups not perpendicular"});
    const auto robots = m.value("robots", nlohmann::json::object());
    for (const auto& [name, r] : robots.items()) {
        std::vector<report::Html> cells{name};
        for (const char* key : {"walls", "redefinitions", "erps", "pairs_without_wall",
                                "groups_too_short", "groups_off_line", "groups_not_perpendicular"})
            cells.push_back(report::cellText(r.is_object() ? r.value(key, nlohmann::json())
                                                           : nlohmann::json()));
        counts.row(std::move(cells));
    }
    out += counts.html();
    if (!f.pairs.empty()) {
        report::Table pairs({"robots", "true distance (m)", "error, shared frame (cm)",
                             "error, own odometry (cm)"});
        for (const auto& p : f.pairs)
            pairs.row({p.a + ", " + p.b, mrpt::format("%.2f", p.trueDistance), cm(p.sharedError),
                       cm(p.odometryError)});
        out += pairs.html();
    }
    if (std::filesystem::exists(FramesyncExperimentFile::path(run.dir)))
        out += experimentSection(run.dir);
    return out;
}

/** Seed 004 sec. 5.2's measure: where the robots end, as each sees the other, against the
 *  truth; the shared frame's beside each robot's own odometry (the baseline), in this run
 *  and over the experiment's seeds. */
common::Headline framesyncHeadline(const method::HeadlineOf<FramesyncLocalizer>& in) {
    common::Headline h;
    const auto redefinitions = common::numberAt(in.metrics, "framesync/redefinitions");
    const bool sharing = in.localizer.config().team.sharing;
    // doc/framesync.md, "The paper's mechanism: as stated, as shipped"
    if (sharing) {
        const auto& team = in.localizer.config().team;
        h.mechanism = team.manager.match.general
                          ? "paper 004 sec. 4.3's wall tests, then sec. 3's general transform "
                            "where none passes (matching = general)"
                          : "paper 004 sec. 4.3's wall tests alone (matching = local; sec. 3's "
                            "general transform is matching = general)";
        h.mechanism += team.onRedefinition == TeamOptions::OnRedefinition::Drop
                           ? "; ERPs dropped on a redefinition (sec. 5.1)"
                           : "; ERPs carried into the new frame (on_redefinition = transform, "
                             "mrloc's)";
    }
    h.reached = !sharing || (redefinitions && *redefinitions > 0);
    h.status = !sharing    ? "frames kept apart ([framesync] sharing = false)"
               : h.reached ? "one frame shared"
                           : "no frame shared (no wall matched between robots; see the walls)";
    std::string differs;
    if (!in.scenario)
        differs = "a log recorded elsewhere, not the paper's corridor";
    else if (in.scenario->robots.size() != 2)
        differs =
            mrpt::format("%zu robots; the paper's experiment has 2", in.scenario->robots.size());
    const char* shared = "under 0.10 m (paper 004 sec. 5.2, one run)";
    const char* own = "about 0.30 m (paper 004 sec. 5.2)";
    h.figures.push_back({"end discrepancy, shared frame",
                         common::numberAt(in.metrics, "framesync/end_relative_error_shared_m"), "m",
                         shared, differs, false});
    h.figures.push_back({"own odometry",
                         common::numberAt(in.metrics, "framesync/end_relative_error_odometry_m"),
                         "m", own, differs, true});
    if (std::filesystem::exists(FramesyncExperimentFile::path(in.outDir))) {
        double s = 0, o = 0;
        size_t n = 0;
        for (const auto& r : FramesyncExperimentFile::read(in.outDir).runs)
            if (r.kind == "paper" && std::isfinite(r.sharedError))
                s += r.sharedError, o += r.odometryError, ++n;
        if (n) {
            const std::string over = mrpt::format(" (mean over %zu seeds)", n);
            h.figures.push_back(
                {"shared frame" + over, s / double(n), "m", shared, differs, false});
            h.figures.push_back({"own odometry" + over, o / double(n), "m", own, differs, true});
        }
    }
    // each robot's pose in the shared frame against its truth there, on the truth's timeline
    for (auto f : common::trajectoryFigures(in.metrics)) {
        f.name = "in the shared frame: " + f.name;
        h.figures.push_back(std::move(f));
    }
    return h;
}

}  // namespace

void registerMethod(method::Registry& registry) {
    method::MethodUnit<FramesyncLocalizer> m;
    m.name = "framesync";
    m.sections = {"framesync"};
    m.keys = {FramesyncConfig::keys().docs()};
    m.reads = {"CObservationRange"};
    m.exampleConfig = "config/framesync_corridor.ini";
    m.headline = framesyncHeadline;
    m.scenario = loadScenario;
    m.experiment = framesyncExperiment;  // seed 004 sec. 5.2 over seeds, noises, drifts
    m.trial = framesyncTrial;            // one run of it (mrloc trial, mrloc batch)
    m.work = framesyncWork;
    m.report.subject = "one frame shared through walls seen by sonar (paper 004)";
    m.report.html = framesyncSection;  // its own picture (fig. 7): no world top view
    registry.add(std::move(m));
}

}  // namespace mrloc::framesync
