#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/IniSection.h>
#include <mrloc/common/Metrics.h>
#include <mrloc/common/RunDirectory.h>
#include <mrloc/report/Plots.h>
#include <mrloc/report/PolygonView.h>
#include <mrloc/report/Report.h>
#include <mrloc/report/ReportOptions.h>
#include <mrloc/report/TopView.h>
#include <mrloc/sim/ShotLog.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/core/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace mrloc::report {

namespace {

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
            default:
                out += c;
        }
    }
    return out;
}

std::string cell(const nlohmann::json& v) {
    if (v.is_number_float()) {
        std::ostringstream s;
        s.precision(4);
        s << v.get<double>();
        return s.str();
    }
    return html(v.is_string() ? v.get<std::string>() : v.dump());
}

std::string table(const nlohmann::json& j) {
    std::string t = "<table>\n";
    for (const auto& [k, v] : j.items())
        if (!v.is_object()) t += "<tr><th>" + html(k) + "</th><td>" + cell(v) + "</td></tr>\n";
    return t + "</table>\n";
}

/** Seed 001 Tables 3/4 and Figs. 10/11 for this run: per robot (test point) the reception
 *  rate of each beacon from the simulator's shot log, and the mean and max error, beside
 *  the paper's figures from [report]. */
std::string beaconSystemSection(const nlohmann::json& metrics, const ReportOptions& paper) {
    const std::string shotsPath = sim::shotLogPath(metrics.value("rawlog", ""));
    if (!std::filesystem::exists(shotsPath)) return "";
    const auto shots = sim::loadShotLog(shotsPath);
    if (shots.empty()) return "";
    std::vector<std::string> robots;
    std::map<int, std::map<std::string, std::pair<int, int>>> heard;  // beacon, robot: n, ok
    for (const auto& s : shots) {
        if (std::find(robots.begin(), robots.end(), s.robot) == robots.end())
            robots.push_back(s.robot);
        auto& c = heard[s.beacon][s.robot];
        ++c.first;
        c.second += s.detected;
    }
    std::string t = "<h2>Beacon system: reception and errors per robot</h2>\n";
    if (!paper.paperCaption.empty())
        t += "<p>Ours, with the paper's in brackets: " + html(paper.paperCaption) + "</p>\n";
    t += "<table><tr><th>successful receiving rate (%)</th>";
    for (const auto& r : robots) t += "<th>" + html(r) + "</th>";
    t += "</tr>\n";
    for (const auto& [beacon, perRobot] : heard) {
        t += "<tr><th>beacon " + std::to_string(beacon) + "</th>";
        const auto p = paper.paperReception.find(beacon);
        for (size_t i = 0; i < robots.size(); ++i) {
            const auto c = perRobot.find(robots[i]);
            t += "<td>";
            if (c != perRobot.end())
                t += mrpt::format("%.0f", 100.0 * c->second.second / c->second.first);
            if (p != paper.paperReception.end() && i < p->second.size())
                t += mrpt::format(" (%g)", p->second[i]);
            t += "</td>";
        }
        t += "</tr>\n";
    }
    const auto row = [&](const char* name, const char* key, double scale, const char* fmt) {
        std::string r = std::string("<tr><th>") + name + "</th>";
        for (const auto& robot : robots) {
            const auto& m = metrics["robots"];
            r += "<td>";
            if (m.contains(robot) && m[robot].contains(key))
                r += mrpt::format(fmt, scale * m[robot][key].get<double>());
            r += "</td>";
        }
        return r + "</tr>\n";
    };
    t += row("mean error (mm)", "mean_m", 1000, "%.1f");
    t += row("max error (mm)", "max_m", 1000, "%.1f");
    t += row("fixes", "n", 1, "%.0f");
    t += "</table>\n";
    if (!paper.paperNote.empty()) t += "<p>Paper: " + html(paper.paperNote) + "</p>\n";
    t += "<p>Shots fired: " + std::to_string(shots.size()) + " (log: <code>" + html(shotsPath) +
         "</code>).</p>\n";
    return t;
}

