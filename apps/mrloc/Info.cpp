// `mrloc info <rawlog>`: what a rawlog holds, before a run: one row per robot, sensor label
// and observation class, the actions by class, the absolute start and end times and the
// file's size, as MRPT's `rawlog-edit --info` shows them (the start and end are the data's:
// a comment's stamp is when the file was annotated). `--json` prints the same for programs.
#include <mrloc/common/Rawlog.h>
#include <mrloc/common/Trajectory.h>
#include <mrpt/3rdparty/tclap/CmdLine.h>
#include <mrpt/core/format.h>
#include <mrpt/obs/CObservationComment.h>
#include <mrpt/system/datetime.h>

#include <filesystem>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>

#include "CommandLine.h"
#include "Commands.h"
#include "IniFile.h"

namespace mrloc::app {

namespace {

struct Stream {
    size_t count = 0;
    size_t restamped = 0;  ///< stamped 0, given the sensory frame's time
    size_t missing = 0;    ///< stamped 0 with no time to take: not in the span
    size_t before1970 = 0;  ///< which localize refuses (ObservationCheck)
    double t0 = 0, t1 = 0;
    bool timed = false;
};

std::string utc(double t) { return common::timeInWords(t); }

}  // namespace

int info(int argc, char** argv) {
    CommandLine cmd(
        "mrloc info: per robot, sensor label and observation class of a rawlog, the count, "
        "rate and time span; the actions by class; the absolute start and end times and the "
        "file's size");
    TCLAP::UnlabeledValueArg<std::string> path("rawlog", "rawlog file", true, "", "RAWLOG", cmd);
    TCLAP::SwitchArg json("j", "json", "print JSON instead of a table", cmd);
    if (const auto code = parseArgs(cmd, argc, argv)) return *code;

    // robot, label, class
    std::map<std::tuple<std::string, std::string, std::string>, Stream> streams;
    checkNotAnIni(path.getValue());
    common::RawlogReader reader(path.getValue());
    size_t total = 0;
    double first = INFINITY, last = -INFINITY;
    for (mrpt::obs::CObservation::Ptr obs; reader.next(obs); ++total) {
        auto& s = streams[{common::robotOfLabel(obs->sensorLabel), obs->sensorLabel,
                           obs->GetRuntimeClass()->className}];
        ++s.count;
        // a comment is stamped when the file was annotated, not when data was taken
        const bool comment = IS_CLASS(*obs, mrpt::obs::CObservationComment);
        if (obs->timestamp == INVALID_TIMESTAMP) {
            ++s.missing;
            continue;
        }
        const double t = common::stampSeconds(obs->timestamp);
        s.before1970 += t < 0;
        if (!s.timed) s.t0 = t, s.t1 = t, s.timed = true;
        s.t0 = std::min(s.t0, t), s.t1 = std::max(s.t1, t);
        if (!comment) first = std::min(first, t), last = std::max(last, t);
    }
    for (const auto& [key, n] : reader.restamped())
        for (auto& [k, s] : streams)
            if (std::get<1>(k) == key.first && std::get<2>(k) == key.second) s.restamped = n;
    const auto bytes = std::filesystem::file_size(path.getValue());
    const bool sf = reader.format() == common::RawlogFormat::ActionsSensoryFrames;
    size_t actions = 0;
    for (const auto& [cls, n] : reader.actions()) actions += n;

    if (json.getValue()) {
        nlohmann::json j;
        j["rawlog"] = path.getValue();
        j["file_size_bytes"] = bytes;
        j["format"] = sf ? "actions+sensory-frames" : "observations-only";
        j["entries"] = reader.entriesRead();
        j["observations"] = total;
        j["actions"] = reader.actions();
        if (std::isfinite(first)) j["start_time"] = first, j["end_time"] = last;
        j["streams"] = nlohmann::json::array();
        for (const auto& [key, s] : streams) {
            nlohmann::json r{{"robot", std::get<0>(key)},
                             {"label", std::get<1>(key)},
                             {"class", std::get<2>(key)},
                             {"count", s.count},
                             {"stamped_0_given_frame_time", s.restamped},
                             {"stamped_0_missing", s.missing}};
            if (s.timed) r["start_time"] = s.t0, r["end_time"] = s.t1;
            j["streams"].push_back(r);
        }
        std::cout << j.dump(2) << "\n";
        return 0;
    }
    std::cout << "rawlog: " << path.getValue() << "\nfile size: " << bytes << " bytes"
              << mrpt::format(" (%.2f MB)", double(bytes) / 1048576.0)
              << "\nformat: " << (sf ? "actions + sensory frames" : "observations only")
              << "\nentries: " << reader.entriesRead() << ", observations: " << total
              << ", actions: " << actions << "\n";
    if (std::isfinite(first))
        std::cout << "start: " << utc(first) << mrpt::format(" (%.6f)", first)
                  << "\nend:   " << utc(last) << mrpt::format(" (%.6f)", last)
                  << mrpt::format("\nspan:  %.3f s\n", last - first);
    else
        std::cout << "start, end: none (every time stamp is 0)\n";
    for (const auto& [cls, n] : reader.actions())
        std::cout << "actions: " << cls << " " << n << "\n";
    std::cout << "\n"
              << mrpt::format("%-10s %-18s %-40s %8s %9s %10s %9s  %s\n", "robot", "label", "class",
                              "count", "rate_hz", "start_s", "span_s", "stamps");
    for (const auto& [key, s] : streams) {
        const double span = s.timed ? s.t1 - s.t0 : 0;
        std::string stamps;
        if (s.restamped)
            stamps = mrpt::format("%zu stamped 0 took their frame's time", s.restamped);
        if (s.missing)
            stamps += (stamps.empty() ? "" : "; ") +
                      mrpt::format("%zu stamped 0 with no time: left out", s.missing);
        if (s.before1970)
            stamps += (stamps.empty() ? "" : "; ") +
                      mrpt::format("%zu before 1970: localize refuses them", s.before1970);
        if (stamps.empty()) stamps = "all valid";
        const std::string label = std::get<1>(key).empty() ? "(none)" : std::get<1>(key);
        const double rate = span > 0 ? double(s.count - s.missing - 1) / span : 0.0;
        std::cout << mrpt::format("%-10s %-18s %-40s %8zu ", std::get<0>(key).c_str(),
                                  label.c_str(), std::get<2>(key).c_str(), s.count)
                  << (s.timed ? mrpt::format("%9.2f %10.3f %9.3f", rate, s.t0 - first, span)
                              : mrpt::format("%9s %10s %9s", "-", "-", "-"))
                  << "  " << stamps << "\n";
    }
    return 0;
}

}  // namespace mrloc::app
