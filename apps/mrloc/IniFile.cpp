#include "IniFile.h"

#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/IniLint.h>
#include <mrloc/common/IniSection.h>
#include <mrloc/common/Names.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

namespace mrloc::app {

namespace fs = std::filesystem;

namespace {

/** A section mrloc reads: a registered method's, the framework's, or a robot's. */
bool ownedByMrloc(std::string section, const std::vector<std::string>& known) {
    // MRPT reads section names in any case ([Scenario] is [scenario]), and so does mrloc
    for (char& c : section) c = char(std::tolower(static_cast<unsigned char>(c)));
    return section.rfind("robot.", 0) == 0 ||
           std::find(known.begin(), known.end(), section) != known.end();
}

/** The section of mrloc's that `section` looks like a misspelling of, if any: within one
 *  edit (two for names of 6 letters or more), any case. Other sections belong to other
 *  programs (MRPT's apps) and are left alone. */
std::optional<std::string> closeTo(const std::string& section,
                                   const std::vector<std::string>& known) {
    const auto best = common::nearMiss(section, known);
    // [robto.r1], [Robot.r1]: a robot's section
    const auto dot = section.find('.');
    if (dot != std::string::npos && common::editDistance(section.substr(0, dot), "robot") <= 1)
        return "robot." + section.substr(dot + 1);
    return best;
}

}  // namespace

bool isMrlocSection(const std::string& section, const method::Registry& registry) {
    return ownedByMrloc(section, registry.sections());
}

/** A rawlog by its name or its first bytes (gzip's magic, or MRPT's binary archive). */
bool looksLikeRawlog(const std::string& path) {
    const std::string ext = fs::path(path).extension().string();
    if (ext == ".rawlog" || ext == ".gz") return true;
    std::ifstream in(path, std::ios::binary);
    unsigned char head[2] = {0, 0};
    in.read(reinterpret_cast<char*>(head), 2);
    return in.gcount() == 2 && ((head[0] == 0x1f && head[1] == 0x8b) || head[0] == 0x00);
}

bool looksLikeIni(const std::string& path) {
    if (looksLikeRawlog(path)) return false;
    const std::string ext = fs::path(path).extension().string();
    if (ext == ".ini" || ext == ".cfg") return true;
    std::ifstream in(path, std::ios::binary);
    char c = 0;
    while (in.get(c) && std::isspace(static_cast<unsigned char>(c))) {
    }
    return in && (c == '[' || c == ';' || c == '#');
}

void checkNotAnIni(const std::string& rawlogPath) {
    if (fs::is_regular_file(rawlogPath) && looksLikeIni(rawlogPath))
        throw Error("rawlog " + rawlogPath +
                    ": this is an INI, not a rawlog (give the INI first: mrloc localize <ini> "
                    "<rawlog>; mrloc simulate <ini> makes a rawlog)");
}

/** The INI's bytes, as read once: checked, parsed and copied into config.ini from these. */
std::string readIniText(const std::string& path) {
    if (fs::is_directory(path))
        throw Error("config " + common::pathInWords(path) + ": is a folder; give an INI file");
    if (!fs::exists(path)) throw Error("config " + common::pathInWords(path) + ": no such file");
    common::checkReadableFile(path, "config", 16u << 20);  // not a FIFO nor /dev/zero
    if (looksLikeRawlog(path))
        throw Error("config " + path + ": this is a rawlog, not an INI (mrloc localize <ini> " +
                    path + " runs a method on it; mrloc info " + path + " lists what it holds)");
    std::ifstream file(path, std::ios::binary);
    std::stringstream text;
    text << file.rdbuf();
    if (!file) throw Error("config " + path + ": cannot read");
    return text.str();
}

/** Opens an INI. Sections of other programs (MRPT's apps: [ro-localization],
 *  [MetricMap_...]) are left alone; a section that looks like a misspelling of one of mrloc's
 *  ([sensor], [Beacons], [robto.r1]) would otherwise be ignored silently, and is refused. */
std::unique_ptr<mrpt::config::CConfigFile> openIni(const std::string& path, const std::string& text,
                                                   const method::Registry& registry) {
    const auto known = registry.sections();
    // mrloc's sections are checked line by line; the others are left as their programs read
    // them.
    common::lintIni(text, path, [&known](const std::string& section) {
        return section.empty() || ownedByMrloc(section, known);
    });
    auto ini = std::make_unique<mrpt::config::CConfigFile>(path);
    std::vector<std::string> sections;
    ini->getAllSections(sections);
    for (const auto& s : sections) {
        if (ownedByMrloc(s, known)) continue;
        if (const auto near = closeTo(s, known))
            throw Error(path + ": [" + s + "]: unknown section (did you mean [" + *near +
                        "]? see doc/ini.md)");
    }
    return ini;
}

/** An INI without [scenario] method: the one method whose own sections it holds, else the
 *  one whose foreign sections (MRPT's) it holds; otherwise an error listing the methods. */
std::string methodOfSections(const method::Registry& registry,
                             const mrpt::config::CConfigFileBase& ini) {
    for (const bool own : {true, false}) {
        std::vector<std::string> owners;
        for (const auto& name : registry.names()) {
            const auto& m = registry.get(name);
            for (const auto& section : own ? m.sections : m.foreignSections)
                if (ini.sectionExists(section)) {
                    owners.push_back(name);
                    break;
                }
        }
        if (owners.size() == 1) return owners.front();
        if (owners.size() > 1)
            throw Error(common::configOrigin(ini) +
                        ": [scenario] method: required, the INI "
                        "holds sections of " +
                        std::to_string(owners.size()) + " methods (" + owners.front() + ", " +
                        owners[1] + ", ...)");
    }
    std::string names;
    for (const auto& n : registry.names()) names += (names.empty() ? "" : ", ") + n;
    throw Error(common::configOrigin(ini) +
                ": [scenario] method: required key is missing, and no section names a method "
                "(one of: " +
                names + ")");
}

}  // namespace mrloc::app