/** The data lines of a text file written by a method ('#' lines are comments): each
 *  line's number ("file:line", for errors) and whitespace-separated fields. */
struct DataLine {
    std::string where;
    std::vector<std::string> fields;
};
std::vector<DataLine> readDataLines(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw Error(path + ": cannot open");
    std::vector<DataLine> lines;
    std::string line;
    for (int lineNo = 1; std::getline(in, line); ++lineNo) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream ls(line);
        DataLine d{path + ":" + std::to_string(lineNo), {}};
        for (std::string f; ls >> f;) d.fields.push_back(f);
        lines.push_back(std::move(d));
    }
    return lines;
}

double number(const std::string& where, const std::string& field) {
    char* end = nullptr;
    const double v = std::strtod(field.c_str(), &end);  // accepts "nan"
    if (end == field.c_str() || *end) throw Error(where + ": '" + field + "' is not a number");
    return v;
}

/** Rows of at least two numbers. */
std::vector<std::vector<double>> readRows(const std::string& path) {
    std::vector<std::vector<double>> rows;
    for (const auto& d : readDataLines(path)) {
        if (d.fields.size() < 2) throw Error(d.where + ": expected numbers");
        std::vector<double> row;
        for (const auto& f : d.fields) row.push_back(number(d.where, f));
        rows.push_back(std::move(row));
    }
    return rows;
}

/** The polygon-map section: the picture of P, V and H per robot, and H as a table. */
std::string polymapSection(const std::string& dir, const nlohmann::json& metrics) {
    const std::string mapPath = dir + "/map.poly";
    if (!std::filesystem::exists(mapPath)) return "";
    std::string out =
        "<h2>Polygon map: hypotheses</h2>\n<p>Black: the map P; green: the sensed "
        "visibility polygon V at the true start; orange: V placed at each "
        "hypothesis; red: the hypotheses (seed 002, hypothesis generation).</p>\n";
    const auto P = common::Polygon::load(mapPath);
    for (const auto& [robot, r] : metrics["robots"].items()) {
        PolygonViewContent view;
        view.map = P;
        for (const auto& row : readRows(dir + "/visibility." + robot + ".txt"))
            view.sensed.push_back({row[0], row[1]});
        const auto hyps = readRows(dir + "/hypotheses." + robot + ".txt");
        for (const auto& row : hyps) view.hypotheses.push_back({row[0], row[1]});
        const auto gtPath = common::run_dir::groundTruth(dir, robot);
        if (std::filesystem::exists(gtPath))
            if (const auto gt = common::loadTum(gtPath); !gt.empty())
                view.truth = common::TPoint2D{gt.front().pose.x(), gt.front().pose.y()};
        const std::string png = "polymap." + robot + ".png";
        renderPolygonView(view, dir + "/" + png);
        out += "<h3>Robot " + html(robot) + ": " + std::to_string(hyps.size()) +
               " hypotheses</h3>\n<img src='" + png + "' alt='map, V and hypotheses'>\n";
        out +=
            "<table><tr><th>#</th><th>x (m)</th><th>y (m)</th><th>translation (m)</th>"
            "<th>mismatch (m)</th><th>distance to truth (m)</th></tr>\n";
        for (size_t i = 0; i < hyps.size(); ++i) {
            const auto& h = hyps[i];
            const double d = view.truth ? (view.hypotheses[i] - *view.truth).norm() : -1;
            out += mrpt::format(
                "<tr><td>%zu</td><td>%.3f</td><td>%.3f</td><td>%.3f %.3f</td>"
                "<td>%.4f</td><td>%s</td></tr>\n",
                i + 1, h[0], h[1], h.size() > 3 ? h[2] : 0.0, h.size() > 3 ? h[3] : 0.0,
                h.size() > 4 ? h[4] : 0.0, d >= 0 ? mrpt::format("%.3f", d).c_str() : "-");
        }
        out += "</table>\n";
    }
    return out;
}

/** The omni-directional camera section (seed 000): true and recovered layouts, and the
 *  accuracy sweep when the run made one. */
