// The beacon study in the run report: tables and gnuplot pictures from beacons.study.json.
#include <mrloc/beacons/BeaconStudyReport.h>
#include <mrloc/beacons/PaperValues.h>
#include <mrloc/report/Plots.h>
#include <mrpt/core/format.h>

#include <algorithm>
#include <filesystem>
#include <map>

namespace mrloc::beacons {

using report::Html;

namespace {

std::string mm(double m) { return mrpt::format("%.1f", 1000 * m); }
std::string pct(double r) { return mrpt::format("%.0f", 100 * r); }

/** "mean / max (reception %)" of one test point. */
std::string pointCell(const PointStats& p) {
    if (p.fixes == 0) return mrpt::format("no fix (0 of %d)", p.trials);
    return mm(p.meanError) + " / " + mm(p.maxError) + " (" + pct(p.reception()) + " %)";
}

/** Over a row's points: mean of every fix, the largest error, the lowest reception. */
struct Overall {
    double mean = 0, max = 0, minReception = 1;
    int fixes = 0;
};
Overall overallOf(const std::vector<PointStats>& points) {
    Overall o;
    double sum = 0;
    for (const auto& p : points) {
        sum += p.meanError * p.fixes;
        o.fixes += p.fixes;
        o.max = std::max(o.max, p.maxError);
        o.minReception = std::min(o.minReception, p.reception());
    }
    o.mean = o.fixes ? sum / o.fixes : 0.0;
    return o;
}

Html choicesSection(const BeaconStudyFile& f) {
    if (f.choices.empty()) return {};
    Html out = report::heading(3, "Method choices at this run's test points");
    out += report::paragraph(mrpt::format(
        "%d trials per test point (paper 001: 10), each choice alone and in turn; each cell is the "
        "horizontal error's mean / max in mm and the share of trials with a fix. The link model "
        "is the one calibrated on paper 001 Table 3, not tuned to this room. Paper 001 "
        "(section 5.3, Fig. 11, active beacons): average error over %.0f mm, maximal over %.0f "
        "mm; its next goal: maximal under 50 mm.",
        f.choiceTrials, 1000 * paper::kActiveMeanErrorM, 1000 * paper::kActiveMaxErrorM));
    std::vector<Html> head{"heads", "receiver's method"};
    for (const auto& p : f.choices.front().points)
        head.push_back(mrpt::format("(%.2f, %.2f) m", p.at.x, p.at.y));
    head.insert(head.end(), {"mean (mm)", "max (mm)", "lowest reception (%)"});
    report::Table table(head);
    for (const auto& c : f.choices) {
        std::vector<Html> cells{c.aiming, c.configured ? report::bold(c.method) : Html(c.method)};
        for (const auto& p : c.points) cells.push_back(pointCell(p));
        const auto o = overallOf(c.points);
        cells.push_back(o.fixes ? Html(mm(o.mean)) : Html("none"));
        cells.push_back(o.fixes ? Html(mm(o.max)) : Html("none"));
        cells.push_back(pct(o.minReception));
        table.row(cells);
    }
    out += table.html();
    // fixed against active, the run's own method: seed 001 says "reduced by a half"
    const auto find = [&](const char* aimingStart) -> const StudyChoiceRow* {
        for (const auto& c : f.choices)
            if (c.configured && c.aiming.rfind(aimingStart, 0) == 0) return &c;
        return nullptr;
    };
    const StudyChoiceRow* active = find("active");
    std::vector<Html> lines;
    for (const auto& c : f.choices) {
        if (!active || !c.configured || c.aiming.rfind("fixed", 0) != 0) continue;
        size_t covered = 0;
        for (const auto& p : c.points) covered += p.reception() >= f.criteria.reception;
        const auto a = overallOf(active->points), x = overallOf(c.points);
        std::string line = c.aiming + ": fixes at " + std::to_string(covered) + " of " +
                           std::to_string(c.points.size()) + " test points (reception at least " +
                           pct(f.criteria.reception) + " %)";
        if (x.fixes && covered == c.points.size())
            line += mrpt::format("; active / fixed: %.2f of the mean error, %.2f of the max",
                                 a.mean / x.mean, a.max / x.max);
        else if (x.fixes)
            line += mrpt::format("; where it fixes, mean %s mm, max %s mm", mm(x.mean).c_str(),
                                 mm(x.max).c_str());
        lines.push_back(line + " (paper 001: active halves both).");
    }
    if (!lines.empty()) out += report::bulletList(lines);
    return out;
}

/** One grid part's rows: value -> variant -> row, and the variants in first-seen order. */
struct GridPart {
    std::map<double, std::map<std::string, const StudyGridRow*>> byValue;
    std::vector<std::string> variants;
};
GridPart gridPart(const BeaconStudyFile& f, const std::string& part) {
    GridPart out;
    for (const auto& g : f.grids) {
        if (g.part != part) continue;
        out.byValue[g.value][g.variant] = &g;
        if (std::find(out.variants.begin(), out.variants.end(), g.variant) == out.variants.end())
            out.variants.push_back(g.variant);
    }
    return out;
}

std::string gridCell(const StudyGridRow* g) {
    if (!g) return "";
    return pct(g->minReception) + " % / " + mm(g->meanError) + " / " + mm(g->maxError) + " / " +
           std::to_string(g->pointsCovered) + " of " + std::to_string(g->points) +
           (g->covers ? " (covered)" : "");
}

/** Error (mm, log scale) where fixed, and the share of test points covered and the lowest
 *  reception (%), against the part's value; one colour per variant. */
Html gridPlot(const GridPart& part, const std::string& dir, const std::string& png,
              const std::string& xLabel, const std::string& caption, double bound) {
    const char* colours[] = {"pal_vermillion", "pal_blue", "pal_green", "pal_purple"};
    std::string data, errors, reception;
    for (size_t v = 0; v < part.variants.size(); ++v) {
        std::vector<std::pair<double, double>> mean, max, rec, covered;
        for (const auto& [x, rows] : part.byValue) {
            const auto it = rows.find(part.variants[v]);
            if (it == rows.end()) continue;
            const StudyGridRow& g = *it->second;
            rec.emplace_back(x, 100 * g.minReception);
            covered.emplace_back(x, g.points ? 100.0 * g.pointsCovered / g.points : 0.0);
            if (g.meanError > 0)
                mean.emplace_back(x, 1000 * g.meanError), max.emplace_back(x, 1000 * g.maxError);
        }
        const std::string n = std::to_string(v), colour = colours[v % 4];
        const std::string name = report::gnuplotString(part.variants[v]);
        data += report::dataBlock("m" + n, mean) + report::dataBlock("x" + n, max) +
                report::dataBlock("r" + n, rec) + report::dataBlock("c" + n, covered);
        if (!mean.empty())
            errors += "$m" + n + " using 1:2 with linespoints lw 2 pt 7 lc rgb " + colour +
                      " title " + report::gnuplotString(part.variants[v] + ": mean") + ", $x" + n +
                      " using 1:2 with linespoints lw 2 pt 6 dt 2 lc rgb " + colour + " title " +
                      report::gnuplotString(part.variants[v] + ": max") + ", ";
        reception += "$c" + n + " using 1:2 with linespoints lw 2 pt 7 lc rgb " + colour +
                     " title " + report::gnuplotString(part.variants[v] + ": points covered") +
                     ", $r" + n + " using 1:2 with linespoints lw 2 pt 6 dt 2 lc rgb " + colour +
                     " title " + report::gnuplotString(part.variants[v] + ": lowest reception") +
                     ", ";
    }
    if (reception.empty()) return {};
    // both panels share the plot area's margins, so that their x axes line up
    std::string body = data +
                       "set multiplot layout 2,1\nset lmargin at screen 0.08\nset rmargin at "
                       "screen 0.56\nset key outside right top\nset xlabel " +
                       report::gnuplotString(xLabel) +
                       "\nset offsets graph 0.04, graph 0.04, 0, 0\n";
    if (!errors.empty())
        body +=
            "set ylabel 'horizontal error (mm)'\nset logscale y\nset title 'error where the "
            "trials gave a fix'\nplot " +
            errors +
            mrpt::format("%g with lines dt 3 lw 2 lc rgb pal_grey title 'bound %.0f mm'\n",
                         1000 * bound, 1000 * bound) +
            "unset logscale y\n";
    body +=
        "set ylabel 'share (%)'\nset yrange [0:105]\nset title 'test points covered, and "
        "the lowest reception over them'\nplot " +
        reception +
        "90 with lines dt 3 lw 2 lc rgb pal_grey title 'paper 001: 90 % reception'\nunset "
        "multiplot\n";
    report::runGnuplot(body, dir + "/" + png, "1200,800");
    return report::Figure{png, caption}.html();
}

Html gridSection(const BeaconStudyFile& f, const std::string& dir, const std::string& part,
                 const std::string& title, const std::string& what, const std::string& xLabel,
                 const std::string& png) {
    const auto rows = gridPart(f, part);
    if (rows.byValue.empty()) return {};
    Html out = report::heading(3, title);
    out += report::paragraph(what +
                             " Each cell: lowest reception over the test points / mean / "
                             "max error (mm) / test points covered.");
    std::vector<Html> head{xLabel};
    head.insert(head.end(), rows.variants.begin(), rows.variants.end());
    report::Table table(head);
    for (const auto& [v, byVariant] : rows.byValue) {
        std::vector<Html> cells{mrpt::format("%g", v)};
        for (const auto& name : rows.variants) {
            const auto it = byVariant.find(name);
            cells.push_back(gridCell(it == byVariant.end() ? nullptr : it->second));
        }
        table.row(cells);
    }
    out += table.html();
    if (part == "coverage") {  // the largest room each covers, beside seed 001's goal
        std::vector<Html> lines;
        for (const auto& name : rows.variants) {
            double largest = 0;
            for (const auto& [v, byVariant] : rows.byValue)
                if (const auto it = byVariant.find(name);
                    it != byVariant.end() && it->second->covers)
                    largest = std::max(largest, v);
            lines.push_back(name + ": " +
                            (largest > 0 ? mrpt::format("covers square rooms up to %g m", largest)
                                         : std::string("covers none of these rooms")) +
                            mrpt::format(" (paper 001's goal: over %g m x %g m)",
                                         paper::kGoalCoverageSide, paper::kGoalCoverageSide));
        }
        out += report::bulletList(lines);
    }
    out += gridPlot(rows, dir, png, xLabel, title, f.criteria.errorBound);
    return out;
}

Html countSection(const BeaconStudyFile& f, const std::string& dir) {
    if (f.counts.empty()) return {};
    Html out = report::heading(
        3, "The fewest beacons that cover a room (paper 001: active needs about half)");
    out += report::paragraph(
        "Square rooms; beacons spread by a centroidal Voronoi layout; a room is covered when "
        "every test point gets a fix in at least " +
        pct(f.criteria.reception) + " % of its trials with every error under " +
        mm(f.criteria.errorBound) +
        " mm. Fixed heads point straight down (the layout's own design); active heads turn to "
        "the receiver.");
    std::map<double, std::pair<const StudyCountRow*, const StudyCountRow*>> by;
    for (const auto& c : f.counts)
        (c.aiming.rfind("active", 0) == 0 ? by[c.size].second : by[c.size].first) = &c;
    report::Table table(
        {"room (m)", "fixed: fewest beacons", "active: fewest beacons",
         mrpt::format("active / fixed (paper 001: about %.1f)", paper::kActiveBeaconShare),
         "fixed: mean / max (mm)", "active: mean / max (mm)"});
    std::vector<std::pair<double, double>> fx, ac;
    const auto count = [](const StudyCountRow* c) {
        return !c          ? std::string()
               : c->fewest ? std::to_string(c->fewest)
                           : std::string("none up to count_max");
    };
    for (const auto& [size, p] : by) {
        std::string ratio = "";
        if (p.first && p.second && p.first->fewest && p.second->fewest)
            ratio = mrpt::format("%.2f", double(p.second->fewest) / p.first->fewest);
        const auto errors = [](const StudyCountRow* c) {
            return c && c->fewest ? mm(c->meanError) + " / " + mm(c->maxError) : std::string();
        };
        table.row({mrpt::format("%g x %g", size, size), count(p.first), count(p.second), ratio,
                   errors(p.first), errors(p.second)});
        if (p.first && p.first->fewest) fx.emplace_back(size, p.first->fewest);
        if (p.second && p.second->fewest) ac.emplace_back(size, p.second->fewest);
    }
    out += table.html();
    if (!fx.empty() || !ac.empty()) {
        report::runGnuplot(
            report::dataBlock("f", fx) + report::dataBlock("a", ac) +
                "set xlabel 'side of the square room (m)'\nset ylabel 'fewest beacons that cover "
                "it'\n"
                "set yrange [0:*]\nset offsets graph 0.04, graph 0.04, graph 0.08, 0\nset key "
                "outside right top\n"
                "plot $f using 1:2 with linespoints lw 2 pt 7 lc rgb pal_vermillion title 'fixed "
                "heads "
                "(straight down)', "
                "$a using 1:2 with linespoints lw 2 pt 5 lc rgb pal_blue title 'active heads'\n",
            dir + "/beacons.study.count.png", "800,420");
        out += report::Figure{"beacons.study.count.png",
                              "beacons needed against the room's size: active heads should need "
                              "fewer than fixed ones"}
                   .html();
    }
    return out;
}

Html agentsSection(const BeaconStudyFile& f, const std::string& dir) {
    if (f.agents.empty()) return {};
    Html out = report::heading(3, "Agents served on one channel or at once");
    out += report::paragraph(
        "Agents stand at random places at least 1 m apart; per epoch the RF beacon serves the "
        "longest waiting agent on a shared channel, or, simultaneously, every agent it can give "
        "its own loudest beacons whose bursts the link predicts inaudible at the other served "
        "receivers (paper 001 section 1: heads turned to different agents). Bursts of one slot "
        "fly at once; a receiver triggers on the earliest it hears, so an interfering burst "
        "that arrives first becomes a wrong range (counted below).");
    report::Table table({"agents", "heads", "channel", "fixes per s per agent: mean / least",
                         "agents per epoch", "mean / max error (mm)", "interfered shots",
                         "fixes over the bound"});
    std::map<std::string, std::vector<std::pair<double, double>>> curves;
    for (const auto& a : f.agents) {
        table.row({std::to_string(a.agents), a.aiming, channelName(a.channel),
                   mrpt::format("%.2f / %.2f", a.meanRate, a.minRate),
                   mrpt::format("%.2f", a.meanAgentsPerEpoch),
                   a.fixes ? mm(a.meanError) + " / " + mm(a.maxError) : std::string("no fix"),
                   mrpt::format("%zu of %zu", a.interfered, a.shots),
                   mrpt::format("%zu of %zu", a.overBound, a.fixes)});
        curves[(a.aiming.rfind("active", 0) == 0 ? "active, " : "fixed, ") +
               std::string(channelName(a.channel))]
            .emplace_back(a.agents, a.meanRate);
    }
    out += table.html();
    std::string body, plot = "plot ";
    int i = 0;
    const char* colours[] = {"pal_blue", "pal_green", "pal_purple", "pal_vermillion", "pal_orange"};
    for (const auto& [name, xy] : curves) {
        body += report::dataBlock("c" + std::to_string(i), xy);
        plot += (i ? ", " : "") + std::string("$c") + std::to_string(i) +
                " using 1:2 with linespoints lw 2 pt 7 lc rgb " + colours[i % 5] + " title " +
                report::gnuplotString(name);
        ++i;
    }
    report::runGnuplot(
        body +
            "set xlabel 'agents'\nset ylabel 'fixes per second per agent (Hz)'\n"
            "set logscale x 2\nset yrange [0:*]\nset offsets graph 0.04, graph 0.04, 0, 0\n"
            "set key outside right top\n" +
            plot + "\n",
        dir + "/beacons.study.agents.png", "1000,450");
    out += report::Figure{"beacons.study.agents.png",
                          "ranging rate each agent gets as more agents share the beacons"}
               .html();
    return out;
}

}  // namespace

Html studySection(const std::string& dir) {
    if (!std::filesystem::exists(BeaconStudyFile::path(dir))) return {};
    const auto f = BeaconStudyFile::read(dir);
    Html out = report::heading(2, "Beacon study: coverage, beacon count, sweeps and agents");
    out += report::paragraph(mrpt::format(
        "Monte Carlo of the beacon system's trials with the simulator's shot physics (the "
        "[ultrasonic] link as calibrated on paper 001 Table 3 and the [sensors] noise, neither "
        "tuned here) and this run's receiver method (%s). %d trials per test point; test "
        "points on a grid; beacons fired per trial: %s. A room is covered when every point is "
        "fixed in at least %s %% of its trials (paper 001's 90 %%) with every error under %s mm "
        "(its next goal).",
        f.method.c_str(), f.trials, f.beaconsPerFix.c_str(), pct(f.criteria.reception).c_str(),
        mm(f.criteria.errorBound).c_str()));
    out += choicesSection(f);
    out +=
        gridSection(f, dir, "coverage", "One beacon set over growing rooms (paper 001: 6 m x 6 m)",
                    "One set of beacons (paper 001's section is 3) spread over square rooms.",
                    "side of the square room (m)", "beacons.study.coverage.png");
    out += countSection(f, dir);
    out += gridSection(f, dir, "beam", "Error against the transducer's beam angle",
                       mrpt::format("This run's room (%.1f x %.1f m) and beacons; the beam "
                                    "angle (full width at -6 dB) of another transducer, which "
                                    "the receiver's delay model knows.",
                                    f.roomX, f.roomY),
                       "beam angle (deg)", "beacons.study.beam.png");
    out += gridSection(f, dir, "beacons", "Error against the number of beacons",
                       mrpt::format("This run's room (%.1f x %.1f m), beacons spread by a "
                                    "centroidal Voronoi layout.",
                                    f.roomX, f.roomY),
                       "beacons", "beacons.study.count_sweep.png");
    out += gridSection(f, dir, "speed", "Error against the robot's speed",
                       "This run's room and beacons; the receiver moves during the trial's "
                       "shots, the fix is compared with where it is at the last one (no motion "
                       "compensation: the fixes mode).",
                       "robot speed (m/s)", "beacons.study.speed.png");
    out += agentsSection(f, dir);
    return out;
}

}  // namespace mrloc::beacons
