#include <mrloc/common/Error.h>
#include <mrloc/common/Progress.h>
#include <mrloc/polymap/Elimination.h>
#include <mrloc/polymap/EliminationExperiment.h>
#include <mrloc/polymap/PaperTables.h>
#include <mrloc/polymap/PolymapLocalizer.h>
#include <mrloc/polymap/ShortestPath.h>
#include <mrloc/polymap/VerificationTour.h>
#include <mrloc/report/Plots.h>
#include <mrloc/report/Report.h>
#include <mrpt/core/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <numeric>

namespace mrloc::polymap {

namespace {

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
            eo.seed = (uint32_t)o.eliminationSeed.value;
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
EliminationSweepFile eliminationSweep(const PolymapOptions& o, double tolerance,
                                      const common::Log& log) {
    EliminationSweepFile sweep;
    const size_t columns = experimentColumns(o, tolerance).size();
    // the work grows with n: count it in map sizes' localizations, weighted by n^2
    double total = 0, done = 0;
    for (const int steps : o.sweepSteps) total += double(steps) * steps * columns * o.sweepStarts;
    common::Progress progress("polymap sweep (Figs. 6-7)", 1000, log);
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
                done += double(steps) * steps * double(o.sweepStarts) / double(count);
                progress.update(size_t(1000 * done / total));
            }
            sweep.rows.push_back(row);
        }
    }
    return sweep;
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
                    " using 1:2 with linespoints lw 2 title " + report::gnuplotString(columns[c]);
        }
        body += std::string("set xlabel 'map vertices n'\n") +
                (travel ? "set ylabel 'mean path d (m)'\nset key outside right top\n"
                        : "set ylabel 'mean time t per localization (ms)'\nset logscale y\n") +
                plot + "\n";
        report::runGnuplot(body,
                           dir + (travel ? "/elimination.fig6.png" : "/elimination.fig7.png"));
    }
}

double meanOf(const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return v.empty() ? 0.0 : s / double(v.size());
}

report::Html number(const char* format, double x) { return report::Html(mrpt::format(format, x)); }

/** The paper's mean over its starts of one of its columns, path (travel) or time. */
double paperMean(int column, bool travel) {
    double sum = 0;
    for (int i = 0; i < paper::kStarts; ++i)
        sum += (travel ? paper::kTravel : paper::kSeconds)[i][column];
    return sum / paper::kStarts;
}

/** Paper 002's Tables 1 (path, `travel`) and 2 (time) with the run's figures: a row per
 *  start, the means and their ratios to column 1, the bounds, and the paper's columns beside
 *  ours where the run is the paper's case. */
class EliminationTables {
 public:
    EliminationTables(const EliminationFile& file, const EliminationTimes& times)
        : file_(file), times_(times), starts_(file.columns.front().travel.size()) {
        for (const auto& c : file.columns) {
            int match = -1;
            for (int k = 0; k < paper::kColumns; ++k)
                if (c.name == paper::kColumnNames[k]) match = k;
            paperColumn_.push_back(starts_ == (size_t)paper::kStarts ? match : -1);
        }
        // the verification tours, when every start has one
        tours_ =
            file.tour.size() == starts_ && std::all_of(file.tour.begin(), file.tour.end(),
                                                       [](double d) { return std::isfinite(d); });
    }

    bool hasTours() const { return tours_; }

    report::Html table(bool travel) const {
        report::Table t(head(travel));
        for (size_t i = 0; i < starts_; ++i) t.row(startRow(i, travel));
        meanRows(t, travel);
        if (travel) fallbackRow(t);
        if (travel) boundRows(t);
        report::Html out = t.html();
        if (travel && paperColumn_[0] >= 0) out += rankingNote();
        return out;
    }

 private:
    bool tourColumn(bool travel) const { return travel && tours_; }

    double ourMean(size_t c, bool travel) const {
        return travel ? meanOf(file_.columns[c].travel) : meanOf(times_.seconds.at(c));
    }

