#include "Commands.h"

#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/IniLint.h>
#include <mrloc/common/IniSection.h>
#include <mrloc/common/LocalizationRun.h>
#include <mrloc/common/Metrics.h>
#include <mrloc/common/Names.h>
#include <mrloc/common/RunDirectory.h>
#include <mrloc/common/RunTransaction.h>
#include <mrloc/common/Version.h>
#include <mrloc/report/ReportOptions.h>
#include <mrloc/sim/Simulator.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <set>
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

/** [scenario] keys that do not describe a simulation: an MRPT INI may get a [scenario] with
 *  these for `mrloc localize` (the method, a ground-truth file), and effective.ini of such a
 *  run keeps only these. */
bool localizeOnlyKey(const std::string& key) {
    static const std::set<std::string> keys{"name",
                                            "method",
                                            "seed",
                                            "ground_truth",
                                            "ground_truth_format",
                                            "ground_truth_robot",
                                            "ground_truth_offset"};
    return keys.count(key) > 0;
}

/** [scenario] describes a simulation unless it holds only localizeOnlyKey keys. */
bool describesSimulation(const mrpt::config::CConfigFileBase& ini) {
    if (!ini.sectionExists("scenario")) return false;
    std::vector<std::string> keys;
    ini.getAllKeys("scenario", keys);
    for (const auto& k : keys)
        if (!localizeOnlyKey(k)) return true;
    return keys.empty();
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

/** --out and --quiet, shared by the commands that write a run directory. */
struct OutputArgs {
    TCLAP::ValueArg<std::string> out{
        "o", "out", "output directory (default: out/<scenario name>)", false, "", "DIR"};
    TCLAP::SwitchArg quiet{"q", "quiet", "no progress bar, only errors"};
    std::string dirOr(const std::string& name) {
        const std::string dir = out.isSet() ? out.getValue() : "out/" + name;
        common::checkRunFolderPath(dir, out.isSet() ? "--out" : "[scenario] name");
        return dir;
    }
};

std::string commandLine(int argc, char** argv) {
    std::string s = "mrloc";
    for (int i = 0; i < argc; ++i) s += std::string(" ") + argv[i];
    return s;
}

/** Everything one INI asks for, read and validated before anything is written. */
struct Setup {
    std::string iniPath;
    std::string iniText;  ///< the file as read, copied to config.ini
    std::unique_ptr<mrpt::config::CConfigFile> ini;
    sim::ScenarioOptions scenario;  ///< [scenario], with --seed applied
    const method::Method* method = nullptr;
    std::unique_ptr<common::Localizer> localizer;  ///< configured
    /** Built when the INI describes a simulation (it has [scenario]). */
    std::optional<method::Scenario> simulation;
    report::ReportOptions reportOptions;
};

Setup loadSetupUnguarded(const method::Registry& registry, const std::string& iniPath,
                         std::optional<long> seed, bool needSimulation) {
    Setup s;
    s.iniPath = iniPath;
    s.iniText = readIniText(iniPath);
    s.ini = openIni(iniPath, s.iniText, registry);
    s.scenario.loadFromConfigFile(*s.ini, "scenario");
    if (seed) {
        if (*seed < 0 || *seed > 4294967295L) throw Error("--seed must be in [0, 4294967295]");
        s.scenario.seed = (unsigned long)*seed;
        // one resolved configuration: everything downstream (the localizer, the scenario,
        // the experiment, effective.ini) reads the seed the run uses; never saved to the file
        s.ini->write("scenario", "seed", std::to_string(*seed));
        s.ini->discardSavingChanges();
    }
    common::checkName(s.scenario.name, s.iniPath + ": [scenario] name");
    if (s.scenario.method.empty()) s.scenario.method = methodOfSections(registry, *s.ini);
    s.method = &registry.get(s.scenario.method);
    s.localizer = s.method->localizer();
    s.localizer->configure(*s.ini);
    if (needSimulation || describesSimulation(*s.ini)) {
        s.simulation = s.method->scenario(*s.ini, *s.localizer);
        s.simulation->config.scenario.seed = s.scenario.seed;
    }
    s.reportOptions.loadFromConfigFile(*s.ini, "report");
    return s;
}

/** Everything read from an INI fails as mrloc::Error naming the INI: MRPT's parser throws its
 *  own exceptions (a `$env{` without its `}`, say), without the file's name. */
Setup loadSetup(const method::Registry& registry, const std::string& iniPath,
                std::optional<long> seed, bool needSimulation) {
    try {
        return loadSetupUnguarded(registry, iniPath, seed, needSimulation);
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error(iniPath + ": " + oneLine(e.what()));
    }
}

/** effective.ini: every section of the INI as given (MRPT's own sections too), then every
 *  section mrloc reads rewritten with its defaults filled in. `simulate`, `localize` and
 *  `run` write the same file for the same INI and seed. */
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
        mrpt::config::CConfigFileMemory all;
        s.scenario.saveToConfigFile(all, "scenario");
        std::vector<std::string> keys;
        all.getAllKeys("scenario", keys);
        for (const auto& k : keys)
            if (localizeOnlyKey(k)) eff.write("scenario", k, all.read_string("scenario", k, ""));
    }
    s.localizer->saveConfig(eff);
    s.reportOptions.saveToConfigFile(eff, "report");
    return eff.getContent();
}

