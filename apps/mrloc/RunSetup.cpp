#include "RunSetup.h"

#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/IniLint.h>
#include <mrloc/common/IniSection.h>
#include <mrloc/common/Metrics.h>
#include <mrloc/common/Names.h>
#include <mrloc/common/RunDirectory.h>
#include <mrloc/common/Seeds.h>
#include <mrloc/common/ShellWord.h>
#include <mrloc/common/Version.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/system/os.h>

#include <algorithm>
#include <cctype>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <thread>

#include "Advice.h"
#include "IniFile.h"
#include "MrptSections.h"

namespace mrloc::app {

namespace fs = std::filesystem;

extern const char* const kCommit;  // BuildInfo.cpp, generated at build time

namespace {

/** "2026-12-02 15:22:35": now, in UTC. */
std::string utcNow() {
    const std::time_t now = std::time(nullptr);
    std::tm utc{};
    gmtime_r(&now, &utc);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%d %H:%M:%S", &utc);
    return text;
}

/** The CPU's model name as /proc/cpuinfo gives it; "unknown" elsewhere. */
std::string cpuModel() {
    std::ifstream in("/proc/cpuinfo");
    for (std::string line; std::getline(in, line);) {
        const auto colon = line.find(':');
        if (line.rfind("model name", 0) != 0 || colon == std::string::npos) continue;
        const auto from = line.find_first_not_of(" \t", colon + 1);
        if (from != std::string::npos) return common::printable(line.substr(from));
    }
    return "unknown";
}

/** Writes the overrides into the INI as read (never into the file), each first checked as
 *  a line of the INI would be: a section mrloc reads, a well-formed key and value. Their
 *  values then meet the section's own checks (range, unknown key) as the INI's do. */
void applyOverrides(const method::Registry& registry, mrpt::config::CConfigFile& ini,
                    const std::vector<KeyOverride>& overrides) {
    std::set<std::string> given;  // a key given twice: which value is meant?
    for (const auto& o : overrides) {
        const std::string origin = o.from + " " + common::printable(o.text());
        std::string name = o.section + "." + o.key;
        for (char& c : name) c = char(std::tolower(static_cast<unsigned char>(c)));
        if (!given.insert(name).second)
            throw Error(origin + ": " + common::printable(o.section + "." + o.key) +
                        " is given twice (--set and --grid give each key once)");
        if (!isMrlocSection(o.section, registry))
            throw Error(origin + ": [" + common::printable(o.section) +
                        "] is not a section mrloc reads (sections: scenario, world, "
                        "robot.<name>, report and the methods'; doc/ini.md)");
        common::lintIni("[" + o.section + "]\n" + o.key + " = " + o.value + "\n", origin,
                        [](const std::string&) { return true; });
        ini.write(o.section, o.key, o.value);
    }
    ini.discardSavingChanges();
}

Setup loadSetupUnguarded(const method::Registry& registry, const std::string& iniPath,
                         std::optional<long> seed, bool needSimulation, const std::string& rawlog,
                         const std::vector<KeyOverride>& overrides) {
    Setup s;
    s.iniPath = iniPath;
    s.iniText = readIniText(iniPath);
    s.ini = openIni(iniPath, s.iniText, registry);
    // MRPT's sections are MRPT's apps' too: a near miss of a key mrloc reads there is a
    // warning, not an error
    s.warnings = mrptKeyWarnings(*s.ini, iniPath);
    applyOverrides(registry, *s.ini, overrides);
    s.scenario.loadFromConfigFile(*s.ini, "scenario");
    if (seed) {
        if (*seed < 0 || *seed > long(common::kMaxSeed))
            throw Error("--seed must be in [0, " + std::to_string(common::kMaxSeed) + "]");
        s.scenario.seed = (unsigned long)*seed;
        // one resolved configuration: everything downstream (the localizer, the scenario,
        // the experiment, effective.ini) reads the seed the run uses; never saved to the file
        s.ini->write("scenario", "seed", std::to_string(*seed));
        s.ini->discardSavingChanges();
    }
    // an INI without a name (MRPT's, a user's) is named after its file: runs of two such INIs
    // go to two folders, not both to out/run
    if (!s.ini->keyExists("scenario", "name")) s.scenario.name = nameFromFile(iniPath);
    common::checkName(s.scenario.name, s.iniPath + ": [scenario] name");
    if (s.scenario.method.empty()) {
        // an MRPT app's INI for a task mrloc does not do: say so, and what would fit its log
        if (const auto app = mrptAppOf(*s.ini))
            throw Error(foreignIniAdvice(registry, iniPath, *app,
                                         rawlog.empty() ? rawlogNamedBy(*s.ini, iniPath) : rawlog));
        s.scenario.method = methodOfSections(registry, *s.ini);
    }
    s.method = &registry.get(s.scenario.method);
    s.localizer = s.method->localizer();
    s.localizer->configure(*s.ini);
    const bool simulates = sim::ScenarioOptions::describesSimulation(*s.ini, "scenario");
    if (needSimulation && !simulates)
        // an INI for a log recorded elsewhere (config/beacons_librsf.ini): say which command
        // reads it, not which simulation key is missing
        throw Error(iniPath +
                    ": describes no simulation ([scenario] holds no robots, world or duration): "
                    "it localizes a log recorded elsewhere: mrloc localize " +
                    common::shellArgument(iniPath) + " <rawlog>");
    if (needSimulation || simulates) {
        s.simulation = s.method->scenario(*s.ini, *s.localizer);
        s.simulation->config.scenario.seed = s.scenario.seed;
        s.simulation->config.scenario.name = s.scenario.name;  // the INI's, or its file's
    }
    s.reportOptions.loadFromConfigFile(*s.ini, "report");
    return s;
}

}  // namespace

KeyOverride parseOverride(const std::string& text, const std::string& what) {
    const auto eq = text.find('=');
    const auto dot = eq == std::string::npos ? eq : text.rfind('.', eq);
    if (eq == std::string::npos || dot == std::string::npos || dot == 0 || dot + 1 == eq)
        throw Error(what + " " + common::printable(text) +
                    ": expected section.key=value (scenario.duration=60, robot.r1.speed=0.3)");
    KeyOverride o{text.substr(0, dot), text.substr(dot + 1, eq - dot - 1), text.substr(eq + 1),
                  what};
    for (const char c : o.section + o.key)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '.' && c != '-')
            throw Error(what + " " + common::printable(text) + ": a section or key name holds '" +
                        common::printable(std::string(1, c)) +
                        "' (letters, digits, '_', '-', '.')");
    if (o.value.size() > 1000 || o.value.find_first_of("\n\r") != std::string::npos)
        throw Error(what + " " + common::printable(text.substr(0, 80)) +
                    ": a value is one line of at most 1,000 characters");
    std::string section = o.section, key = o.key;
    for (char& c : section) c = char(std::tolower(static_cast<unsigned char>(c)));
    for (char& c : key) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (section == "scenario" && key == "seed")
        throw Error(what + " scenario.seed: the seed is --seed's (mrloc batch: --seeds A..B)");
    return o;
}