    std::vector<report::Html> head(bool travel) const {
        std::vector<report::Html> head{"start"};
        if (tourColumn(travel)) head.push_back("tour d (m)");
        for (size_t c = 0; c < file_.columns.size(); ++c) {
            head.push_back(file_.columns[c].name + (travel ? " d (m)" : " t (ms)"));
            if (paperColumn_[c] >= 0) head.push_back(travel ? "paper d" : "paper t (s)");
        }
        return head;
    }

    std::vector<report::Html> startRow(size_t i, bool travel) const {
        std::vector<report::Html> cells{std::to_string(i + 1) +
                                        (i == file_.trueStart ? " (run)" : "")};
        if (tourColumn(travel)) cells.push_back(number("%.2f", file_.tour[i]));
        for (size_t c = 0; c < file_.columns.size(); ++c) {
            const auto& col = file_.columns[c];
            const std::string ok =
                (col.survivors[i] == 1 ? "" : " (not localized)") +
                (col.fallbacks[i] > 0 ? mrpt::format(" (%d fell back)", col.fallbacks[i])
                                      : std::string());
            cells.push_back(travel ? mrpt::format("%.2f", col.travel[i]) + ok
                                   : mrpt::format("%.2f", 1e3 * times_.seconds.at(c).at(i)));
            if (paperColumn_[c] >= 0)
                cells.push_back(number(
                    "%.1f", (travel ? paper::kTravel : paper::kSeconds)[i][paperColumn_[c]]));
        }
        return cells;
    }

    /** Averages, and each average over the first column's (the paper's d_i/d_1, t_i/t_1). */
    void meanRows(report::Table& t, bool travel) const {
        std::vector<report::Html> avg{"mean"}, ratio{"ratio to column 1"};
        if (tourColumn(travel)) {
            avg.push_back(number("%.2f", meanOf(file_.tour)));
            ratio.push_back("");
        }
        const double first = ourMean(0, travel);
        const double paperFirst = paperColumn_[0] >= 0 ? paperMean(paperColumn_[0], travel) : 0;
        for (size_t c = 0; c < file_.columns.size(); ++c) {
            const double m = ourMean(c, travel);
            avg.push_back(number("%.2f", travel ? m : 1e3 * m));
            ratio.push_back(number("%.3f", first > 0 ? m / first : 0.0));
            if (paperColumn_[c] >= 0) {
                const double pm = paperMean(paperColumn_[c], travel);
                avg.push_back(number("%.2f", pm));
                ratio.push_back(paperFirst > 0 ? number("%.3f", pm / paperFirst) : report::Html());
            }
        }
        t.row(avg).row(ratio);
    }

    /** The probes each algorithm took beyond its own candidates, over every start (issue
     *  55: the completed candidates, the triangulation's, every algorithm's); only if any. */
    void fallbackRow(report::Table& t) const {
        std::vector<report::Html> cells{"probes beyond the algorithm's own candidates"};
        if (tours_) cells.push_back("");
        int any = 0;
        for (const auto& col : file_.columns) {
            const int n = std::accumulate(col.fallbacks.begin(), col.fallbacks.end(), 0);
            any += n;
            cells.push_back(std::to_string(n));
            if (paperColumn_[&col - file_.columns.data()] >= 0) cells.push_back("");
        }
        if (any > 0) t.row(std::move(cells));
    }

    /** Each algorithm's mean path over the bounds: the first-separation distance, and, start
     *  by start, the verification tour. */
    void boundRows(report::Table& t) const {
        const auto boundRow = [&](const std::string& label, auto value) {
            std::vector<report::Html> cells{label};
            if (tours_) cells.push_back("");
            for (size_t c = 0; c < file_.columns.size(); ++c) {
                cells.push_back(number("%.2f", value(file_.columns[c])));
                if (paperColumn_[c] >= 0) cells.push_back("");
            }
            t.row(std::move(cells));
        };
        if (std::isfinite(file_.bound) && file_.bound > 0)
            boundRow("mean d / first-separation bound",
                     [&](const auto& col) { return meanOf(col.travel) / file_.bound; });
        if (!tours_) return;
        boundRow("mean d / mean tour",
                 [&](const auto& col) { return meanOf(col.travel) / meanOf(file_.tour); });
        boundRow("worst d / tour", [&](const auto& col) {
            double worst = 0;
            for (size_t i = 0; i < starts_; ++i)
                worst = std::max(worst, col.travel[i] / file_.tour[i]);
            return worst;
        });
    }