/** config.ini (a copy of the INI), effective.ini and provenance.json, with this step's
 *  command line added to the steps already recorded there. */
void writeProvenance(const Setup& s, const std::string& dir, const std::string& step,
                     const std::string& command) {
    common::makeDirectories(dir);
    common::writeFileAtomically(common::run_dir::configCopy(dir), s.iniText);
    common::writeFileAtomically(common::run_dir::effectiveIni(dir), effectiveIni(s));
    nlohmann::json p = nlohmann::json::object();
    const std::string path = common::run_dir::provenance(dir);
    if (fs::is_regular_file(fs::symlink_status(path))) p = common::loadJson(path);
    if (!p.is_object()) p = nlohmann::json::object();  // not ours: begun again
    if (!p.contains("steps") || !p["steps"].is_object()) p["steps"] = nlohmann::json::object();
    p["ini"] = s.iniPath;
    p["seed"] = s.scenario.seed;
    p["version"] = kVersion;
    p["steps"][step] = command;
    common::saveJson(path, p);
}

std::string doSimulate(Setup& s, const std::string& dir, bool quiet) {
    const auto files =
        sim::simulateToFiles(s.simulation->config, dir, quiet, s.simulation->payload.get());
    return files.rawlog;
}

/** `rawlogShownAs`: the rawlog's path as metrics.json records it (the run folder's, not the
 *  staging folder's, for a rawlog this command simulated). */
void doLocalize(Setup& s, const std::string& rawlog, const std::string& dir, bool quiet,
                const std::string& rawlogShownAs) {
    const std::string& name = s.method->name;
    common::LocalizationRunOptions options{name, rawlog, dir, quiet, s.scenario.groundTruth};
    options.rawlogShownAs = rawlogShownAs;
    const auto result = common::runLocalization(*s.localizer, options);
    if (s.method->experiment)
        s.method->experiment({*s.ini, *s.localizer, result.truth, dir, s.scenario.seed});
    if (quiet) return;
    const auto& m = result.metrics;
    std::cerr << "localized " << m["observations"] << " observations with '" << name << "'";
    if (m.value("ground_truth", false))
        std::cerr << ": RMSE " << m["rmse_m"].get<double>() << " m, max "
                  << m["max_m"].get<double>() << " m over " << m["n"] << " estimates";
    std::cerr << "\n";
}

std::string doReport(const method::Registry& registry, const std::string& dir) {
    const std::string metricsPath = common::run_dir::metrics(dir);
    if (!fs::exists(metricsPath))
        throw Error(dir + ": not a run directory (no metrics.json; run `mrloc localize` first)");
    const auto metrics = common::loadJson(metricsPath);
    const std::string name = metrics.value("method", "");
    if (!registry.has(name))
        throw Error(metricsPath + ": method '" + name + "' is not one this mrloc knows");
    return report::makeReport(dir, registry.get(name).report);
}

