#include "BatchSummary.h"

#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/Metrics.h>
#include <mrloc/common/Names.h>
#include <mrloc/report/Html.h>
#include <mrloc/report/Plots.h>
#include <mrpt/core/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace mrloc::app {

namespace fs = std::filesystem;

namespace {

constexpr size_t kBins = 20;

FigureStats statsOf(const std::string& name, const std::string& unit, bool baseline,
                    const std::vector<double>& values) {
    FigureStats f;
    f.name = name, f.unit = unit, f.baseline = baseline;
    f.count = values.size();
    if (values.empty()) return f;
    // mean (summed in seed order, as the experiments sum), median and p95 as every run's
    // error statistics; min and max here, as figures may be negative
    const auto stats = common::computeStats(values);
    f.mean = stats.mean, f.median = stats.median, f.p95 = stats.p95;
    const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
    f.min = *lo, f.max = *hi;
    double ss = 0;
    for (const double v : values) ss += (v - f.mean) * (v - f.mean);
    f.sd = values.size() > 1 ? std::sqrt(ss / double(values.size() - 1)) : 0;
    f.histogram.assign(kBins, 0);
    const double width = (f.max - f.min) / double(kBins);
    for (const double v : values)
        ++f.histogram[width > 0 ? std::min(kBins - 1, size_t((v - f.min) / width)) : 0];
    return f;
}

/** The job log's last status of each job (its line number in jobs.txt, from 1), and the
 *  number of jobs it shows done (exit 0) more than once. */
struct JobLog {
    std::map<size_t, std::string> lastProblem;  ///< jobs whose last entry failed
    std::map<size_t, size_t> doneCount;
};

JobLog readJobLog(const std::string& path) {
    JobLog log;
    if (!fs::is_regular_file(fs::symlink_status(path))) return log;
    common::checkReadableFile(path, "job log", 1u << 30);
    std::ifstream in(path);
    std::string line;
    std::getline(in, line);  // Seq Host Starttime JobRuntime Send Receive Exitval Signal Command
    while (std::getline(in, line)) {
        std::istringstream fields(line);
        std::vector<std::string> f;
        for (std::string w; f.size() < 8 && (fields >> w);) f.push_back(w);
        if (f.size() < 8) continue;  // a line cut short by a crash
        char* end = nullptr;
        const size_t seq = std::strtoul(f[0].c_str(), &end, 10);
        const long exitval = std::strtol(f[6].c_str(), nullptr, 10);
        const long sig = std::strtol(f[7].c_str(), nullptr, 10);
        if (exitval == 0 && sig == 0) {
            ++log.doneCount[seq];
            log.lastProblem.erase(seq);
        } else {
            log.lastProblem[seq] =
                sig ? "killed by signal " + std::to_string(sig) : "exit " + std::to_string(exitval);
        }
    }
    return log;
}

nlohmann::json toJson(const FigureStats& f) {
    return {{"name", f.name},
            {"unit", f.unit},
            {"baseline", f.baseline},
            {"count", f.count},
            {"mean", f.mean},
            {"median", f.median},
            {"p95", f.p95},
            {"sd", f.sd},
            {"min", f.min},
            {"max", f.max},
            {"histogram", f.histogram}};
}

nlohmann::json toJson(const BatchSummary& s) {
    nlohmann::json j;
    j["plan"] = toJson(s.plan);
    j["method"] = s.method;
    j["trials"] = s.trials;
    j["points"] = nlohmann::json::array();
    for (const auto& p : s.points) {
        nlohmann::json jp{
            {"index", p.index}, {"name", p.name}, {"done", p.done}, {"reached", p.reached}};
        jp["keys"] = nlohmann::json::object();
        for (const auto& k : p.keys) jp["keys"][k.section + "." + k.key] = k.value;
        jp["figures"] = nlohmann::json::array();
        for (const auto& f : p.figures) jp["figures"].push_back(toJson(f));
        j["points"].push_back(jp);
    }
    for (const auto* list : {&s.failed, &s.missing}) {
        auto& out = j[list == &s.failed ? "failed" : "missing"] = nlohmann::json::array();
        for (const auto& t : *list)
            out.push_back({{"point", t.point}, {"seed", t.seed}, {"why", t.why}});
    }
    j["rerun"] = s.rerun;
    return j;
}

BatchSummary summaryFromJson(const nlohmann::json& j, const std::string& where) {
    BatchSummary s;
    try {
        s.plan = planFromJson(j.at("plan"), "plan");
        s.method = j.at("method").get<std::string>();
        s.trials = wholeNumber(j.at("trials"));
        for (const auto& jp : j.at("points")) {
            PointSummary p;
            p.index = wholeNumber(jp.at("index"));
            if (p.index >= s.plan.pointCount()) throw Error("a point outside the plan");
            p.name = s.plan.pointName(p.index);
            p.keys = s.plan.pointKeys(p.index);
            p.done = wholeNumber(jp.at("done"));
            p.reached = wholeNumber(jp.at("reached"));
            for (const auto& jf : jp.at("figures")) {
                FigureStats f;
                f.name = jf.at("name").get<std::string>();
                f.unit = jf.at("unit").get<std::string>();
                f.baseline = jf.at("baseline").get<bool>();
                f.count = wholeNumber(jf.at("count"));
                for (auto [field, key] : {std::pair{&f.mean, "mean"},
                                          {&f.median, "median"},
                                          {&f.p95, "p95"},
                                          {&f.sd, "sd"},
                                          {&f.min, "min"},
                                          {&f.max, "max"}})
                    *field = jf.at(key).get<double>();
                for (const auto& h : jf.at("histogram")) f.histogram.push_back(wholeNumber(h));
                if (f.histogram.size() > kBins) throw Error("a histogram of more than 20 bins");
                p.figures.push_back(f);
            }
            if (p.figures.size() > 1000) throw Error("more than 1,000 figures");
            s.points.push_back(p);
        }
        for (const char* list : {"failed", "missing"})
            for (const auto& jt : j.at(list))
                (std::string(list) == "failed" ? s.failed : s.missing)
                    .push_back({wholeNumber(jt.at("point")), wholeNumber(jt.at("seed")),
                                jt.at("why").get<std::string>()});
        s.rerun = wholeNumber(j.at("rerun"));
    } catch (const Error& e) {
        throw Error(where + ": " + e.what());
    } catch (const std::exception& e) {
        throw Error(where + ": not a batch summary (" + oneLine(e.what()) +
                    "); mrloc batch "
                    "--collect writes it again");
    }
    return s;
}

std::string number(double v) { return mrpt::format("%.4g", v); }

}  // namespace