    /** Where the ranking of the algorithms by path is not the paper's, a paragraph saying so
     *  under the table rather than leave the reader to find it in the ratios. */
    report::Html rankingNote() const {
        const double first = ourMean(0, true);
        const double paperFirst = paperMean(paperColumn_[0], true);
        int ourLow = -1, ourHigh = -1, paperLow = -1, paperHigh = -1;
        std::vector<double> ours(file_.columns.size()), theirs(file_.columns.size());
        for (size_t c = 0; c < file_.columns.size(); ++c) {
            if (paperColumn_[c] < 0) continue;
            ours[c] = meanOf(file_.columns[c].travel) / first;
            theirs[c] = paperMean(paperColumn_[c], true) / paperFirst;
            const auto pick = [&](int& best, const std::vector<double>& v, bool low) {
                if (best < 0 || (low ? v[c] < v[best] : v[c] > v[best])) best = int(c);
            };
            pick(ourLow, ours, true), pick(ourHigh, ours, false);
            pick(paperLow, theirs, true), pick(paperHigh, theirs, false);
        }
        const auto name = [&](int c) { return file_.columns[size_t(c)].name; };
        std::string differs;
        if (ourLow != paperLow)
            differs += mrpt::format(
                "the shortest mean path here is the %s algorithm's (%.3f of column 1), the "
                "paper's the %s algorithm's (%.3f)",
                name(ourLow).c_str(), ours[ourLow], name(paperLow).c_str(), theirs[paperLow]);
        if (ourHigh != paperHigh)
            differs += std::string(differs.empty() ? "" : "; ") +
                       mrpt::format(
                           "the longest here is the %s algorithm's (%.3f), the "
                           "paper's the %s algorithm's (%.3f)",
                           name(ourHigh).c_str(), ours[ourHigh], name(paperHigh).c_str(),
                           theirs[paperHigh]);
        if (differs.empty()) return {};
        return report::paragraph(report::bold("Not the paper's order:") + " " + differs + ". " +
                                 firstBranching() + " (doc/polymap.md discusses why).");
    }

    /** Where each algorithm's elimination from the run's start first departs from column 1's
     *  (a probe leaving another number of hypotheses): the probe each chose there and what it
     *  left (a probe that leaves more to eliminate farther on makes a path longer). */
    std::string firstBranching() const {
        const auto& first = file_.columns.front();
        const auto probeAt = [](const EliminationFile::Column& col, size_t k) {
            if (k >= col.stops.size()) return std::string("no probe");
            const std::string left = k < col.stopsLeft.size() && col.stopsLeft[k] >= 0
                                         ? mrpt::format(", leaving %d hypothes%s", col.stopsLeft[k],
                                                        col.stopsLeft[k] == 1 ? "is" : "es")
                                         : std::string();
            return mrpt::format("(%.2f, %.2f) m", col.stops[k].x, col.stops[k].y) + left;
        };
        std::string out;
        for (size_t c = 1; c < file_.columns.size(); ++c) {
            const auto& col = file_.columns[c];
            size_t k = 0;
            // the same count after each probe: the same branch of the elimination (the probes
            // themselves differ by a few centimetres between the candidate sets)
            while (k < col.stopsLeft.size() && k < first.stopsLeft.size() &&
                   col.stopsLeft[k] == first.stopsLeft[k])
                ++k;
            if (k == col.stops.size() && k == first.stops.size()) continue;  // the same branch
            out += std::string(out.empty() ? "" : "; ") +
                   mrpt::format("%s at probe %zu: %s, where %s took %s", col.name.c_str(), k + 1,
                                probeAt(col, k).c_str(), first.name.c_str(),
                                probeAt(first, k).c_str());
        }
        if (out.empty()) return "From the run's start every algorithm takes the same probes.";
        return mrpt::format("From the run's start (start %zu) the algorithms first part from %s ",
                            file_.trueStart + 1, first.name.c_str()) +
               "as follows: " + out + ".";
    }

