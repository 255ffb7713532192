#include "MrptTruth.h"

#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/GroundTruthFile.h>
#include <mrloc/common/IniSection.h>
#include <mrloc/common/MrptKeys.h>
#include <mrpt/core/bits_math.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace mrloc::app {

namespace fs = std::filesystem;

namespace {

bool sameFile(const std::string& a, const std::string& b) {
    std::error_code ec;
    return fs::equivalent(a, b, ec) && !ec;
}

/** ro-localization's start, the frame offset of its truth. */
mrpt::poses::CPose3D mrptStart(const mrpt::config::CConfigFileBase& ini) {
    namespace k = common::mrpt_ini;
    if (!ini.keyExists(k::kOdometryX.section, k::kOdometryX.name)) return {};
    common::IniSection s(ini, k::kOdometryX.section);  // MRPT's: its other keys are its own
    return mrpt::poses::CPose3D(s.real(k::kOdometryX.name, 0, -1e6, 1e6),
                                s.real(k::kOdometryY.name, 0, -1e6, 1e6), 0,
                                mrpt::DEG2RAD(s.real(k::kOdometryPhi.name, 0, -360, 360)), 0, 0);
}

}  // namespace

std::optional<FoundTruth> mrptTruthOf(const mrpt::config::CConfigFileBase& ini,
                                      const std::string& iniPath, const std::string& rawlog,
                                      std::string& note) {
    FoundTruth found;
    found.source.offset = mrptStart(ini);
    namespace k = common::mrpt_ini;
    const std::string named =
        ini.read_string(k::kGroundTruthFile.section, k::kGroundTruthFile.name, "");
    if (!named.empty()) {
        const std::string gt = common::pathFromIni(iniPath, named);
        const std::string ownLog = common::pathFromIni(
            iniPath, ini.read_string(k::kRoRawlogFile.section, k::kRoRawlogFile.name, ""));
        if (!sameFile(ownLog, rawlog)) {
            note = "[ro-localization] groundTruthFile " + named + " is the truth of " + ownLog +
                   ", not of this log: not used";
        } else if (const auto format =
                       fs::is_regular_file(gt) ? common::groundTruthFormatOf(gt) : std::nullopt) {
            found.source.path = gt;
            found.source.format = *format;
            found.from = "MRPT's [ro-localization] groundTruthFile (" + named + ")";
            return found;
        }
    }
    // MRPT's datasets: <stem>_GT.txt beside <stem>.rawlog
    fs::path stem = fs::path(rawlog);
    while (stem.has_extension() && (stem.extension() == ".gz" || stem.extension() == ".rawlog"))
        stem.replace_extension();
    const std::string beside = stem.string() + "_GT.txt";
    if (fs::is_regular_file(beside))
        if (const auto format = common::groundTruthFormatOf(beside)) {
            found.source.path = beside;
            found.source.format = *format;
            found.from =
                fs::path(beside).filename().string() + " beside the rawlog (MRPT's naming)";
            return found;
        }
    return std::nullopt;
}

}  // namespace mrloc::app
