#include <mrloc/beacons/ShotLog.h>
#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrpt/core/format.h>

#include <fstream>
#include <sstream>

namespace mrloc::beacons {

std::string shotLogPath(const std::string& rawlogPath) {
    const std::string ext = ".rawlog";
    std::string stem = rawlogPath;
    if (stem.size() > ext.size() && stem.compare(stem.size() - ext.size(), ext.size(), ext) == 0)
        stem.resize(stem.size() - ext.size());
    return stem + ".shots.txt";
}

void saveShotLog(const std::string& path, const ShotLog& log) {
    std::string text =
        "# start_s end_s robot section beacon pan_rad tilt_rad off_axis_rad distance_m "
        "margin_db line_of_sight detected range_m\n";
    for (const auto& s : log)
        text +=
            mrpt::format("%.6f %.6f %s %s %d %.6f %.6f %.6f %.6f %.3f %d %d %.6f\n", s.start, s.end,
                         s.robot.c_str(), s.section.c_str(), s.beacon, s.pan, s.tilt, s.offAxis,
                         s.distance, s.marginDb, int(s.lineOfSight), int(s.detected), s.range);
    common::writeFileAtomically(path, text);
}

ShotLog loadShotLog(const std::string& path) {
    mrloc::common::checkReadableFile(path, "shot log", 1u << 30);
    std::ifstream in(path);
    if (!in) throw Error("shot log " + path + ": cannot open");
    ShotLog log;
    size_t lineNo = 0;
    for (std::string line; std::getline(in, line);) {
        ++lineNo;
        if (line.empty() || line[0] == '#') continue;
        std::istringstream s(line);
        ShotRecord r;
        int los = 0, det = 0;
        if (!(s >> r.start >> r.end >> r.robot >> r.section >> r.beacon >> r.pan >> r.tilt >>
              r.offAxis >> r.distance >> r.marginDb >> los >> det >> r.range))
            throw Error("shot log " + path + ":" + std::to_string(lineNo) + ": expected 13 fields");
        r.lineOfSight = los != 0;
        r.detected = det != 0;
        log.push_back(r);
    }
    return log;
}

}  // namespace mrloc::beacons