    const EliminationFile& file_;
    const EliminationTimes& times_;
    size_t starts_;
    std::vector<int> paperColumn_;  ///< ours -> the paper's, -1 if it has none
    bool tours_ = false;
};

/** The experiment's tables, ours beside the paper's where the run is the paper's case. */
report::Html eliminationTables(const EliminationFile& file, const EliminationTimes& times) {
    const EliminationTables tables(file, times);
    return report::heading(3, "Elimination: path length per start (paper 002 Table 1)") +
           report::paragraph(
               "Every hypothesis in turn the truth; closed loop with exact views; d is the "
               "robot's travel in metres. The paper's map units are not stated: compare the "
               "ratios. Two bounds (doc/polymap.md): the first-separation distance, " +
               (std::isfinite(file.bound) ? mrpt::format("%.2f m", file.bound)
                                          : std::string("none found")) +
               ", the shortest travel to any point where the hypotheses' views differ, which no "
               "strategy beats from any start; and, start by start, the verification tour "
               "(Dudek, Romanik and Whitesides 1998): the least travel that rules out every "
               "other hypothesis with the truth known, found exactly by search over every "
               "algorithm's candidates and probes" +
               (tables.hasTours() ? std::string()
                                  : " (not computed: more than " +
                                        std::to_string(kMaxTourHypotheses) + " hypotheses)") +
               ". Paper 002 reports no bound.") +
           tables.table(true) +
           report::heading(3, "Elimination: run time per start (paper 002 Table 2)") +
           report::paragraph(
               "One whole localization, this machine, one core, milliseconds; the "
               "paper's in seconds (Visual C++ 2010).") +
           tables.table(false);
}

/** Figs. 6-7 and their table, if the run swept. */
report::Html sweepSection(const std::string& dir) {
    if (!std::filesystem::exists(EliminationSweepFile::path(dir))) return {};
    const auto sweep = EliminationSweepFile::read(dir);
    plotSweep(sweep, dir);
    report::Table table({"n", "k", "algorithm", "mean d (m)", "mean t (ms)", "not localized"});
    for (const auto& r : sweep.rows)
        table.row({std::to_string(r.n), std::to_string(r.k), r.column,
                   mrpt::format("%.2f", r.meanTravel), mrpt::format("%.2f", 1e3 * r.meanSeconds),
                   std::to_string(r.notLocalized)});
    return report::heading(3, "Elimination against map size (paper 002 Figs. 6-7)") +
           report::paragraph(
               "Steps maps of the run's shape, n vertices, their sites the hypotheses; mean "
               "over up to " +
               std::to_string(sweep.rows.empty() ? 0 : sweep.rows.front().starts) +
               " starts per map, evenly spread.") +
           report::Figure{"elimination.fig6.png",
                          "mean travel against n for each algorithm: lower is better"}
               .html() +
           report::Figure{"elimination.fig7.png",
                          "mean computing time against n for each algorithm"}
               .html() +
           table.html();
}

}  // namespace

