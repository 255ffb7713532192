#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/DataFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/polymap/PolymapFiles.h>

#include <cmath>
#include <sstream>

namespace mrloc::polymap {

using common::formatNumber;

std::string HypothesesFile::path(const std::string& dir, const std::string& robot) {
    return dir + "/hypotheses." + robot + ".txt";
}

void HypothesesFile::write(const std::string& dir, const std::string& robot) const {
    std::ostringstream out;
    out << "# polymap result of robot " << robot << " (paper 002, hypothesis generation)\n"
        << "# time t: of the scan (s)\n# V x y: a vertex of the sensed visibility polygon, "
           "robot frame (m)\n"
        << "# H x y translation_x translation_y mismatch: a hypothesis (m)\n"
        << "t " << formatNumber(time) << "\n";
    for (const auto& p : sensed)
        out << "V " << formatNumber(p.x) << " " << formatNumber(p.y) << "\n";
    for (const auto& h : hypotheses)
        out << "H " << formatNumber(h.point.x) << " " << formatNumber(h.point.y) << " "
            << formatNumber(h.translation.x) << " " << formatNumber(h.translation.y) << " "
            << formatNumber(h.mismatch) << "\n";
    common::writeFileAtomically(path(dir, robot), out.str());
}

HypothesesFile HypothesesFile::read(const std::string& dir, const std::string& robot) {
    HypothesesFile f;
    for (const auto& line : common::readDataLines(path(dir, robot))) {
        const std::string& kind = line.fields[0];
        if (kind == "t") {
            line.expectFields(2);
            f.time = line.number(1);
        } else if (kind == "V") {
            line.expectFields(3);
            f.sensed.push_back({line.number(1), line.number(2)});
        } else if (kind == "H") {
            line.expectFields(6);
            Hypothesis h;
            h.point = {line.number(1), line.number(2)};
            h.translation = {line.number(3), line.number(4)};
            h.mismatch = line.number(5);
            f.hypotheses.push_back(h);
        } else {
            throw Error(line.where + ": expected a line starting with t, V or H");
        }
    }
    return f;
}

void EliminationFile::write(const std::string& dir) const {
    std::ostringstream out;
    out << "# polymap elimination experiment (paper 002 Tables 1-2), exact views\n"
        << "# true_start i: the run's true start, index into H (0-based)\n"
        << "# C column name: an algorithm (cells, randomized:X, triangulation, windows)\n"
        << "# R column start travel probes survivors fallbacks: one localization (m;\n"
        << "#   fallbacks: probes beyond the algorithm's own candidates)\n"
        << "# P column x y: the route from the true start; Q column x y left: its probes (m)\n"
        << "#   and the hypotheses live after each\n"
        << "# K column x y: the first step's candidates; O x y: OI at the true start (m)\n"
        << "# bound d: the first-separation distance, a bound on every strategy's travel (m)\n"
        << "# tour start d probes: the verification tour from that start (m; nan: none)\n"
        << "# tour_probe x y, tour_path x y: the true start's tour, its probes and path (m)\n"
        << "true_start " << trueStart << "\nbound " << formatNumber(bound) << "\n";
    for (size_t i = 0; i < tour.size(); ++i)
        out << "tour " << i << " " << formatNumber(tour[i]) << " " << tourProbes.at(i) << "\n";
    for (const auto& p : trueTour)
        out << "tour_probe " << formatNumber(p.x) << " " << formatNumber(p.y) << "\n";
    for (const auto& p : trueTourRoute)
        out << "tour_path " << formatNumber(p.x) << " " << formatNumber(p.y) << "\n";
    for (const auto& p : overlay)
        out << "O " << formatNumber(p.x) << " " << formatNumber(p.y) << "\n";
    for (size_t c = 0; c < columns.size(); ++c) {
        const auto& col = columns[c];
        out << "C " << c << " " << col.name << "\n";
        for (size_t i = 0; i < col.travel.size(); ++i)
            out << "R " << c << " " << i << " " << formatNumber(col.travel[i]) << " "
                << col.probes[i] << " " << col.survivors[i] << " " << col.fallbacks.at(i) << "\n";
        for (const auto& p : col.route)
            out << "P " << c << " " << formatNumber(p.x) << " " << formatNumber(p.y) << "\n";
        for (size_t k = 0; k < col.stops.size(); ++k)
            out << "Q " << c << " " << formatNumber(col.stops[k].x) << " "
                << formatNumber(col.stops[k].y) << " " << col.stopsLeft.at(k) << "\n";
        for (const auto& p : col.candidates)
            out << "K " << c << " " << formatNumber(p.x) << " " << formatNumber(p.y) << "\n";
    }
    common::writeFileAtomically(path(dir), out.str());
}

EliminationFile EliminationFile::read(const std::string& dir) {
    EliminationFile f;
    for (const auto& line : common::readDataLines(path(dir))) {
        const std::string& kind = line.fields[0];
        const auto column = [&f, &line]() -> Column& {
            const double c = line.number(1);
            if (c < 0 || c >= (double)f.columns.size() || c != std::floor(c))
                throw Error(line.where + ": no column " + line.fields[1] + " declared before");
            return f.columns[(size_t)c];
        };
        if (kind == "true_start") {
            line.expectFields(2);
            f.trueStart = (size_t)line.number(1);
        } else if (kind == "bound") {
            line.expectFields(2);
            f.bound = line.number(1);
        } else if (kind == "C") {
            line.expectFields(3);
            if (line.number(1) != (double)f.columns.size())
                throw Error(line.where + ": columns must be numbered 0, 1, ... in order");
            f.columns.emplace_back().name = line.fields[2];
        } else if (kind == "R") {
            if (line.fields.size() != 6) line.expectFields(7);  // before issue 55: 6
            auto& col = column();
            if (line.number(2) != (double)col.travel.size())
                throw Error(line.where + ": starts must be numbered 0, 1, ... in order");
            col.travel.push_back(line.number(3));
            col.probes.push_back((int)line.number(4));
            col.survivors.push_back((int)line.number(5));
            col.fallbacks.push_back(line.fields.size() > 6 ? (int)line.number(6) : 0);
        } else if (kind == "Q") {
            if (line.fields.size() != 4) line.expectFields(5);  // before issue 55: 4
            column().stops.push_back({line.number(2), line.number(3)});
            column().stopsLeft.push_back(line.fields.size() > 4 ? (int)line.number(4) : -1);
        } else if (kind == "P" || kind == "K") {
            line.expectFields(4);
            (kind == "P" ? column().route : column().candidates)
                .push_back({line.number(2), line.number(3)});
        } else if (kind == "O") {
            line.expectFields(3);
            f.overlay.push_back({line.number(1), line.number(2)});
        } else if (kind == "tour") {
            line.expectFields(4);
            if (line.number(1) != (double)f.tour.size())
                throw Error(line.where + ": tours must be numbered 0, 1, ... in order");
            f.tour.push_back(line.number(2));
            f.tourProbes.push_back((int)line.number(3));
        } else if (kind == "tour_probe" || kind == "tour_path") {
            line.expectFields(3);
            (kind == "tour_probe" ? f.trueTour : f.trueTourRoute)
                .push_back({line.number(1), line.number(2)});
        } else {
            throw Error(line.where +
                        ": expected a line starting with true_start, bound, tour, tour_probe, "
                        "tour_path, O, C, R, P, Q or K");
        }
    }
    return f;
}

void EliminationTimes::write(const std::string& dir) const {
    std::ostringstream out;
    out << "# polymap elimination experiment: T column start seconds (one localization)\n";
    for (size_t c = 0; c < seconds.size(); ++c)
        for (size_t i = 0; i < seconds[c].size(); ++i)
            out << "T " << c << " " << i << " " << formatNumber(seconds[c][i]) << "\n";
    common::writeFileAtomically(path(dir), out.str());
}

EliminationTimes EliminationTimes::read(const std::string& dir) {
    EliminationTimes t;
    for (const auto& line : common::readDataLines(path(dir))) {
        line.expectFields(4);
        if (line.fields[0] != "T") throw Error(line.where + ": expected a line starting with T");
        const size_t c = (size_t)line.number(1), i = (size_t)line.number(2);
        if (c > 1000 || i > 100000) throw Error(line.where + ": column or start out of range");
        if (t.seconds.size() <= c) t.seconds.resize(c + 1);
        if (t.seconds[c].size() != i)
            throw Error(line.where + ": starts must be numbered 0, 1, ... in order");
        t.seconds[c].push_back(line.number(3));
    }
    return t;
}

void EliminationSweepFile::write(const std::string& dir) const {
    std::ostringstream out;
    out << "# polymap elimination sweep (paper 002 Figs. 6-7), exact views\n"
        << "# n k starts column mean_travel_m mean_seconds not_localized\n";
    for (const auto& r : rows)
        out << r.n << " " << r.k << " " << r.starts << " " << r.column << " "
            << formatNumber(r.meanTravel) << " " << formatNumber(r.meanSeconds) << " "
            << r.notLocalized << "\n";
    common::writeFileAtomically(path(dir), out.str());
}

EliminationSweepFile EliminationSweepFile::read(const std::string& dir) {
    EliminationSweepFile f;
    for (const auto& line : common::readDataLines(path(dir))) {
        line.expectFields(7);
        f.rows.push_back({(int)line.number(0), (int)line.number(1), (int)line.number(2),
                          line.fields[3], line.number(4), line.number(5), (int)line.number(6)});
    }
    return f;
}

}  // namespace mrloc::polymap