Setup loadSetup(const method::Registry& registry, const std::string& iniPath,
                std::optional<long> seed, bool needSimulation, const std::string& rawlog,
                const std::vector<KeyOverride>& overrides) {
    try {
        return loadSetupUnguarded(registry, iniPath, seed, needSimulation, rawlog, overrides);
    } catch (const Error& e) {
        // a key --set gave is named as --set gave it, not as the INI's
        const std::string what = e.what();
        for (const auto& o : overrides) {
            const std::string tag = iniPath + ": [" + o.section + "] " + o.key + ": ";
            if (what.rfind(tag, 0) == 0)
                throw Error(o.from + " " + common::printable(o.text()) + ": " +
                            what.substr(tag.size()));
        }
        throw;
    } catch (const std::exception& e) {
        throw Error(iniPath + ": " + oneLine(e.what()));
    }
}

std::vector<method::WorkItem> workOf(const Setup& s, bool simulating, bool localizing) {
    std::vector<method::WorkItem> items;
    const sim::ScenarioConfig* scenario = s.simulation ? &s.simulation->config : nullptr;
    if (simulating && scenario) {
        // the simulator's own part, whatever the method: its robots' motion, odometry and
        // ground truth. quickstart.ini measured 3.4 us per robot and step with its beacons'
        // sensing (doc/errors.md, "Work"); the motion alone is taken as 2 us, each method
        // adding its sensing
        constexpr double kSecondsPerRobotStep = 2e-6;
        const double steps = scenario->scenario.duration / scenario->scenario.dt;
        method::WorkItem w;
        w.what = "the simulation";
        w.keys = "[scenario] duration / dt x robots";
        w.seconds =
            steps * double(std::max<size_t>(1, scenario->robots.size())) * kSecondsPerRobotStep;
        w.simulation = true;
        items.push_back(w);
    }
    if (s.method->work)
        for (auto& w : s.method->work(*s.localizer, scenario))
            if ((w.simulation && simulating) || (!w.simulation && localizing))
                items.push_back(std::move(w));
    return items;
}