std::vector<method::WorkItem> polymapWork(const PolymapLocalizer& localizer,
                                          const sim::ScenarioConfig* scenario) {
    const PolymapOptions& o = localizer.options();
    if (!localizer.hasPolygon()) return {};  // a grid map: nothing simulated, no experiment
    // Measured (doc/errors.md, "Work") on the steps map of n = 148 vertices: a scan costs
    // 0.4 ms and 1 us per ray, and the rawlog keeps 3.5 bytes per ray (gzip); the randomized
    // algorithm's column of the experiment 1 ms per random point, with the map's 12
    // hypotheses. Both are taken to grow with n.
    constexpr double kSecondsPerScan = 4e-4, kSecondsPerRay = 1e-6, kBytesPerRay = 3.5;
    constexpr double kSecondsPerRandomPoint = 1e-3;
    // Every algorithm's localization from one start: 8 ms on the n = 148 map, the mean over
    // the five columns of polymap_sweep.ini, growing as n^2.15 (0.49 s at n = 1012).
    constexpr double kSecondsPerStart = 8e-3, kStartExponent = 2.15;
    const auto perStart = [&](double vertices) {
        return kSecondsPerStart * std::pow(vertices / 148, kStartExponent);
    };
    const double n = double(localizer.generatedMap().polygon.size()),
                 mapFactor = std::max(1.0, n / 148);
    std::vector<method::WorkItem> out;
    // what sets the map's vertices, in the keys' words
    const char* vertices = !o.mapFile.empty()       ? "the map's"
                           : o.generator == "steps" ? "steps x branches_per_step"
                                                    : "rooms x room_steps";
    const double columns = double(experimentColumns(o, 0).size());  // 0 without elimination
    if (columns > 0) {
        // Tables 1-2: every hypothesis a start, every column; the hypotheses are the map's
        // sites when it was generated, else taken as the steps maps' n / 12
        const double starts = localizer.generatedMap().sites.empty()
                                  ? std::max(1.0, n / 12)
                                  : double(localizer.generatedMap().sites.size());
        method::WorkItem w;
        w.what = mrpt::format("the experiment's %.0f localizations", starts * columns);
        w.keys = mrpt::format(
            "[polymap] elimination (and random_points) x hypotheses, growing with the vertices "
            "(%s)",
            vertices);
        w.seconds = starts * columns * perStart(n);
        out.push_back(w);
    }
    if (columns > 0 && !o.sweepSteps.empty()) {
        double seconds = 0, runs = 0;
        for (const int steps : o.sweepSteps) {
            StepsMapOptions so = o.steps;
            so.steps = steps;
            const auto map = stepsMap(so);
            const double count = double(std::min(map.sites.size(), size_t(o.sweepStarts)));
            runs += count * columns;
            seconds += count * columns * perStart(double(map.polygon.size()));
        }
        method::WorkItem w;
        w.what = mrpt::format("the sweep's %.0f localizations", runs);
        w.keys = "[polymap] sweep_steps x sweep_starts x elimination";
        w.seconds = seconds;
        out.push_back(w);
    }
    if (scenario && o.scanRate > 0) {
        const double scans = scenario->scenario.duration * o.scanRate;
        method::WorkItem w;
        w.what = mrpt::format("%.0f scans of %d rays", scans, o.scanRays);
        w.keys = mrpt::format(
            "[polymap] scan_rate x scan_rays, the vertices (%s), x [scenario] duration", vertices);
        w.seconds = scans * (kSecondsPerScan + double(o.scanRays) * kSecondsPerRay) * mapFactor;
        w.bytes = scans * double(o.scanRays) * kBytesPerRay;
        w.simulation = true;
        out.push_back(w);
    }
    if (std::find(o.elimination.begin(), o.elimination.end(), ProbeStrategy::Randomized) !=
        o.elimination.end()) {
        double points = 0;
        for (const int x : o.randomPoints) points += x;
        method::WorkItem w;
        w.what = "the experiment's randomized columns";
        w.keys = "[polymap] random_points";
        w.seconds = points * kSecondsPerRandomPoint * mapFactor *
                    double(1 + o.sweepSteps.size() * size_t(o.sweepStarts) / 12);
        out.push_back(w);
    }
    return out;
}

/** Seed 002's experiment (Tables 1-2) on the run's hypotheses: every hypothesis in turn the
 *  truth, every configured algorithm, closed loop with exact views, deciding with the
 *  tolerance the hypotheses were generated with; then the sweep over n, if asked. */
