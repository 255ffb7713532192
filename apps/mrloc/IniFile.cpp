#include "IniFile.h"

#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/IniLint.h>
#include <mrloc/common/IniSection.h>

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
bool ownedByMrloc(const std::string& section, const std::vector<std::string>& known) {
    return section.rfind("robot.", 0) == 0 ||
           std::find(known.begin(), known.end(), section) != known.end();
}

/** Edit distance (insertions, deletions, substitutions, adjacent swaps), case-insensitive. */
size_t editDistance(const std::string& a, const std::string& b) {
    const auto lower = [](char c) { return char(std::tolower(static_cast<unsigned char>(c))); };
    std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
    for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
    for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
    for (size_t i = 1; i <= a.size(); ++i)
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t cost = lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1;
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
            if (i > 1 && j > 1 && lower(a[i - 1]) == lower(b[j - 2]) &&
                lower(a[i - 2]) == lower(b[j - 1]))
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
        }
    return d[a.size()][b.size()];
}

/** The section of mrloc's that `section` looks like a misspelling of, if any: within one
 *  edit (two for names of 6 letters or more), any case. Other sections belong to other
 *  programs (MRPT's apps) and are left alone. */
std::optional<std::string> closeTo(const std::string& section,
                                   const std::vector<std::string>& known) {
    std::optional<std::string> best;
    size_t bestDistance = SIZE_MAX;
    for (const auto& k : known) {
        const size_t allowed = k.size() >= 6 ? 2 : 1;
        const size_t d = editDistance(section, k);
        if (d <= allowed && d < bestDistance) best = k, bestDistance = d;
    }
    // [robto.r1], [Robot.r1]: a robot's section
    const auto dot = section.find('.');
    if (dot != std::string::npos && editDistance(section.substr(0, dot), "robot") <= 1)
        return "robot." + section.substr(dot + 1);
    return best;
}

}  // namespace

/** A rawlog by its name or its first bytes (gzip's magic, or MRPT's binary archive). */
bool looksLikeRawlog(const std::string& path) {
    const std::string ext = fs::path(path).extension().string();
    if (ext == ".rawlog" || ext == ".gz") return true;
    std::ifstream in(path, std::ios::binary);
    unsigned char head[2] = {0, 0};
    in.read(reinterpret_cast<char*>(head), 2);
    return in.gcount() == 2 && ((head[0] == 0x1f && head[1] == 0x8b) || head[0] == 0x00);
}

/** The INI's bytes, as read once: checked, parsed and copied into config.ini from these. */
std::string readIniText(const std::string& path) {
    if (fs::is_directory(path)) throw Error("config " + path + ": is a folder; give an INI file");
    if (!fs::exists(path)) throw Error("config " + path + ": no such file");
    common::checkReadableFile(path, "config", 16u << 20);  // not a FIFO nor /dev/zero
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
