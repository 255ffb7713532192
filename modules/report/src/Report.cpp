#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/Evaluation.h>
#include <mrloc/common/IniSection.h>
#include <mrloc/common/Metrics.h>
#include <mrloc/common/Names.h>
#include <mrloc/common/Outcome.h>
#include <mrloc/common/RunDirectory.h>
#include <mrloc/report/EvaluationPlots.h>
#include <mrloc/report/Plots.h>
#include <mrloc/report/Report.h>
#include <mrloc/report/ReportOptions.h>
#include <mrloc/report/TopView.h>
#include <mrpt/core/format.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace mrloc::report {

std::string keyInWords(const std::string& key) {
    static const std::map<std::string, std::string> known = {
        {"n", "estimates compared with the truth"},
        {"rmse_m", "RMSE (m)"},
        {"mean_m", "mean error (m)"},
        {"median_m", "median error (m)"},
        {"p95_m", "95th percentile (m)"},
        {"max_m", "max error (m)"},
        {"wall_s", "localization time (s)"},
        {"observations", "observations read"},
        {"rawlog_format", "rawlog format"},
        {"ground_truth", "ground truth available"},
        {"estimates", "estimates"}};
    if (const auto it = known.find(key); it != known.end()) return it->second;
    static const std::pair<const char*, const char*> units[] = {
        {"_mm", " (mm)"}, {"_m", " (m)"}, {"_s", " (s)"}, {"_deg", " (deg)"}, {"_hz", " (Hz)"}};
    std::string words = key, unit;
    for (const auto& [suffix, u] : units) {
        const std::string sfx = suffix;
        if (words.size() > sfx.size() &&
            words.compare(words.size() - sfx.size(), sfx.size(), sfx) == 0) {
            words.resize(words.size() - sfx.size());
            unit = u;
            break;
        }
    }
    for (char& c : words)
        if (c == '_') c = ' ';
    return words + unit;
}

