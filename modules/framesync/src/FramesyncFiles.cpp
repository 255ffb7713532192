#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/DataFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/framesync/FramesyncFiles.h>

#include <cmath>
#include <sstream>

namespace mrloc::framesync {

using common::formatNumber;

std::vector<PairFigure> endFigures(const common::Trajectories& shared,
                                   const common::Trajectories& odometry,
                                   const common::Trajectories& truth) {
    using mrpt::poses::CPose2D;
    struct End {
        double t;
        CPose2D shared, odometry, truth;
    };
    std::map<std::string, End> ends;
    for (const auto& [robot, est] : shared) {
        const auto odo = odometry.find(robot);
        const auto gt = truth.find(robot);
        if (est.empty() || odo == odometry.end() || odo->second.empty() || gt == truth.end())
            continue;
        const auto& last = est.back();
        const auto t = common::interpolate(gt->second, last.t);
        if (!t) continue;
        ends[robot] = {last.t, CPose2D(last.pose), CPose2D(odo->second.back().pose), CPose2D(*t)};
    }
    // b as robot a sees it (in a's body frame): a frame that is rotated as a whole, as the
    // reference robot's own frame drifts, leaves it unchanged
    const auto relative = [](const CPose2D& a, const CPose2D& b) {
        const CPose2D d = b - a;
        return TPoint2D(d.x(), d.y());
    };
    std::vector<PairFigure> out;
    for (auto a = ends.begin(); a != ends.end(); ++a)
        for (auto b = std::next(a); b != ends.end(); ++b) {
            const End &ea = a->second, &eb = b->second;
            const TPoint2D truthSeen = relative(ea.truth, eb.truth);
            PairFigure p;
            p.a = a->first, p.b = b->first;
            p.time = std::max(ea.t, eb.t);
            p.trueDistance = truthSeen.norm();
            p.sharedError = (relative(ea.shared, eb.shared) - truthSeen).norm();
            p.odometryError = (relative(ea.odometry, eb.odometry) - truthSeen).norm();
            out.push_back(p);
        }
    return out;
}

std::pair<double, double> meanPairErrors(const std::vector<PairFigure>& pairs) {
    if (pairs.empty()) return {NAN, NAN};
    double s = 0, o = 0;
    for (const auto& p : pairs) s += p.sharedError, o += p.odometryError;
    return {s / double(pairs.size()), o / double(pairs.size())};
}

void FramesyncRunFile::write(const std::string& dir) const {
    std::ostringstream out;
    out << "# framesync run (paper 004): walls, redefinitions, end figures; m, rad, s\n"
        << "# wall robot sonar t frame_version ax ay bx by normal residual erps\n"
        << "# redefinition robot reference t version rotation shift overlap own_wall "
           "reference_wall\n"
        << "# pair a b t true_distance shared_error odometry_error\n";
    for (const auto& w : walls)
        out << "wall " << w.robot << " " << w.sonar << " " << formatNumber(w.time) << " "
            << w.frameVersion << " " << formatNumber(w.wall.a.x) << " " << formatNumber(w.wall.a.y)
            << " " << formatNumber(w.wall.b.x) << " " << formatNumber(w.wall.b.y) << " "
            << formatNumber(w.wall.normal) << " " << formatNumber(w.wall.residual) << " "
            << w.wall.erps << "\n";
    for (const auto& e : events)
        out << "redefinition " << e.robot << " " << e.reference << " " << formatNumber(e.time)
            << " " << e.version << " " << formatNumber(e.redefinition.rotation) << " "
            << formatNumber(e.redefinition.shift) << " " << formatNumber(e.redefinition.overlap)
            << " " << e.ownWall << " " << e.referenceWall << "\n";
    for (const auto& p : pairs)
        out << "pair " << p.a << " " << p.b << " " << formatNumber(p.time) << " "
            << formatNumber(p.trueDistance) << " " << formatNumber(p.sharedError) << " "
            << formatNumber(p.odometryError) << "\n";
    common::writeFileAtomically(path(dir), out.str());
}

FramesyncRunFile FramesyncRunFile::read(const std::string& dir) {
    FramesyncRunFile f;
    for (const auto& line : common::readDataLines(path(dir))) {
        const std::string& tag = line.fields.at(0);
        if (tag == "wall") {
            line.expectFields(12);
            AnnouncedWall w;
            w.robot = line.fields[1];
            w.sonar = int(line.number(2));
            w.time = line.number(3);
            w.frameVersion = uint32_t(line.number(4));
            w.wall.a = {line.number(5), line.number(6)};
            w.wall.b = {line.number(7), line.number(8)};
            w.wall.normal = line.number(9);
            w.wall.residual = line.number(10);
            w.wall.erps = size_t(line.number(11));
            f.walls.push_back(w);
        } else if (tag == "redefinition") {
            line.expectFields(10);
            RedefinitionEvent e;
            e.robot = line.fields[1];
            e.reference = line.fields[2];
            e.time = line.number(3);
            e.version = uint32_t(line.number(4));
            e.redefinition.rotation = line.number(5);
            e.redefinition.shift = line.number(6);
            e.redefinition.overlap = line.number(7);
            e.ownWall = uint64_t(line.number(8));
            e.referenceWall = uint64_t(line.number(9));
            f.events.push_back(e);
        } else if (tag == "pair") {
            line.expectFields(7);
            f.pairs.push_back({line.fields[1], line.fields[2], line.number(3), line.number(4),
                               line.number(5), line.number(6)});
        } else {
            throw Error(line.where + ": unknown record '" + tag + "'");
        }
    }
    return f;
}

void FramesyncExperimentFile::write(const std::string& dir) const {
    std::ostringstream out;
    out << "# framesync experiment (paper 004 sec. 5.2 over many runs): errors in m\n"
        << "# run kind value seed shared_error odometry_error walls redefinitions\n";
    for (const auto& r : runs)
        out << "run " << r.kind << " " << formatNumber(r.value) << " " << r.seed << " "
            << formatNumber(r.sharedError) << " " << formatNumber(r.odometryError) << " " << r.walls
            << " " << r.redefinitions << "\n";
    common::writeFileAtomically(path(dir), out.str());
}

FramesyncExperimentFile FramesyncExperimentFile::read(const std::string& dir) {
    FramesyncExperimentFile f;
    for (const auto& line : common::readDataLines(path(dir))) {
        if (line.fields.at(0) != "run")
            throw Error(line.where + ": unknown record '" + line.fields[0] + "'");
        line.expectFields(8);
        const std::string& kind = line.fields[1];
        if (kind != "paper" && kind != "noise" && kind != "drift")
            throw Error(line.where + ": unknown kind '" + kind + "'");
        f.runs.push_back({kind, line.number(2), (unsigned long)line.number(3), line.number(4),
                          line.number(5), size_t(line.number(6)), size_t(line.number(7))});
    }
    return f;
}

}  // namespace mrloc::framesync