std::string effectiveIni(const Setup& s) {
    mrpt::config::CConfigFileMemory eff;
    std::vector<std::string> sections;
    s.ini->getAllSections(sections);
    for (const auto& section : sections) {
        std::vector<std::string> keys;
        s.ini->getAllKeys(section, keys);
        for (const auto& k : keys) eff.write(section, k, s.ini->read_string(section, k, ""));
    }
    if (s.simulation) {
        s.simulation->config.save(eff);
        if (s.simulation->saveOptions) s.simulation->saveOptions(eff);
    } else {
        // no simulation: only what `localize` reads, so that the file runs again as is
        s.scenario.saveLocalizeKeys(eff, "scenario");
    }
    s.localizer->saveConfig(eff);
    s.reportOptions.saveToConfigFile(eff, "report");
    return eff.getContent();
}

namespace {

/** "[section] key = value" for each `*_seed` key of the INI, comma-separated. */
std::string seedOverrides(const mrpt::config::CConfigFileBase& ini) {
    std::string out;
    std::vector<std::string> sections, keys;
    ini.getAllSections(sections);
    for (const auto& section : sections) {
        ini.getAllKeys(section, keys);
        for (const auto& key : keys)
            if (key.size() > 5 && key.compare(key.size() - 5, 5, "_seed") == 0)
                out += (out.empty() ? "" : ", ") + ("[" + section + "] " + key + " = ") +
                       ini.read_string(section, key, "");
    }
    return out;
}

}  // namespace

void writeProvenance(const Setup& s, const std::string& dir, const std::string& step,
                     const std::string& command, const std::string& rawlog) {
    common::makeDirectories(dir);
    common::writeFileAtomically(common::run_dir::configCopy(dir), s.iniText);
    common::writeFileAtomically(common::run_dir::effectiveIni(dir), effectiveIni(s));
    nlohmann::json p = nlohmann::json::object();
    const std::string path = common::run_dir::provenance(dir);
    // an object (readProvenanceFile refuses anything else)
    if (fs::is_regular_file(fs::symlink_status(path))) p = common::readProvenanceFile(path);
    if (!p.contains("steps") || !p["steps"].is_object()) p["steps"] = nlohmann::json::object();
    p["ini"] = s.iniPath;
    p["seed"] = s.scenario.seed;
    // the sub-seeds the INI fixes instead of drawing them from the run's seed (common/Seeds.h)
    if (const auto fixed = seedOverrides(*s.ini); !fixed.empty())
        p["seed_overrides"] = fixed;
    else
        p.erase("seed_overrides");
    p["version"] = kVersion;
    p["steps"][step] = command;
    // what made the run, for a reader comparing figures and timings across machines
    p["commit"] = kCommit;
    p["mrpt_version"] = mrpt::system::MRPT_getVersion();
    p["date_utc"] = utcNow();
    p["cpu"] = cpuModel();
    p["cores"] = std::max(1u, std::thread::hardware_concurrency());
    if (step == "simulate" || step == "run") p["simulated"] = true;
    if (!rawlog.empty())
        p["rawlog"] = rawlog;
    else if (step != "report")
        p.erase("rawlog");
    common::saveJson(path, p);
}

namespace {
/** Two paths name the same file (both as seen from here). */
bool sameFile(const std::string& a, const std::string& b) {
    std::error_code ec1, ec2;
    const auto ca = fs::weakly_canonical(a, ec1), cb = fs::weakly_canonical(b, ec2);
    return ec1 || ec2 ? a == b : ca == cb;
}
}  // namespace

std::string replacedRunNote(const std::string& dir, const std::string& iniPath,
                            const std::string& rawlog) {
    const std::string path = common::run_dir::provenance(dir);
    if (!fs::is_regular_file(fs::symlink_status(path))) return "";
    nlohmann::json p;
    try {
        p = common::readProvenanceFile(path);
    } catch (const Error&) {
        return "";  // the transaction names what is wrong with the folder
    }
    const std::string ini = p.value("ini", "");
    const bool rawlogs = !rawlog.empty() && p.contains("rawlog") && p["rawlog"].is_string();
    const std::string was = rawlogs ? p["rawlog"].get<std::string>() : "";
    if (!ini.empty() && !sameFile(ini, iniPath))
        return dir + " holds a run of " + common::printable(ini) + "; this one, of " + iniPath +
               ", replaces it (--out DIR keeps both)";
    if (rawlogs && !sameFile(was, rawlog))
        return dir + " holds a run on " + common::printable(was) + "; this one, on " + rawlog +
               ", replaces it (--out DIR keeps both)";
    return "";
}

std::string nameFromFile(const std::string& path) {
    std::string name = fs::path(path).stem().string().substr(0, 64);
    for (char& c : name)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.'))
            c = '_';
    if (!name.empty() && (name.front() == '-' || name.front() == '.')) name.front() = '_';
    return name.empty() ? "run" : name;
}

std::string checkIni(const method::Registry& registry, const std::string& iniPath) {
    return effectiveIni(loadSetup(registry, iniPath, std::nullopt, false));
}

}  // namespace mrloc::app