std::string cellText(const nlohmann::json& v) {
    if (v.is_null()) return "none";
    if (v.is_boolean()) return v.get<bool>() ? "yes" : "no";
    if (v.is_number_float()) {
        std::ostringstream s;
        s.precision(4);
        s << v.get<double>();
        return s.str();
    }
    if (v.is_array()) {
        std::string out;
        for (const auto& e : v) out += (out.empty() ? "" : ", ") + cellText(e);
        return out.empty() ? "none" : out;
    }
    return v.is_string() ? v.get<std::string>()
                         : v.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

namespace {

/** Reads the run directory: metrics, effective.ini, estimates and truth. */
RunView readRun(const std::string& dir) {
    if (!std::filesystem::exists(common::run_dir::metrics(dir)))
        throw Error(dir + ": not a run directory (no metrics.json; run `mrloc localize` first)");
    RunView run;
    run.dir = dir;
    run.metrics = common::readMetricsFile(common::run_dir::metrics(dir));
    if (!run.metrics.contains("robots") || !run.metrics["robots"].is_object())
        throw Error(common::run_dir::metrics(dir) + ": no 'robots'");
    run.effective = std::make_shared<mrpt::config::CConfigFileMemory>();
    if (std::ifstream in(common::run_dir::effectiveIni(dir)); in) {
        std::stringstream text;
        text << in.rdbuf();
        run.effective->setContent(text.str());
    }
    for (const auto& [robot, r] : run.metrics["robots"].items()) {
        // a run folder may come from someone else: its robots name files the report reads
        // and pictures it writes, so they must be names, not paths
        common::checkRobotName(robot, common::run_dir::metrics(dir) + ": robots");
        run.estimates[robot] = common::loadTum(common::run_dir::estimates(dir, robot));
        const auto gtPath = common::run_dir::groundTruth(dir, robot);
        if (std::filesystem::exists(gtPath)) run.truth[robot] = common::loadTum(gtPath);
    }
    return run;
}

/** Odometry alone per robot (odometry.<robot>.txt), placed where the robot truly was at its
 *  first reading (else at its first estimate), as the baseline's errors are computed. */
common::Trajectories odometryPaths(const RunView& run) {
    common::Trajectories out;
    for (const auto& [robot, est] : run.estimates) {
        const std::string path = common::run_dir::odometry(run.dir, robot);
        if (!std::filesystem::exists(path) || est.empty()) continue;
        const auto odo = common::loadTum(path);
        if (odo.empty()) continue;
        std::optional<mrpt::poses::CPose3D> start;
        if (const auto gt = run.truth.find(robot); gt != run.truth.end())
            start = common::startPoseOf(gt->second, odo.front().t);
        if (!start) start = est.front().pose;
        const mrpt::poses::CPose3D align = *start + (-odo.front().pose);
        for (const auto& p : odo) out[robot].push_back({p.t, align + p.pose});
    }
    return out;
}

/** Robots whose path and x, y, heading get pictures of their own (a swarm's first few). */
constexpr size_t kRobotsPictured = 4;

bool isBaseline(const RunView& run, const std::string& robot) {
    const auto& robots = run.metrics["robots"];
    return robots.contains(robot) && robots[robot].is_object() &&
           robots[robot].value("baseline", false);
}

/** Each robot's evaluation on the truth's timeline, as metrics.json's (doc/evaluation.md),
 *  drawn: the error over time and its CDF for all, and the first robots' x, y, heading and
 *  path coloured by the error. */
std::vector<EvaluatedTrack> truthTimelinePictures(const RunView& run, const std::string& dir) {
    std::vector<EvaluatedTrack> tracks;
    const auto odometry = odometryPaths(run);
    for (const auto& [robot, est] : run.estimates) {
        const auto gt = run.truth.find(robot);
        if (gt == run.truth.end() || est.empty()) continue;
        EvaluatedTrack t;
        t.name = isBaseline(run, robot) ? robot + " (baseline)" : robot;
        t.estimate = common::evaluate(est, gt->second);
        if (const auto odo = odometry.find(robot); odo != odometry.end())
            t.odometry = common::evaluate(odo->second, gt->second);
        t.truth = gt->second;
        if (const auto path = common::run_dir::covariance(dir, robot);
            std::filesystem::exists(path))
            t.covariances = common::loadCovariances(path);
        tracks.push_back(std::move(t));
    }
    if (tracks.empty()) return tracks;
    plotTruthTimelineError(tracks, dir + "/error_time.png");
    plotTruthTimelineCdf(tracks, dir + "/error_cdf.png");
    size_t pictured = 0;
    for (const auto& [robot, est] : run.estimates)
        for (const auto& t : tracks)
            if (pictured < kRobotsPictured && t.name == robot && !t.estimate.errors.empty()) {
                plotPoseOverTime(t, dir + "/pose_time." + robot + ".png");
                plotErrorTopView(t, dir + "/error_topview." + robot + ".png");
                ++pictured;
            }
    return tracks;
}

/** A robot with covered stamps that is not a baseline: one its pictures and gap limit are for. */
bool isPicturedTrack(const EvaluatedTrack& t) {
    return t.name.find(" (baseline)") == std::string::npos && !t.estimate.errors.empty();
}

/** The alignment the errors are taken under and the gap limit, in a sentence. */
std::string alignmentInWords(const std::vector<EvaluatedTrack>& tracks) {
    std::string limits;
    for (const auto& t : tracks)
        if (isPicturedTrack(t))
            limits += mrpt::format("%s%s %.3g s", limits.empty() ? "" : ", ", t.name.c_str(),
                                   t.estimate.coverage.maxGap);
    const auto align = tracks.empty() ? common::Alignment::None : tracks.front().estimate.align;
    return std::string("Alignment: ") + common::alignmentName(align) +
           (align == common::Alignment::None
                ? " (the estimates are scored in the truth's frame, the map's: an offset of the "
                  "whole path is an error; mrloc eval --align se2 or origin scores them otherwise)"
                : "") +
           ". Gap limit (5 times the median interval between estimates, at least 1 s): " +
           (limits.empty() ? std::string("no robot has a covered stamp") : limits) + ".";
}

/** The truth-timeline pictures with what they show. */
Html truthTimelineSection(const std::vector<EvaluatedTrack>& tracks) {
    Html out = heading(2, "Error on the truth's timeline") +
               paragraph(
                   "At every stamp of the truth, the estimate interpolated there (doc/"
                   "evaluation.md); grey where there is no estimate to interpolate (before the "
                   "first, after the last, or across a gap longer than the limit), counted as "
                   "not covered, never left out. Odometry alone is dashed in the robot's "
                   "colour.") +
               paragraph(alignmentInWords(tracks)) +
               Figure{"error_time.png",
                      "position error at every truth stamp: the estimate (solid) should stay under "
                      "odometry alone (dashed); grey where nothing was estimated"}
                   .html() +
               Figure{"error_cdf.png",
                      "share of the truth stamps within each error: further left is better; "
                      "dashed, odometry alone"}
                   .html();
    size_t pictured = 0;
    for (const auto& t : tracks) {
        if (!isPicturedTrack(t) || pictured == kRobotsPictured) continue;
        ++pictured;
        out += heading(3, "Robot " + t.name) +
               Figure{"pose_time." + t.name + ".png",
                      "x, y and heading against time: the estimate (thin) should lie on the truth "
                      "(wide grey)"}
                   .html() +
               Figure{"error_topview." + t.name + ".png",
                      t.covariances.empty() ? "the path coloured by its error (dark small, yellow "
                                              "large): look where it turns yellow"
                                            : "the path coloured by its error (dark small, yellow "
                                              "large); the 2-sigma ellipses should hold the truth"}
                   .html();
    }
    if (tracks.size() > pictured)
        out +=
            paragraph(mrpt::format("x, y, heading and the path coloured by the error are "
                                   "drawn for the first %zu robots; the error plots above "
                                   "hold all %zu.",
                                   pictured, tracks.size()));
    return out;
}

/** provenance.json (written by the app), or an empty object. */
nlohmann::json provenanceOf(const std::string& dir) {
    const std::string path = common::run_dir::provenance(dir);
    if (!std::filesystem::exists(path)) return nlohmann::json::object();
    return common::readProvenanceFile(path);
}

std::string textAt(const nlohmann::json& j, const char* key) {
    return j.contains(key) ? cellText(j[key]) : std::string();
}

/** Was the log simulated by mrloc (in this folder, or beside a simulated truth)? */
bool simulatedRun(const nlohmann::json& provenance, const nlohmann::json& metrics) {
    if (provenance.value("simulated", false)) return true;
    return metrics.value("ground_truth_from", "").find("mrloc's simulator") != std::string::npos;
}

/** What ran: the method, the INI, the rawlog, real or simulated, where the truth came from. */
Html whatRan(const RunView& run, const Section& section, const nlohmann::json& provenance) {
    const auto& m = run.metrics;
    Table t;
    const std::string method = m.value("method", "?");
    t.headedRow("method",
                {code(method) + (section.subject.empty() ? Html() : Html(": " + section.subject))});
    if (provenance.contains("ini"))
        t.headedRow(
            "INI",
            {code(textAt(provenance, "ini")) + " (copied: " + link("config.ini", "config.ini") +
             "; with every default: " + link("effective.ini", "effective.ini") + ")"});
    t.headedRow("rawlog", {code(m.value("rawlog", "?"))});
    const bool simulated = simulatedRun(provenance, m);
    t.headedRow("log", {simulated ? Html("simulated by mrloc, seed " + textAt(provenance, "seed"))
                                  : Html("recorded elsewhere (not simulated in this run)")});
    if (provenance.contains("seed_overrides"))
        t.headedRow("fixed sub-seeds",
                    {Html("drawn from these INI keys, not from the run's seed: " +
                          textAt(provenance, "seed_overrides"))});
    const std::string truthFrom = m.value("ground_truth_from", "");
    t.headedRow(
        "ground truth",
        {truthFrom.empty() ? Html("none: the errors below cannot be computed") : Html(truthFrom)});
    return t.html();
}

/** The headline: the outcome, then each figure beside the paper's, baselines marked; on a log
 *  recorded elsewhere (`besidePaper` false) no paper's figure: the papers' numbers are for
 *  their own experiments, not for a user's log. */
Html headlineBlock(const nlohmann::json& metrics, const std::string& where, bool besidePaper) {
    if (!metrics.contains("headline")) return paragraph("No headline in metrics.json.");
    const auto h = common::headlineFromJson(metrics["headline"], where);
    Html out =
        paragraph(bold(h.reached ? "Outcome: " : "Outcome (goal not reached): ") + Html(h.status));
    if (!h.mechanism.empty()) out += paragraph(bold("What ran: ") + Html(h.mechanism));
    Table t(besidePaper ? std::vector<Html>{"figure", "this run", "the paper",
                                            "how this run differs from the paper's"}
                        : std::vector<Html>{"figure", "this run"});
    for (const auto& f : h.figures) {
        auto cells = figureCells(f);
        if (!besidePaper) cells.resize(2);
        t.row(cells);
    }
    if (t.rows()) out += t.html();
    if (!besidePaper && t.rows())
        out += paragraph(
            "This log was recorded elsewhere: no paper's figure is set beside this run's, since "
            "the papers' figures are for their own experiments.");
    std::vector<Html> warnings;
    if (metrics.contains("warnings") && metrics["warnings"].is_array())
        for (const auto& w : metrics["warnings"]) warnings.push_back(cellText(w));
    if (!warnings.empty()) out += paragraph(bold("Warnings:")) + bulletList(warnings);
    return out;
}

/** Provenance: what produced this run, from provenance.json. */
Html provenanceSection(const nlohmann::json& p) {
    if (p.empty()) return paragraph("No provenance.json in this run directory.");
    Table t;
    if (p.contains("date_utc")) t.headedRow("date (UTC)", {textAt(p, "date_utc")});
    if (p.contains("version"))
        t.headedRow("mrloc", {"version " + textAt(p, "version") +
                              (p.contains("commit") ? ", commit " + textAt(p, "commit") : "")});
    if (p.contains("mrpt_version")) t.headedRow("MRPT", {textAt(p, "mrpt_version")});
    if (p.contains("cpu"))
        t.headedRow("machine", {textAt(p, "cpu") +
                                (p.contains("cores") ? ", " + textAt(p, "cores") + " cores" : "")});
    if (p.contains("steps") && p["steps"].is_object())
        for (const auto& [step, command] : p["steps"].items())
            t.headedRow(step + " command", {code(cellText(command))});
    return t.html();
}

/** The page's title: [report] title, else, for a log recorded elsewhere, its file and the
 *  method, else the scenario's name and the method's subject (a paper's experiment). */
std::string titleOf(const RunView& run, const Section& section, const ReportOptions& options,
                    bool simulated) {
    if (!options.title.empty()) return options.title;
    if (!simulated) {
        const std::string rawlog =
            std::filesystem::path(run.metrics.value("rawlog", "")).filename().string();
        return (rawlog.empty() ? std::string("a log") : rawlog) + ": " +
               run.metrics.value("method", "mrloc") + " on a log recorded elsewhere";
    }
    std::string name = run.effective->read_string("scenario", "name", "");
    if (name.empty()) name = run.metrics.value("method", "mrloc");
    return section.subject.empty() ? name : name + ": " + section.subject;
}

/** The generic figures first, in the order a reader asks for them; then the rest. */
Html orderedMetricsTable(const nlohmann::json& j) {
    static const std::vector<std::string> first{"rmse_m", "mean_m", "median_m",     "p95_m",
                                                "max_m",  "n",      "observations", "wall_s"};
    // shown in the top block, or as a table of its own
    static const std::set<std::string> elsewhere{"method", "rawlog", "ground_truth",
                                                 "ground_truth_from", "warnings"};
    Table t;
    for (const auto& k : first)
        if (j.contains(k) && !j[k].is_object()) t.headedRow(keyInWords(k), {cellText(j[k])});
    for (const auto& [k, v] : j.items())
        if (!v.is_object() && !elsewhere.count(k) &&
            std::find(first.begin(), first.end(), k) == first.end())
            t.headedRow(keyInWords(k), {cellText(v)});
    return t.html();
}

}  // namespace

std::vector<Html> figureCells(const common::HeadlineFigure& f) {
    // a no-break space: the number and its unit stay on one line
    return {f.baseline ? Html(f.name + " (baseline)") : bold(f.name),
            common::valueText(f, "\u00a0"), f.paper.empty() ? "no figure in the paper" : f.paper,
            f.differs.empty() ? (f.paper.empty() ? "" : "the paper's experiment") : f.differs};
}

Html metricsTable(const nlohmann::json& j) {
    Table t;
    for (const auto& [k, v] : j.items())
        if (!v.is_object()) t.headedRow(keyInWords(k), {cellText(v)});
    return t.html();
}

std::string makeReport(const std::string& dir, const Section& section) {
    const RunView run = readRun(dir);
    const auto& metrics = run.metrics;
    RobotErrors errors;
    for (const auto& [robot, est] : run.estimates)
        if (const auto gt = run.truth.find(robot); gt != run.truth.end())
            if (auto e = common::positionErrors(est, gt->second); !e.empty()) {
                // a baseline robot (dead reckoning) is named so in the plots' keys
                const bool baseline = metrics["robots"].contains(robot) &&
                                      metrics["robots"][robot].is_object() &&
                                      metrics["robots"][robot].value("baseline", false);
                errors[baseline ? robot + " (baseline)" : robot] = std::move(e);
            }
    const bool topView = bool(section.topView);
    if (topView) {
        TopViewContent view;
        if (run.effective->sectionExists("world")) {
            sim::WorldOptions w;
            w.loadFromConfigFile(*run.effective, "world");
            view.world = w;
        }
        view.estimates = run.estimates;
        view.groundTruth = run.truth;
        view.odometry = odometryPaths(run);
        section.topView(run, view);
        renderTopView(view, dir + "/topview.png");
    }
    const bool perRobot = !errors.empty() && oneErrorPerRobot(errors);
    std::vector<EvaluatedTrack> tracks;
    if (!errors.empty()) {
        if (perRobot)
            plotErrorPerRobot(errors, dir + "/error_robots.png");
        else
            tracks = truthTimelinePictures(run, dir);
    }

    const auto provenance = provenanceOf(dir);
    ReportOptions options;
    options.loadFromConfigFile(*run.effective, "report");
    const bool simulated = simulatedRun(provenance, metrics);
    const std::string title = titleOf(run, section, options, simulated);
    Html body = heading(1, title) + heading(2, "What ran") + whatRan(run, section, provenance) +
                heading(2, "Headline") +
                headlineBlock(metrics, common::run_dir::metrics(dir), simulated);
    if (simulated && (!options.paperCaption.empty() || !options.paperNote.empty()))
        body += paragraph(bold("Compared with the paper:") + " " + options.paperCaption +
                          (options.paperNote.empty() ? "" : ". " + options.paperNote));
    body += heading(2, "Provenance") + provenanceSection(provenance);
    body += heading(2,
                    "Position error against the truth (horizontal, all robots but the "
                    "baselines)") +
            orderedMetricsTable(metrics);
    Table perRobotTable({"robot", "estimates", "compared", "RMSE (m)", "median (m)",
                         "95th percentile (m)", "max (m)"});
    for (const auto& [robot, r] : metrics["robots"].items()) {
        std::vector<Html> cells{
            r.value("baseline", false) ? Html(robot + " (baseline)") : Html(robot),
            cellText(r.value("estimates", 0))};
        for (const char* k : {"n", "rmse_m", "median_m", "p95_m", "max_m"})
            cells.push_back(r.contains(k) ? cellText(r[k]) : "none");
        perRobotTable.row(std::move(cells));
    }
    body += heading(2, "Per robot") + perRobotTable.html();
    const std::string method = metrics.value("method", "?");
    if (metrics.contains(method) && metrics[method].is_object() && !metrics[method].empty())
        body += heading(2, "Method figures") + metricsTable(metrics[method]);
    if (section.html) body += section.html(run);
    if (topView)
        body += heading(2, "Top view") +
                paragraph(
                    "Each robot in its colour (one colour-blind-safe palette in every "
                    "picture): the truth a wide pale band, the estimate a thin line, odometry "
                    "alone dashed; axes in metres, the legend beside the drawing.") +
                Figure{"topview.png",
                       "each robot in its colour: the estimate (thin line) should lie on the truth "
                       "(wide pale band); odometry alone dashed; the ring, the start"}
                    .html();
    if (errors.empty())
        body += paragraph("No estimate with ground truth beside it: no errors to plot.");
    else if (perRobot)
        body += heading(2, "Error per robot") +
                paragraph("One estimate per robot: one marker each.") +
                Figure{"error_robots.png", "one dot per robot: its position error"}.html();
    else
        body += truthTimelineSection(tracks);
    const std::string page = htmlPage(title, body);
    common::writeFileAtomically(common::run_dir::report(dir), page);
    return common::run_dir::report(dir);
}

}  // namespace mrloc::report