std::vector<std::string> eliminationExperiment(const method::ExperimentOf<PolymapLocalizer>& in) {
    const auto& loc = in.localizer;
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
    std::vector<size_t> all(positions.size());  // every hypothesis live
    for (size_t i = 0; i < all.size(); ++i) all[i] = i;
    if (all.size() > 1)  // the same for every start
        if (const auto d =
                Eliminator(P, positions, columns.front().second).firstSeparation(all, {0, 0}))
            file.bound = *d;
    const TPoint2D at = positions[file.trueStart];
    // The verification tours' sites: every column's first candidates and its probes.
    std::vector<TPoint2D> firstCandidates;
    std::vector<std::vector<TPoint2D>> probesFrom(positions.size());
    common::Progress progress("polymap experiment (Tables 1-2)", columns.size() * positions.size(),
                              in.log);
    for (const auto& [name, eo] : columns) {
        const Eliminator eliminator(P, positions, eo);
        EliminationFile::Column col;
        col.name = name;
        if (all.size() > 1) {  // what the first step chose from, for the picture
            const auto [candidates, oi] = eliminator.candidatesAndRegion(all);
            for (const auto& c : candidates) col.candidates.push_back(at + c);
            firstCandidates.insert(firstCandidates.end(), candidates.begin(), candidates.end());
            if (file.overlay.empty())
                for (const auto& v : oi.outer) file.overlay.push_back(at + v);
        }
        times.seconds.emplace_back();
        for (size_t start = 0; start < positions.size(); ++start) {
            progress.update(file.columns.size() * positions.size() + start);
            const auto [run, seconds] = timedElimination(eliminator, start);
            times.seconds.back().push_back(seconds);
            col.travel.push_back(run.travel);
            col.probes.push_back((int)run.probes.size());
            col.survivors.push_back((int)run.survivors.size());
            col.fallbacks.push_back(
                (int)std::count_if(run.probes.begin(), run.probes.end(),
                                   [](const Probe& p) { return p.source != ProbeSource::Own; }));
            for (const auto& probe : run.probes) probesFrom[start].push_back(probe.at);
            if (start != file.trueStart) continue;
            col.route.push_back(positions[start]);
            for (size_t p = 0; p < run.probes.size(); ++p) {
                const auto& probe = run.probes[p];
                for (size_t k = 1; k < probe.path.points.size(); ++k)
                    col.route.push_back(positions[start] + probe.path.points[k]);
                col.stops.push_back(positions[start] + probe.at);
                col.stopsLeft.push_back((int)run.leftAfter[p]);
            }
        }
        file.columns.push_back(std::move(col));
    }
    progress.finish();
    if (all.size() > 1 && all.size() <= kMaxTourHypotheses) {
        const Eliminator eliminator(P, positions, columns.front().second);
        const auto tours = verificationTours(eliminator, firstCandidates, probesFrom);
        for (size_t start = 0; start < tours.size(); ++start) {
            const auto& tour = tours[start];
            file.tour.push_back(tour ? tour->length : std::nan(""));
            file.tourProbes.push_back(tour ? (int)tour->probes.size() : 0);
            if (!tour || start != file.trueStart) continue;
            const ShortestPaths paths(eliminator.triangulation());
            file.trueTourRoute.push_back(at);
            for (size_t k = 0; k < tour->probes.size(); ++k) {
                const TPoint2D from = k == 0 ? at : at + tour->probes[k - 1];
                const auto leg = paths.path(from, at + tour->probes[k]).points;
                file.trueTourRoute.insert(file.trueTourRoute.end(), leg.begin() + 1, leg.end());
                file.trueTour.push_back(at + tour->probes[k]);
            }
        }
    }
    file.write(in.outDir);
    times.write(in.outDir);
    std::vector<std::string> written{EliminationFile::path(in.outDir),
                                     EliminationTimes::path(in.outDir)};
    if (!o.sweepSteps.empty()) {
        eliminationSweep(o, r.tolerance, in.log).write(in.outDir);
        written.push_back(EliminationSweepFile::path(in.outDir));
    }
    return written;
}

report::Html eliminationSection(const std::string& dir, const EliminationFile& file) {
    report::Html out;
    if (!file.columns.empty()) out += eliminationTables(file, EliminationTimes::read(dir));
    return out + sweepSection(dir);
}

}  // namespace mrloc::polymap