BatchSummary collectBatch(const std::string& dir) {
    BatchSummary s;
    s.plan = batch_dir::readPlan(dir);
    s.trials = s.plan.trialCount();
    const JobLog log = readJobLog(batch_dir::joblog(dir));
    for (const auto& [seq, n] : log.doneCount) s.rerun += n > 1 ? n - 1 : 0;  // jobs
    for (size_t p = 0; p < s.plan.pointCount(); ++p) {
        PointSummary point;
        point.index = p;
        point.name = s.plan.pointName(p);
        point.keys = s.plan.pointKeys(p);
        // figures in the order the trials give them, values in seed order
        std::vector<std::string> order;
        std::map<std::string, std::vector<double>> values;
        std::map<std::string, std::pair<std::string, bool>> unitOf;
        for (unsigned long seed = s.plan.firstSeed; seed <= s.plan.lastSeed; ++seed) {
            const size_t seq = s.plan.jobOf(p, seed);
            const std::string path = batch_dir::record(dir, p, seed);
            if (!fs::exists(fs::symlink_status(path))) {
                const auto problem = log.lastProblem.find(seq);
                if (problem != log.lastProblem.end())
                    s.failed.push_back({p, seed, problem->second + " (no record)"});
                else
                    s.missing.push_back({p, seed, "not run"});
                continue;
            }
            const auto line = common::readJsonFile(path);
            try {
                if (line.contains("error")) {
                    s.failed.push_back({p, seed, line.at("error").get<std::string>()});
                    continue;
                }
                if (wholeNumber(line.at("seed")) != seed ||
                    wholeNumber(line.at("point")) != p)
                    throw Error("its seed or point is not its name's");
                if (s.method.empty()) s.method = line.at("method").get<std::string>();
                ++point.done;
                point.reached += line.at("reached").get<bool>() ? 1 : 0;
                for (const auto& f : line.at("figures")) {
                    const std::string name = f.at("name").get<std::string>();
                    if (!unitOf.count(name)) {
                        if (order.size() >= 1000) throw Error("more than 1,000 figures");
                        order.push_back(name);
                        unitOf[name] = {f.at("unit").get<std::string>(),
                                        f.at("baseline").get<bool>()};
                    }
                    if (f.at("value").is_number()) values[name].push_back(f["value"].get<double>());
                }
            } catch (const Error& e) {
                throw Error(path + ": " + e.what());
            } catch (const std::exception& e) {
                throw Error(path + ": not a trial record (" + oneLine(e.what()) + ")");
            }
        }
        for (const auto& name : order)
            point.figures.push_back(
                statsOf(name, unitOf[name].first, unitOf[name].second, values[name]));
        s.points.push_back(point);
    }
    return s;
}