std::optional<long> seedOf(TCLAP::ValueArg<long>& seed) {
    return seed.isSet() ? std::optional<long>(seed.getValue()) : std::nullopt;
}

}  // namespace

std::string checkIni(const method::Registry& registry, const std::string& iniPath) {
    return effectiveIni(loadSetup(registry, iniPath, std::nullopt, false));
}

std::optional<int> parseArgs(TCLAP::CmdLine& cmd, int argc, char** argv) {
    if (cmd.parse(argc, argv)) return std::nullopt;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--help" || a == "-h" || a == "--version") return 0;
    }
    return 2;
}

namespace {

/** The command line of the commands that simulate an INI: <ini> [--seed] [--out] [-q]. */
struct ScenarioCommand {
    TCLAP::CmdLine cmd;
    TCLAP::UnlabeledValueArg<std::string> ini{"ini", "scenario INI file", true, "", "INI", cmd};
    TCLAP::ValueArg<long> seed{"s", "seed", "random seed (overrides [scenario] seed)", false, 0,
                               "N", cmd};
    OutputArgs output;

    explicit ScenarioCommand(const std::string& description) : cmd(description, ' ', kVersion) {
        cmd.add(output.out);
        cmd.add(output.quiet);
    }
    Setup setup(const method::Registry& registry) {
        return loadSetup(registry, ini.getValue(), seedOf(seed), true);
    }
};

}  // namespace

int simulate(const method::Registry& registry, int argc, char** argv) {
    ScenarioCommand c(
        "mrloc simulate: simulate the INI's scenario into a rawlog "
        "(<out>/<name>.rawlog), ground truth (<out>/<name>.<robot>.gt.txt) and "
        "effective.ini");
    if (const auto code = parseArgs(c.cmd, argc, argv)) return *code;
    Setup s = c.setup(registry);
    const std::string dir = c.output.dirOr(s.scenario.name);
    common::RunTransaction tx(dir, "simulate");
    std::string rawlog;
    try {
        rawlog = doSimulate(s, tx.staging(), c.output.quiet.getValue());
        writeProvenance(s, tx.staging(), "simulate", commandLine(argc, argv));
        tx.commit();
    } catch (const Error& e) {
        throw Error(tx.inFolderTerms(e.what()));
    }
    std::cout << (fs::path(dir) / fs::path(rawlog).filename()).string() << "\n";
    return 0;
}

int localize(const method::Registry& registry, int argc, char** argv) {
    TCLAP::CmdLine cmd(
        "mrloc localize: run the INI's method ([scenario] method; without it, the "
        "method whose section the INI holds, or whose MRPT sections it holds) on any MRPT rawlog, "
        "in "
        "either rawlog format. Ground truth "
        "is taken from <rawlog stem>.<robot>.gt.txt when present.",
        ' ', kVersion);
    TCLAP::UnlabeledValueArg<std::string> iniArg("ini", "INI file", true, "", "INI", cmd);
    TCLAP::UnlabeledValueArg<std::string> rawlog("rawlog", "rawlog file", true, "", "RAWLOG", cmd);
    OutputArgs o;
    cmd.add(o.out);
    cmd.add(o.quiet);
    if (const auto code = parseArgs(cmd, argc, argv)) return *code;
    if (looksLikeRawlog(iniArg.getValue()) && !looksLikeRawlog(rawlog.getValue())) {
        std::cerr << "mrloc localize: the arguments are swapped: the INI comes first, "
                     "mrloc localize <ini> <rawlog> ("
                  << iniArg.getValue() << " is a rawlog)\n";
        return 2;
    }
    Setup s = loadSetup(registry, iniArg.getValue(), std::nullopt, false);
    const std::string dir = o.dirOr(s.scenario.name);
    common::RunTransaction tx(dir, "localize");
    try {
        doLocalize(s, rawlog.getValue(), tx.staging(), o.quiet.getValue(), rawlog.getValue());
        writeProvenance(s, tx.staging(), "localize", commandLine(argc, argv));
        tx.commit();
    } catch (const Error& e) {
        throw Error(tx.inFolderTerms(e.what()));
    }
    std::cout << dir << "\n";
    return 0;
}