std::string omnivisionSection(const std::string& dir, const nlohmann::json& metrics) {
    const std::string layoutPath = dir + "/layout.txt";
    if (!std::filesystem::exists(layoutPath)) return "";
    std::vector<LayoutPoint> points;
    for (const auto& d : readDataLines(layoutPath)) {
        const auto& f = d.fields;
        if (f.size() != 10) throw Error(d.where + ": expected a name and 9 numbers");
        LayoutPoint p{f[0], 0, 0, 0, 0, 0, 0, 0, 0, 0};
        double* v[] = {&p.paperX, &p.paperY, &p.refinedX, &p.refinedY, &p.cxx,
                       &p.cxy,    &p.cyy,    &p.trueX,    &p.trueY};
        for (size_t i = 0; i < 9; ++i) *v[i] = number(d.where, f[i + 1]);
        points.push_back(p);
    }
    const auto& m = metrics.value("omnivision", nlohmann::json::object());
    const std::string pair = m.value("pair", "A B");
    plotLayout(points,
               "layout: " + pair.substr(0, pair.find(' ')) + " at the origin, " +
                   pair.substr(pair.find(' ') + 1) + " on the x axis",
               dir + "/layout.png");
    std::string out =
        "<h2>Relative layout (seed 000)</h2>\n<p>Green: the truth; red: the paper's solution "
        "(eq. (8) for L, then the sine rule); blue: the least-squares refinement over every "
        "identified bearing and measured distance, with its 3-sigma ellipses.</p>\n"
        "<img src='layout.png' alt='true and recovered layouts'>\n";
    if (m.contains("restarts") && !m["restarts"].empty()) {
        out += "<p>Restarts (the stopped pair shared no witness):</p><ul>\n";
        for (const auto& r : m["restarts"]) out += "<li>" + html(r.get<std::string>()) + "</li>\n";
        out += "</ul>\n";
    }
    out +=
        "<table><tr><th>robot</th><th>paper x, y (m)</th><th>refined x, y (m)</th>"
        "<th>sigma x, y (mm)</th><th>truth x, y (m)</th></tr>\n";
    for (const auto& p : points)
        out += mrpt::format(
            "<tr><td>%s</td><td>%.3f, %.3f</td><td>%.3f, %.3f</td><td>%.1f, %.1f</td>"
            "<td>%.3f, %.3f</td></tr>\n",
            html(p.robot).c_str(), p.paperX, p.paperY, p.refinedX, p.refinedY,
            1000 * std::sqrt(std::max(0.0, p.cxx)), 1000 * std::sqrt(std::max(0.0, p.cyy)), p.trueX,
            p.trueY);
    out += "</table>\n";
    const std::string accPath = dir + "/accuracy.txt";
    if (std::filesystem::exists(accPath)) {
        std::vector<AccuracyRow> rows;
        std::string table =
            "<table><tr><th>varied</th><th>bearing sigma (deg)</th><th>distance sigma (%)</th>"
            "<th>paper (%)</th><th>least squares (%)</th><th>trials</th><th>failed</th></tr>\n";
        for (const auto& d : readDataLines(accPath)) {
            const auto& f = d.fields;
            if (f.size() != 7) throw Error(d.where + ": expected 7 fields");
            AccuracyRow r{f[0], number(d.where, f[1]), number(d.where, f[2]), number(d.where, f[3]),
                          number(d.where, f[4])};
            rows.push_back(r);
            table += mrpt::format(
                "<tr><td>%s</td><td>%g</td><td>%g</td><td>%.3f</td><td>%.3f</td><td>%s</td>"
                "<td>%s</td></tr>\n",
                html(r.axis).c_str(), r.angleSigmaDeg, 100 * r.distanceSigma, 100 * r.paper,
                100 * r.refined, f[5].c_str(), f[6].c_str());
        }
        const bool proposed = m.value("method", "proposed") == "proposed";
        plotAccuracy(rows, proposed ? "odometer" : "LiDAR", dir + "/accuracy.png");
        out +=
            "<h3>Accuracy against noise (Monte Carlo on this run's true layout)</h3>\n"
            "<p>Median relative error of all pairwise distances, mean over the trials.</p>\n"
            "<img src='accuracy.png' alt='accuracy against noise'>\n" +
            table + "</table>\n";
    }
    return out;
}

}  // namespace