BatchSummary readSummary(const std::string& path) {
    return summaryFromJson(common::readJsonFile(path), path);
}

void writeSummary(const std::string& dir, const BatchSummary& s) {
    common::writeFileAtomically(batch_dir::summaryText(dir), summaryText(s));
    common::saveJson(batch_dir::summary(dir), toJson(s));
}

std::string summaryText(const BatchSummary& s) {
    std::ostringstream out;
    out << "# mrloc batch: " << common::printable(s.method) << ", " << s.trials << " trials, seeds "
        << s.plan.firstSeed << ".." << s.plan.lastSeed << ", " << s.plan.pointCount()
        << " points\n";
    for (const auto& k : s.plan.sets) out << "# --set " << common::printable(k.text()) << "\n";
    const auto label = [](const FigureStats& f) {
        return common::printable(f.name + (f.baseline ? " (baseline)" : ""));
    };
    int width = 6;  // the names' column, as wide as the longest (at most 80)
    for (const auto& p : s.points)
        for (const auto& f : p.figures)
            width = std::max(width, int(std::min<size_t>(80, label(f).size())));
    for (const auto& p : s.points) {
        out << "\n## " << common::printable(p.name) << ": " << p.done << " of "
            << s.plan.seedCount() << " trials done, " << p.reached << " reached the goal\n"
            << mrpt::format("%-*s %6s %10s %10s %10s %10s %10s %10s %s\n", width, "figure", "count",
                            "mean", "median", "p95", "sd", "min", "max", "unit");
        for (const auto& f : p.figures)
            out << mrpt::format("%-*s %6zu %10s %10s %10s %10s %10s %10s %s\n", width,
                                label(f).c_str(), f.count, number(f.mean).c_str(),
                                number(f.median).c_str(), number(f.p95).c_str(),
                                number(f.sd).c_str(), number(f.min).c_str(), number(f.max).c_str(),
                                common::printable(f.unit).c_str());
    }
    out << "\n" << s.failed.size() << " failed, " << s.missing.size() << " missing";
    if (s.rerun) out << ", " << s.rerun << " done more than once (job log)";
    out << "\n";
    for (const auto* list : {&s.failed, &s.missing})
        for (const auto& t : *list)
            out << (list == &s.failed ? "failed" : "missing") << " point " << t.point << " seed "
                << t.seed << ": " << common::printable(t.why) << "\n";
    return out.str();
}

