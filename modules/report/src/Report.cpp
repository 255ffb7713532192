#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/IniSection.h>
#include <mrloc/common/Metrics.h>
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

std::string html(const std::string& s) {
    std::string out;
    for (char c : s) {
        switch (c) {
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '&':
                out += "&amp;";
                break;
            case '\'':
                out += "&#39;";  // safe inside attributes too, quoted either way
                break;
            case '"':
                out += "&quot;";
                break;
            default:
                out += c;
        }
    }
    return out;
}

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

namespace {

std::string cell(const nlohmann::json& v) {
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
        for (const auto& e : v) out += (out.empty() ? "" : ", ") + cell(e);
        return out.empty() ? "none" : out;
    }
    return html(v.is_string() ? v.get<std::string>()
                              : v.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
}

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
        run.estimates[robot] = common::loadTum(common::run_dir::estimates(dir, robot));
        const auto gtPath = common::run_dir::groundTruth(dir, robot);
        if (std::filesystem::exists(gtPath)) run.truth[robot] = common::loadTum(gtPath);
    }
    return run;
}

/** Provenance: what produced this run, from provenance.json (written by the app). */
std::string provenanceSection(const std::string& dir) {
    const std::string path = common::run_dir::provenance(dir);
    if (!std::filesystem::exists(path)) return "<p>No provenance.json in this run directory.</p>\n";
    const auto p = common::loadJson(path);
    std::string t = "<table class='provenance'>\n";
    const auto row = [&](const std::string& head, const std::string& value) {
        t += "<tr><th>" + head + "</th><td>" + value + "</td></tr>\n";
    };
    if (p.contains("ini"))
        row("INI", "<code>" + html(p["ini"].get<std::string>()) +
                       "</code> (copied: <a href='config.ini'>config.ini</a>; with every default: "
                       "<a href='effective.ini'>effective.ini</a>)");
    if (p.contains("seed")) row("seed", cell(p["seed"]));
    if (p.contains("version")) row("mrloc version", cell(p["version"]));
    if (p.contains("steps"))
        for (const auto& [step, command] : p["steps"].items())
            row(html(step) + " command", "<code>" + cell(command) + "</code>");
    return t + "</table>\n";
}

}  // namespace

std::string metricsTable(const nlohmann::json& j) {
    std::string t = "<table>\n";
    for (const auto& [k, v] : j.items())
        if (!v.is_object())
            t += "<tr><th>" + html(keyInWords(k)) + "</th><td>" + cell(v) + "</td></tr>\n";
    return t + "</table>\n";
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
    std::string page =
        "<!DOCTYPE html>\n<html><head><meta charset='utf-8'><title>mrloc report: " + html(method) +
        "</title>\n<style>body{font-family:sans-serif;max-width:960px;margin:2em auto}"
        "table{border-collapse:collapse;margin:1em 0}th,td{border:1px solid #ccc;padding:3px 8px;"
        "text-align:left}img{max-width:100%;border:1px solid #ddd}</style></head><body>\n";
    page += "<h1>mrloc report: " + html(method) + "</h1>\n";
    page += provenanceSection(dir);
    ReportOptions paper;
    paper.loadFromConfigFile(*run.effective, "report");
    if (!paper.paperCaption.empty() || !paper.paperNote.empty())
        page += "<p><b>Compared with the paper:</b> " + html(paper.paperCaption) +
                (paper.paperNote.empty() ? "" : ". " + html(paper.paperNote)) + "</p>\n";
    page += "<p>rawlog: <code>" + html(metrics.value("rawlog", "?")) + "</code></p>\n";
    page += "<h2>Position error against the truth (horizontal, all robots)</h2>\n" +
            metricsTable(metrics);
    page +=
        "<h2>Per robot</h2>\n<table><tr><th>robot</th><th>estimates</th><th>compared</th>"
        "<th>RMSE (m)</th><th>median (m)</th><th>95th percentile (m)</th><th>max (m)</th></tr>\n";
    for (const auto& [robot, r] : metrics["robots"].items()) {
        page += "<tr><td>" + html(robot) + "</td><td>" + cell(r.value("estimates", 0)) + "</td>";
        for (const char* k : {"n", "rmse_m", "median_m", "p95_m", "max_m"})
            page += "<td>" + (r.contains(k) ? cell(r[k]) : std::string("none")) + "</td>";
        page += "</tr>\n";
    }
    page += "</table>\n";
    if (metrics.contains(method) && metrics[method].is_object() && !metrics[method].empty())
        page += "<h2>Method figures</h2>\n" + metricsTable(metrics[method]);
    if (section.html) page += section.html(run);
    if (topView)
        page +=
            "<h2>Top view</h2>\n<p>Each robot in its colour: the truth pale, the estimates "
            "full; the legend and the scale are in the picture.</p>\n"
            "<img src='topview.png' alt='top view'>\n";
    if (errors.empty())
        page += "<p>No estimate with ground truth beside it: no errors to plot.</p>\n";
    else if (perRobot)
        page +=
            "<h2>Error per robot</h2>\n<p>One estimate per robot: one marker each.</p>\n"
            "<img src='error_robots.png' alt='error per robot'>\n";
    else
        page +=
            "<h2>Error over time</h2>\n<img src='error_time.png' alt='error over time'>\n"
            "<h2>Error CDF</h2>\n<img src='error_cdf.png' alt='error CDF'>\n";
    page += "</body></html>\n";
    common::writeFileAtomically(common::run_dir::report(dir), page);
    return common::run_dir::report(dir);
}

}  // namespace mrloc::report