int report(const method::Registry& registry, int argc, char** argv) {
    TCLAP::CmdLine cmd(
        "mrloc report: render report.html and its pictures in a directory written by "
        "`mrloc localize`",
        ' ', kVersion);
    TCLAP::UnlabeledValueArg<std::string> dir("run-dir", "run directory", true, "", "DIR", cmd);
    if (const auto code = parseArgs(cmd, argc, argv)) return *code;
    if (!fs::is_regular_file(fs::symlink_status(common::run_dir::metrics(dir.getValue()))))
        throw Error(dir.getValue() +
                    ": not a run directory (no metrics.json; run `mrloc localize` first)");
    common::RunTransaction tx(dir.getValue(), "report");
    std::string page;
    try {
        page = doReport(registry, tx.staging());
        tx.commit();
    } catch (const Error& e) {
        throw Error(tx.inFolderTerms(e.what()));
    }
    std::cout << (fs::path(dir.getValue()) / fs::path(page).filename()).string() << "\n";
    return 0;
}

int run(const method::Registry& registry, int argc, char** argv) {
    ScenarioCommand c(
        "mrloc run: simulate, localize and report in a row; everything goes to "
        "<out> (default out/<scenario name>)");
    if (const auto code = parseArgs(c.cmd, argc, argv)) return *code;
    Setup s = c.setup(registry);
    const std::string dir = c.output.dirOr(s.scenario.name);
    common::RunTransaction tx(dir, "run");
    try {
        const std::string rawlog = doSimulate(s, tx.staging(), c.output.quiet.getValue());
        doLocalize(s, rawlog, tx.staging(), c.output.quiet.getValue(),
                   (fs::path(dir) / fs::path(rawlog).filename()).string());
        writeProvenance(s, tx.staging(), "run", commandLine(argc, argv));
        doReport(registry, tx.staging());
        tx.commit();
    } catch (const Error& e) {
        // The files named in the message are the run's own, removed with the rest of it.
        throw Error(s.iniPath + " (" + dir + " left as it was): " + tx.inFolderTerms(e.what()));
    }
    std::cout << "report: " << common::run_dir::report(dir) << "\n";
    return 0;
}

namespace {
constexpr const char* kUsage =
    "usage: mrloc <command> [options]   (mrloc <command> --help for details)\n"
    "\n"
    "commands:\n"
    "  simulate <ini>           simulate the INI's scenario into a rawlog + ground truth\n"
    "  localize <ini> <rawlog>  run the INI's method on any MRPT rawlog\n"
    "  report <run-dir>         render report.html and pictures of a localize run\n"
    "  run <ini>                simulate, localize and report in a row\n"
    "  info <rawlog>            per robot and sensor label: class, count, rate, time span\n";
}  // namespace

int main(const method::Registry& registry, int argc, char** argv) {
    common::installSignalCleanup();
    if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h")) {
        std::cout << kUsage;
        return argc < 2 ? 2 : 0;
    }
    const std::string command = argv[1];
    try {
        if (command == "simulate") return simulate(registry, argc - 1, argv + 1);
        if (command == "localize") return localize(registry, argc - 1, argv + 1);
        if (command == "report") return report(registry, argc - 1, argv + 1);
        if (command == "run") return run(registry, argc - 1, argv + 1);
        if (command == "info") return info(argc - 1, argv + 1);
        std::cerr << "mrloc: unknown command '" << command << "'\n" << kUsage;
        return 2;
    } catch (const TCLAP::ArgException& e) {
        std::cerr << "mrloc " << command << ": " << e.error() << " (" << e.argId() << ")\n"
                  << "see: mrloc " << command << " --help\n";
        return 2;
    } catch (const mrloc::Error& e) {
        std::cerr << "mrloc " << command << ": error: " << oneLine(e.what()) << "\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "mrloc " << command << ": unexpected error: " << oneLine(e.what()) << "\n";
        return 1;
    }
}

}  // namespace mrloc::app