namespace {

/** One figure's plot: its histogram at a single point; mean (with the sd as error bars),
 *  median and 95th percentile against the grid's points otherwise. */
void plotFigure(const BatchSummary& s, const std::string& name, const std::string& png) {
    const auto unitText = [](const FigureStats& f) {
        return f.unit.empty() ? std::string("count") : f.unit;
    };
    std::ostringstream g;
    g << "set key outside right top\n";
    if (s.points.size() == 1) {
        const auto& f = *std::find_if(s.points[0].figures.begin(), s.points[0].figures.end(),
                                      [&](const FigureStats& x) { return x.name == name; });
        const double width = f.max > f.min ? (f.max - f.min) / double(kBins) : 1;
        g << "$bins << EOD\n";
        for (size_t b = 0; b < f.histogram.size(); ++b)
            g << mrpt::format("%.10g %zu\n", f.min + (double(b) + 0.5) * width, f.histogram[b]);
        // whole trials on the y axis, the bins' edges on the x axis (a tick every bin or
        // every few), a quarter bin between the outer bars and the frame
        const size_t most = *std::max_element(f.histogram.begin(), f.histogram.end());
        const size_t yStep = std::max<size_t>(1, (most + 7) / 8);
        const size_t binsPerTick = (kBins + 7) / 8;
        g << "EOD\n"
          << "set xlabel " << report::gnuplotString(f.name + " (" + unitText(f) + ")") << "\n"
          << mrpt::format(
                 "set xrange [%.10g:%.10g]\nset xtics %.10g, %.10g\nset format x '%%.3g'\n",
                 f.min - 0.25 * width, f.min + (double(kBins) + 0.25) * width, f.min,
                 width * double(binsPerTick))
          << mrpt::format("set ytics %zu\nset yrange [0:%zu]\n", yStep, most + yStep)
          << "set ylabel 'trials'\nset style fill solid 0.5\n"
          << "set boxwidth " << mrpt::format("%.10g", width * 0.9) << "\n"
          << "set arrow from " << mrpt::format("%.10g", f.mean) << ", graph 0 to "
          << mrpt::format("%.10g", f.mean) << ", graph 1 nohead lc rgb pal_vermillion lw 2\n"
          << "set arrow from " << mrpt::format("%.10g", f.p95) << ", graph 0 to "
          << mrpt::format("%.10g", f.p95) << ", graph 1 nohead lc rgb pal_green lw 2 dt 2\n"
          << "plot $bins using 1:2 with boxes lc rgb pal_blue title "
          << report::gnuplotString(mrpt::format("%zu trials", f.count))
          << ", NaN with lines lc rgb pal_vermillion lw 2 title 'mean'"
          << ", NaN with lines lc rgb pal_green lw 2 dt 2 title '95th percentile'\n";
    } else {
        // x: the grid's value when one numeric key makes the grid, else the point's number
        bool numeric = s.plan.grid.size() == 1;
        std::vector<double> xs;
        for (const auto& p : s.points) {
            char* end = nullptr;
            const std::string& v = p.keys.empty() ? std::string() : p.keys.back().value;
            const double x = std::strtod(v.c_str(), &end);
            numeric = numeric && !v.empty() && end && *end == '\0' && std::isfinite(x);
            xs.push_back(x);
        }
        std::string unit;
        g << "$stats << EOD\n";
        for (size_t i = 0; i < s.points.size(); ++i) {
            const auto& fs = s.points[i].figures;
            const auto f = std::find_if(fs.begin(), fs.end(),
                                        [&](const FigureStats& x) { return x.name == name; });
            if (f == fs.end() || f->count == 0) continue;
            unit = unitText(*f);
            g << mrpt::format("%.10g %.10g %.10g %.10g %.10g\n", numeric ? xs[i] : double(i),
                              f->mean, f->sd, f->median, f->p95);
        }
        g << "EOD\n";
        g << "set offsets graph 0.05, graph 0.05, 0, 0\n";  // end points' error bars in view
        if (numeric) {
            g << "set xlabel " << report::gnuplotString(s.plan.grid[0].name()) << "\n";
        } else {
            g << "set xlabel 'grid point (numbered in the table above)'\nset xtics 1\n";
            g << "set xrange [-0.5:" << s.points.size() - 0.5 << "]\n";
        }
        g << "set ylabel " << report::gnuplotString(name + " (" + unit + ")") << "\n"
          << "plot $stats using 1:2:3 with yerrorlines lc rgb pal_blue pt 7 title 'mean +/- sd'"
          << ", $stats using 1:4 with linespoints lc rgb pal_orange pt 5 title 'median'"
          << ", $stats using 1:5 with linespoints lc rgb pal_green pt 9 dt 2 title "
             "'95th percentile'\n";
    }
    report::runGnuplot(g.str(), png);
}

}  // namespace

