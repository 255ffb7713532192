#include "Advice.h"

#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/LocalizationRun.h>
#include <mrloc/common/MrptKeys.h>
#include <mrloc/common/Rawlog.h>

#include <filesystem>

namespace mrloc::app {

namespace fs = std::filesystem;

std::string fitHintOf(const method::Registry& registry, const std::string& current,
                      const std::map<std::string, size_t>& classCounts) {
    std::string hint;
    for (const auto& name : registry.names()) {
        if (name == current) continue;
        const auto& m = registry.get(name);
        for (const auto& cls : m.reads)
            if (classCounts.count(cls)) {
                hint += std::string(hint.empty() ? "" : "; ") + "method '" + name + "' reads " +
                        cls + (m.exampleConfig.empty() ? "" : ": start from " + m.exampleConfig);
                break;
            }
    }
    return hint.empty() ? "no mrloc method reads what this log holds (mrloc info lists it)" : hint;
}

std::map<std::string, size_t> classesOf(const std::string& rawlogPath) {
    std::map<std::string, size_t> counts;
    common::RawlogReader reader(rawlogPath);
    for (mrpt::obs::CObservation::Ptr obs; reader.next(obs);)
        ++counts[common::shortClassName(*obs)];
    return counts;
}

std::optional<std::string> mrptAppOf(const mrpt::config::CConfigFileBase& ini) {
    // the sections MRPT's apps read (MRPT 2.5's config_files/): the SLAM apps'
    // [MappingApplication] (pf-localization's INIs are polymap's and beacons')
    if (ini.sectionExists("MappingApplication"))
        return std::string(
            "an INI of MRPT's SLAM apps (icp-slam, rbpf-slam, kf-slam: [MappingApplication]); "
            "mrloc localizes on known maps, it does not build them");
    return std::nullopt;
}

std::string rawlogNamedBy(const mrpt::config::CConfigFileBase& ini, const std::string& iniPath) {
    namespace k = common::mrpt_ini;
    for (const auto& key : {k::kExperimentRawlogFile, k::kRoRawlogFile, k::kMappingRawlogFile}) {
        const std::string named = ini.read_string(key.section, key.name, "");
        if (named.empty()) continue;
        const std::string path = common::pathFromIni(iniPath, named);
        std::error_code ec;
        if (fs::is_regular_file(path, ec)) return path;
    }
    return "";
}

std::string foreignIniAdvice(const method::Registry& registry, const std::string& iniPath,
                             const std::string& what, const std::string& rawlog) {
    std::string line = iniPath + ": " + what;
    if (rawlog.empty())
        return line +
               ". mrloc info <rawlog> lists what a log holds, and mrloc localize "
               "<mrloc ini> <rawlog> runs an mrloc method on it";
    const auto classes = classesOf(rawlog);
    return line + ". " + rawlog + " holds " + common::contentInWords(classes) + ": " +
           fitHintOf(registry, "", classes);
}

}  // namespace mrloc::app
