#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/DataFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/Names.h>
#include <mrloc/formation/FormationFiles.h>
#include <mrloc/formation/FormationPayload.h>

#include <optional>
#include <sstream>

namespace mrloc::formation {

using common::formatNumber;

std::pair<double, double> absMoments(const std::vector<double>& xs) {
    double sum = 0, sq = 0;
    for (const double x : xs) sum += std::abs(x), sq += x * x;
    const double n = double(xs.size()), mean = sum / n;
    return {mean, std::sqrt(std::max(0.0, sq / n - mean * mean))};
}

FormationRunFile FormationRunFile::fromRun(const Team& team, const common::Trajectories& estimates,
                                           const common::Trajectories& truth) {
    FormationRunFile f;
    f.route = team.options().route;
    f.start = team.options().start;
    f.obstacles = team.obstacles();
    const auto truthAt = [&](size_t robot, double t) -> std::optional<TPoint2D> {
        const auto gt = truth.find(team.options().names[robot]);
        if (gt == truth.end()) return std::nullopt;
        const auto p = common::interpolate(gt->second, t);
        if (!p) return std::nullopt;
        return TPoint2D{p->x(), p->y()};
    };
    for (const auto& e : team.moves()) {
        const Move& m = e.move;
        MoveRow row{e.time, team.options().names[m.robot], m.target};
        const auto end = truthAt(m.robot, e.time);
        if (end) row.truth = *end;
        const auto b1 = truthAt(m.base[0], e.time), b2 = truthAt(m.base[1], e.time),
                   anchor = truthAt(m.anchor, e.time);
        if (end && b1 && b2 && anchor) {
            const auto e = stepError(*b1, *b2, *anchor, *end);
            row.lateral = e.lateral, row.longitudinal = e.longitudinal;
        }
        f.moves.push_back(row);
    }
    const auto dr = estimates.find(kDeadReckoningRobot);
    const auto drTruth = truth.find(kDeadReckoningRobot);
    if (dr != estimates.end() && !dr->second.empty() && drTruth != truth.end()) {
        const auto& last = dr->second.back();
        if (const auto p = common::interpolate(drTruth->second, last.t)) {
            f.deadReckoningFinalError = std::hypot(p->x() - last.pose.x(), p->y() - last.pose.y());
            f.deadReckoningFinalTime = last.t;
        }
    }
    return f;
}

void FormationRunFile::write(const std::string& dir) const {
    std::ostringstream out;
    out << "# formation run (paper 003): route, strip, moves, shared obstacles, world frame (m)\n"
        << "# route x y | start x y | move t robot believed_x believed_y true_x true_y lateral "
           "longitudinal\n"
        << "# obstacle x y radius | dead_reckoning t final_error\n";
    for (const auto& p : route)
        out << "route " << formatNumber(p.x) << " " << formatNumber(p.y) << "\n";
    for (const auto& p : start)
        out << "start " << formatNumber(p.x) << " " << formatNumber(p.y) << "\n";
    for (const auto& m : moves)
        out << "move " << formatNumber(m.time) << " " << m.robot << " "
            << formatNumber(m.believed.x) << " " << formatNumber(m.believed.y) << " "
            << formatNumber(m.truth.x) << " " << formatNumber(m.truth.y) << " "
            << formatNumber(m.lateral) << " " << formatNumber(m.longitudinal) << "\n";
    for (const auto& o : obstacles)
        out << "obstacle " << formatNumber(o.centre.x) << " " << formatNumber(o.centre.y) << " "
            << formatNumber(o.radius) << "\n";
    out << "dead_reckoning " << formatNumber(deadReckoningFinalTime) << " "
        << formatNumber(deadReckoningFinalError) << "\n";
    common::writeFileAtomically(path(dir), out.str());
}

FormationRunFile FormationRunFile::read(const std::string& dir) {
    FormationRunFile f;
    for (const auto& line : common::readDataLines(path(dir))) {
        const std::string& tag = line.fields.at(0);
        if (tag == "route" || tag == "start") {
            line.expectFields(3);
            (tag == "route" ? f.route : f.start).push_back({line.number(1), line.number(2)});
        } else if (tag == "move") {
            line.expectFields(9);
            f.moves.push_back({line.number(1),
                               line.fields[2],
                               {line.number(3), line.number(4)},
                               {line.number(5), line.number(6)},
                               line.number(7),
                               line.number(8)});
        } else if (tag == "obstacle") {
            line.expectFields(4);
            f.obstacles.push_back({{line.number(1), line.number(2)}, line.number(3)});
        } else if (tag == "dead_reckoning") {
            line.expectFields(3);
            f.deadReckoningFinalTime = line.number(1);
            f.deadReckoningFinalError = line.number(2);
        } else {
            throw Error(line.where + ": unknown record '" + tag + "'");
        }
    }
    return f;
}

void FormationExperimentFile::write(const std::string& dir) const {
    std::ostringstream out;
    out << "# formation Monte Carlo experiment (paper 003 sec. 5), errors in m, times in s\n"
        << "# table route wheel_speed runs moves formation dead_reckoning formation_time "
           "dead_reckoning_time\n"
        << "# curve route wheel_speed kind time error | robots n runs error\n"
        << "# step source lateral_mean lateral_sd longitudinal_mean longitudinal_sd count\n"
        << "# pixel route wheel_speed runs arrived formation formation_sd formation_max "
           "dead_reckoning lost_moves frames rotation\n";
    for (const auto& r : table)
        out << "table " << r.route << " " << formatNumber(r.wheelSpeed) << " " << r.runs << " "
            << r.moves << " " << formatNumber(r.formation) << " " << formatNumber(r.deadReckoning)
            << " " << formatNumber(r.formationTime) << " " << formatNumber(r.deadReckoningTime)
            << "\n";
    for (const auto& c : curves)
        out << "curve " << c.route << " " << formatNumber(c.wheelSpeed) << " " << c.kind << " "
            << formatNumber(c.time) << " " << formatNumber(c.error) << "\n";
    for (const auto& r : robots)
        out << "robots " << r.robots << " " << r.runs << " " << formatNumber(r.error) << "\n";
    for (const auto& s : steps)
        out << "step " << s.source << " " << formatNumber(s.lateralMean) << " "
            << formatNumber(s.lateralSd) << " " << formatNumber(s.longitudinalMean) << " "
            << formatNumber(s.longitudinalSd) << " " << s.count << "\n";
    for (const auto& r : pixel)
        out << "pixel " << r.route << " " << formatNumber(r.wheelSpeed) << " " << r.runs << " "
            << r.arrived << " " << formatNumber(r.formation) << " " << formatNumber(r.formationSd)
            << " " << formatNumber(r.formationMax) << " " << formatNumber(r.deadReckoning) << " "
            << formatNumber(r.lostMoves) << " " << formatNumber(r.frames) << " "
            << formatNumber(r.rotation) << "\n";
    common::writeFileAtomically(path(dir), out.str());
}

FormationExperimentFile FormationExperimentFile::read(const std::string& dir) {
    FormationExperimentFile f;
    for (const auto& line : common::readDataLines(path(dir))) {
        const std::string& tag = line.fields.at(0);
        // a route names the report's fig. 14 picture: a name, never a path (the file may
        // come from a run folder someone sent)
        if (tag == "table" || tag == "curve" || tag == "pixel")
            common::checkName(line.fields.at(1), line.where);
        if (tag == "table") {
            line.expectFields(9);
            f.table.push_back({line.fields[1], line.number(2), size_t(line.number(3)),
                               size_t(line.number(4)), line.number(5), line.number(6),
                               line.number(7), line.number(8)});
        } else if (tag == "curve") {
            line.expectFields(6);
            f.curves.push_back(
                {line.fields[1], line.fields[3], line.number(2), line.number(4), line.number(5)});
        } else if (tag == "robots") {
            line.expectFields(4);
            f.robots.push_back({size_t(line.number(1)), size_t(line.number(2)), line.number(3)});
        } else if (tag == "step") {
            line.expectFields(7);
            f.steps.push_back({line.fields[1], line.number(2), line.number(3), line.number(4),
                               line.number(5), size_t(line.number(6))});
        } else if (tag == "pixel") {
            line.expectFields(12);
            f.pixel.push_back({line.fields[1], line.number(2), size_t(line.number(3)),
                               size_t(line.number(4)), line.number(5), line.number(6),
                               line.number(7), line.number(8), line.number(9), line.number(10),
                               line.number(11)});
        } else {
            throw Error(line.where + ": unknown record '" + tag + "'");
        }
    }
    return f;
}

}  // namespace mrloc::formation
