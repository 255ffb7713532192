#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/DataFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/polymap/PolymapFiles.h>

#include <sstream>

namespace mrloc::polymap {

using common::formatNumber;

std::string HypothesesFile::path(const std::string& dir, const std::string& robot) {
    return dir + "/hypotheses." + robot + ".txt";
}

void HypothesesFile::write(const std::string& dir, const std::string& robot) const {
    std::ostringstream out;
    out << "# polymap result of robot " << robot << " (seed 002, hypothesis generation)\n"
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

}  // namespace mrloc::polymap
