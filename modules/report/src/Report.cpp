#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/IniSection.h>
#include <mrloc/common/Metrics.h>
#include <mrloc/common/Names.h>
#include <mrloc/common/RunDirectory.h>
#include <mrloc/report/Plots.h>
#include <mrloc/report/Report.h>
#include <mrloc/report/ReportOptions.h>
#include <mrloc/report/TopView.h>

#include <filesystem>
#include <fstream>
#include <map>
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
    run.metrics = common::loadJson(common::run_dir::metrics(dir));
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

/** Provenance: what produced this run, from provenance.json (written by the app). */
Html provenanceSection(const std::string& dir) {
    const std::string path = common::run_dir::provenance(dir);
    if (!std::filesystem::exists(path))
        return paragraph("No provenance.json in this run directory.");
    const auto p = common::loadJson(path);
    Table t;
    if (p.contains("ini"))
        t.headedRow("INI",
                    {code(cellText(p["ini"])) + " (copied: " + link("config.ini", "config.ini") +
                     "; with every default: " + link("effective.ini", "effective.ini") + ")"});
    if (p.contains("seed")) t.headedRow("seed", {cellText(p["seed"])});
    if (p.contains("version")) t.headedRow("mrloc version", {cellText(p["version"])});
    if (p.contains("steps") && p["steps"].is_object())
        for (const auto& [step, command] : p["steps"].items())
            t.headedRow(step + " command", {code(cellText(command))});
    return t.html();
}

}  // namespace

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
            if (auto e = common::positionErrors(est, gt->second); !e.empty())
                errors[robot] = std::move(e);
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
        section.topView(run, view);
        renderTopView(view, dir + "/topview.png");
    }
    const bool perRobot = !errors.empty() && oneErrorPerRobot(errors);
    if (!errors.empty()) {
        if (perRobot) {
            plotErrorPerRobot(errors, dir + "/error_robots.png");
        } else {
            plotErrorOverTime(errors, dir + "/error_time.png");
            plotErrorCdf(errors, dir + "/error_cdf.png");
        }
    }

    const std::string method = metrics.value("method", "?");
    Html body = heading(1, "mrloc report: " + method) + provenanceSection(dir);
    ReportOptions paper;
    paper.loadFromConfigFile(*run.effective, "report");
    if (!paper.paperCaption.empty() || !paper.paperNote.empty())
        body += paragraph(bold("Compared with the paper:") + " " + paper.paperCaption +
                          (paper.paperNote.empty() ? "" : ". " + paper.paperNote));
    body += paragraph("rawlog: " + code(metrics.value("rawlog", "?")));
    body += heading(2, "Position error against the truth (horizontal, all robots)") +
            metricsTable(metrics);
    Table perRobotTable({"robot", "estimates", "compared", "RMSE (m)", "median (m)",
                         "95th percentile (m)", "max (m)"});
    for (const auto& [robot, r] : metrics["robots"].items()) {
        std::vector<Html> cells{robot, cellText(r.value("estimates", 0))};
        for (const char* k : {"n", "rmse_m", "median_m", "p95_m", "max_m"})
            cells.push_back(r.contains(k) ? cellText(r[k]) : "none");
        perRobotTable.row(std::move(cells));
    }
    body += heading(2, "Per robot") + perRobotTable.html();
    if (metrics.contains(method) && metrics[method].is_object() && !metrics[method].empty())
        body += heading(2, "Method figures") + metricsTable(metrics[method]);
    if (section.html) body += section.html(run);
    if (topView)
        body += heading(2, "Top view") +
                paragraph(
                    "Each robot in its colour: the truth pale, the estimates full; the "
                    "legend and the scale are in the picture.") +
                Figure{"topview.png", "top view"}.html();
    if (errors.empty())
        body += paragraph("No estimate with ground truth beside it: no errors to plot.");
    else if (perRobot)
        body += heading(2, "Error per robot") +
                paragraph("One estimate per robot: one marker each.") +
                Figure{"error_robots.png", "error per robot"}.html();
    else
        body += heading(2, "Error over time") + Figure{"error_time.png", "error over time"}.html() +
                heading(2, "Error CDF") + Figure{"error_cdf.png", "error CDF"}.html();
    const std::string page = htmlPage("mrloc report: " + method, body);
    common::writeFileAtomically(common::run_dir::report(dir), page);
    return common::run_dir::report(dir);
}

}  // namespace mrloc::report
