// `mrloc info <rawlog>`: what a rawlog holds, per robot and sensor label, before a run.
#include <mrloc/common/Rawlog.h>
#include <mrloc/common/Trajectory.h>
#include <mrloc/common/Version.h>
#include <mrpt/3rdparty/tclap/CmdLine.h>
#include <mrpt/core/format.h>
#include <mrpt/system/datetime.h>

#include <iostream>
#include <map>

#include "Commands.h"

namespace mrloc::app {

int info(int argc, char** argv) {
    TCLAP::CmdLine cmd(
        "mrloc info: per robot and sensor label of a rawlog, the observation "
        "class, count, rate and time span",
        ' ', kVersion);
    TCLAP::UnlabeledValueArg<std::string> path("rawlog", "rawlog file", true, "", "RAWLOG", cmd);
    if (const auto code = parseArgs(cmd, argc, argv)) return *code;

    struct Stream {
        std::string cls;
        size_t count = 0;
        double t0 = 0, t1 = 0;
    };
    std::map<std::pair<std::string, std::string>, Stream> streams;
    common::RawlogReader reader(path.getValue());
    size_t total = 0;
    for (mrpt::obs::CObservation::Ptr obs; reader.next(obs); ++total) {
        const double t = mrpt::Clock::toDouble(obs->timestamp);
        auto& s = streams[{common::robotOfLabel(obs->sensorLabel), obs->sensorLabel}];
        if (s.count == 0) {
            s.cls = obs->GetRuntimeClass()->className;
            s.t0 = t;
        }
        s.t1 = t;
        ++s.count;
    }
    std::cout << "rawlog: " << path.getValue() << "\nformat: "
              << (reader.format() == common::RawlogFormat::ActionsSensoryFrames
                      ? "actions + sensory frames"
                      : "observations only")
              << "\nentries: " << reader.entriesRead() << ", observations: " << total << "\n\n";
    std::cout << mrpt::format("%-10s %-18s %-36s %8s %9s %9s %9s\n", "robot", "label", "class",
                              "count", "rate_hz", "start_s", "span_s");
    double first = 1e300;
    for (const auto& [key, s] : streams) first = std::min(first, s.t0);
    for (const auto& [key, s] : streams) {
        const double span = s.t1 - s.t0;
        std::cout << mrpt::format("%-10s %-18s %-36s %8zu %9.2f %9.3f %9.3f\n", key.first.c_str(),
                                  key.second.c_str(), s.cls.c_str(), s.count,
                                  span > 0 ? double(s.count - 1) / span : 0.0, s.t0 - first, span);
    }
    return 0;
}

}  // namespace mrloc::app