std::string renderBatchReport(const std::string& dir) {
    const std::string path = batch_dir::summary(dir);
    if (!fs::is_regular_file(fs::symlink_status(path)))
        throw Error(dir + ": a batch without its summary (mrloc batch --collect " + dir +
                    " writes it)");
    const BatchSummary s = readSummary(path);
    using namespace report;
    Html body = heading(1, "mrloc batch: " + s.method);
    body += paragraph(
        mrpt::format("%zu trials: seeds %lu..%lu", s.trials, s.plan.firstSeed, s.plan.lastSeed) +
        std::string(s.points.size() > 1 ? mrpt::format(" at %zu grid points", s.points.size())
                                        : std::string()) +
        mrpt::format("; %zu failed, %zu missing.", s.failed.size(), s.missing.size()));
    if (!s.plan.sets.empty()) {
        std::vector<Html> sets;
        for (const auto& k : s.plan.sets) sets.push_back(code(k.text()));
        body += paragraph("Every trial's keys:") + bulletList(sets);
    }
    // the figures, in the first point's order, one plot each
    std::vector<std::string> names;
    for (const auto& p : s.points)
        for (const auto& f : p.figures)
            if (std::find(names.begin(), names.end(), f.name) == names.end())
                names.push_back(f.name);
    if (names.size() > 100) names.resize(100);
    for (size_t k = 0; k < names.size(); ++k) {
        body += heading(2, names[k]);
        Table t({"grid point", "trials", "mean", "median", "95th percentile", "sd", "min", "max",
                 "unit"});
        for (const auto& p : s.points)
            for (const auto& f : p.figures)
                if (f.name == names[k])
                    t.headedRow(
                        std::to_string(p.index) + ": " + p.name,
                        {std::to_string(f.count), number(f.mean), number(f.median), number(f.p95),
                         number(f.sd), number(f.min), number(f.max), f.unit});
        body += t.html();
        const std::string png = mrpt::format("batch.figure%zu.png", k);
        plotFigure(s, names[k], (fs::path(dir) / png).string());
        body += Figure{png,
                       names[k] + ": " +
                           (s.points.size() == 1
                                ? "histogram over the trials; the mean and 95th percentile as lines"
                                : "mean, median and 95th percentile at each grid point")}
                    .html();
    }
    if (!s.failed.empty() || !s.missing.empty()) {
        body += heading(2, "Failed and missing trials");
        Table t({"", "point", "seed", "why"});
        for (const auto* list : {&s.failed, &s.missing})
            for (const auto& tr : *list)
                t.row({list == &s.failed ? "failed" : "missing", std::to_string(tr.point),
                       std::to_string(tr.seed), tr.why});
        body += t.html();
    }
    const std::string page = (fs::path(dir) / "report.html").string();
    common::writeFileAtomically(page, htmlPage("mrloc batch: " + s.method, body));
    return page;
}

}  // namespace mrloc::app