std::string makeReport(const std::string& dir) {
    if (!std::filesystem::exists(common::run_dir::metrics(dir)))
        throw Error(dir + ": not a run directory (no metrics.json; run `mrloc localize` first)");
    const auto metrics = common::loadJson(common::run_dir::metrics(dir));

    TopViewContent view;
    ReportOptions paper;
    if (std::filesystem::exists(common::run_dir::effectiveIni(dir))) {
        mrpt::config::CConfigFile ini(common::run_dir::effectiveIni(dir));
        paper.loadFromConfigFile(ini, "report");
        if (ini.sectionExists("world")) {
            sim::WorldOptions w;
            w.loadFromConfigFile(ini, "world");
            view.world = w;
        }
        common::IniSection beacons(ini, "beacons");
        view.beacons = common::readBeaconKeys(beacons);
    }
    RobotErrors errors;
    if (!metrics.contains("robots")) throw Error(common::run_dir::metrics(dir) + ": no 'robots'");
    for (const auto& [robot, r] : metrics["robots"].items()) {
        view.estimates[robot] = common::loadTum(common::run_dir::estimates(dir, robot));
        const auto gtPath = common::run_dir::groundTruth(dir, robot);
        if (std::filesystem::exists(gtPath)) {
            view.groundTruth[robot] = common::loadTum(gtPath);
            auto e = common::positionErrors(view.estimates[robot], view.groundTruth[robot]);
            if (!e.empty()) errors[robot] = std::move(e);
        }
    }
    // The polygon view and the relative layout replace the world top view.
    const bool polygonMap = std::filesystem::exists(dir + "/map.poly");
    const bool relativeLayout = std::filesystem::exists(dir + "/layout.txt");
    const bool topView = !polygonMap && !relativeLayout;
    if (topView) renderTopView(view, dir + "/topview.png");
    const bool hasErrors = !errors.empty();
    if (hasErrors) {
        plotErrorOverTime(errors, dir + "/error_time.png");
        plotErrorCdf(errors, dir + "/error_cdf.png");
    }

    std::string page =
        "<!DOCTYPE html>\n<html><head><meta charset='utf-8'><title>mrloc report</title>\n"
        "<style>body{font-family:sans-serif;max-width:960px;margin:2em auto}"
        "table{border-collapse:collapse;margin:1em 0}th,td{border:1px solid #ccc;padding:3px 8px;"
        "text-align:left}img{max-width:100%;border:1px solid #ddd}</style></head><body>\n";
    page += "<h1>mrloc report: " + html(metrics.value("method", "?")) + "</h1>\n";
    page += "<p>rawlog: <code>" + html(metrics.value("rawlog", "?")) + "</code></p>\n";
    page += "<h2>Metrics (horizontal position error, metres)</h2>\n" + table(metrics);
    for (const auto& [robot, r] : metrics["robots"].items())
        page += "<h3>Robot " + html(robot) + "</h3>\n" + table(r);
    page += beaconSystemSection(metrics, paper);
    const std::string method = metrics.value("method", "");
    if (metrics.contains(method) && metrics[method].is_object())
        page += "<h2>Method figures</h2>\n" + table(metrics[method]);
    page += polymapSection(dir, metrics);
    page += omnivisionSection(dir, metrics);
    if (topView)
        page +=
            "<h2>Top view</h2>\n<p>Green: ground truth; red: estimates; blue: beacons; grey: "
            "obstacles.</p>\n<img src='topview.png' alt='top view'>\n";
    if (hasErrors)
        page +=
            "<h2>Error over time</h2>\n<img src='error_time.png' alt='error over time'>\n"
            "<h2>Error CDF</h2>\n<img src='error_cdf.png' alt='error CDF'>\n";
    else
        page += "<p>No estimate with ground truth beside it: no errors to plot.</p>\n";
    page += "</body></html>\n";
    common::writeFileAtomically(common::run_dir::report(dir), page);
    return common::run_dir::report(dir);
}

}  // namespace mrloc::report
