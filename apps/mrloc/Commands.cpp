// The verbs: their command lines, and each step run as a transaction on its run folder
// (common::RunTransaction). Reading the INI is IniFile's, resolving it RunSetup's.
#include "Commands.h"

#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/FolderLock.h>
#include <mrloc/common/LocalizationRun.h>
#include <mrloc/common/Log.h>
#include <mrloc/common/Metrics.h>
#include <mrloc/common/Outcome.h>
#include <mrloc/common/ParallelFor.h>
#include <mrloc/common/RunDirectory.h>
#include <mrloc/common/RunTransaction.h>
#include <mrloc/common/Version.h>
#include <mrloc/report/Index.h>
#include <mrloc/sim/Simulator.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>

#include "Advice.h"
#include "BatchPlan.h"
#include "BatchSummary.h"
#include "IniFile.h"
#include "KeysDoc.h"
#include "MrptTruth.h"
#include "RunSetup.h"
#include "StderrLog.h"

namespace mrloc::app {

namespace fs = std::filesystem;

namespace {

/** --out and --quiet, shared by the commands that write a run directory. */
constexpr long kMaxThreads = 1024;
constexpr const char* kThreadsHelp =
    "threads for the experiments and searches (default: every core); the work estimate "
    "divides by the same number";

struct OutputArgs {
    TCLAP::ValueArg<std::string> out{
        "o", "out", "output directory (default: out/<scenario name>)", false, "", "DIR"};
    TCLAP::SwitchArg quiet{"q", "quiet", "no progress bar, only errors"};
    TCLAP::ValueArg<long> threads{"", "threads", kThreadsHelp, false, 0, "N"};
    void addTo(TCLAP::CmdLine& cmd) {
        cmd.add(out);
        cmd.add(quiet);
        cmd.add(threads);
    }
    /** Every parallelFor of this process runs on --threads threads, when given. */
    void applyThreads() {
        if (!threads.isSet()) return;
        if (threads.getValue() < 1 || threads.getValue() > kMaxThreads)
            throw Error("--threads must be 1 to " + std::to_string(kMaxThreads));
        common::setThreadCount(unsigned(threads.getValue()));
    }
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

/** Refuses work beyond the budget before anything is written; announces long work. */
void checkWorkOf(const Setup& s, bool simulating, bool localizing, bool quiet) {
    const auto line = method::checkWork(workOf(s, simulating, localizing), common::threadCount());
    if (line && !quiet) std::cerr << "mrloc: " << *line << "\n";
}

std::string doSimulate(Setup& s, const std::string& dir, const common::Log& log) {
    const auto files =
        sim::simulateToFiles(s.simulation->config, dir, log, s.simulation->payload.get());
    // The payload's on-board parts (formation's camera among them) go now, while their EGL
    // context lives: MRPT's CFBORender terminates the EGL display every renderer shares
    // when it is destroyed, so a camera that outlived the experiment's cameras or the
    // report's renderer threw from its destructor at exit (exit 134, issue 31).
    s.simulation->payload.reset();
    return files.rawlog;
}

/** `rawlogShownAs`: the rawlog's path as metrics.json records it (the run folder's, not the
 *  staging folder's, for a rawlog this command simulated). Returns the method's headline,
 *  also written into metrics.json. */
common::Headline doLocalize(const method::Registry& registry, Setup& s, const std::string& rawlog,
                            const std::string& dir, const common::Log& log,
                            const std::string& rawlogShownAs) {
    const std::string& name = s.method->name;
    common::LocalizationRunOptions options{name, rawlog, dir, &log, s.scenario.groundTruth};
    if (options.groundTruth.path.empty() && !s.simulation) {
        // a log recorded elsewhere: its truth where MRPT's apps look for it
        std::string note;
        if (const auto found = mrptTruthOf(*s.ini, s.iniPath, rawlog, note)) {
            options.groundTruth = found->source;
            options.groundTruthFrom = found->from;
        }
        if (!note.empty() && log.showsProgress()) std::cerr << "note: " << note << "\n";
    }
    options.rawlogShownAs = rawlogShownAs;
    options.fitHint = [&registry, &name](const std::map<std::string, size_t>& classes) {
        return fitHintOf(registry, name, classes);
    };
    auto result = common::runLocalization(*s.localizer, options);
    const sim::ScenarioConfig* scenario = s.simulation ? &s.simulation->config : nullptr;
    if (s.method->experiment)
        s.method->experiment({*s.localizer, scenario, result.truth, dir, s.scenario.seed, log});
    auto headline = s.method->headline({*s.localizer, scenario, result.metrics, dir});
    if (result.metrics["robots"].empty() && headline.reached) {
        // whatever the method's figures, a run without a single estimate reached nothing
        headline.reached = false;
        headline.status = "no estimate";
    }
    result.metrics["headline"] = common::toJson(headline);
    common::saveJson(common::run_dir::metrics(dir), result.metrics);
    return headline;
}

}  // namespace

common::Headline simulateAndLocalize(const method::Registry& registry, Setup& s,
                                     const std::string& dir) {
    const StderrLog log(true);  // a trial's warnings, and no progress
    const std::string rawlog = doSimulate(s, dir, log);
    return doLocalize(registry, s, rawlog, dir, log, rawlog);
}

namespace {

std::string doReport(const method::Registry& registry, const std::string& dir) {
    const std::string metricsPath = common::run_dir::metrics(dir);
    if (!fs::exists(metricsPath))
        throw Error(dir + ": not a run directory (no metrics.json; run `mrloc localize` first)");
    const auto metrics = common::readMetricsFile(metricsPath);
    const std::string name = metrics.value("method", "");
    if (!registry.has(name))
        throw Error(metricsPath + ": method '" + name + "' is not one this mrloc knows");
    try {
        return report::makeReport(dir, registry.get(name).report);
    } catch (const nlohmann::json::exception& e) {
        // a method's section reads its own part of metrics.json: a file from elsewhere
        // holding another type there is named, not an "unexpected error"
        throw Error(metricsPath + ": a value of another type than mrloc writes there (" +
                    oneLine(e.what()) + ")");
    }
}

std::optional<long> seedOf(TCLAP::ValueArg<long>& seed) {
    return seed.isSet() ? std::optional<long>(seed.getValue()) : std::nullopt;
}

}  // namespace

std::string checkIni(const method::Registry& registry, const std::string& iniPath) {
    return effectiveIni(loadSetup(registry, iniPath, std::nullopt, false));
}

namespace {

/** TCLAP's "(required)  INI file" without its tag: the message says "missing" already. */
std::string withoutRequiredTag(std::string description) {
    const std::string tag = "(required)";
    if (description.rfind(tag, 0) == 0) description.erase(0, tag.size());
    const auto text = description.find_first_not_of(' ');
    return text == std::string::npos ? description : description.substr(text);
}

/** TCLAP's usage errors in one line that names what is wrong ("missing <RAWLOG> (rawlog
 *  file)"), then the usage; TCLAP's own says "One or more required arguments missing!"
 *  without naming them. */
class OneLineOutput : public TCLAP::StdOutput {
 public:
    void failure(TCLAP::CmdLineInterface& c, TCLAP::ArgException& e) override {
        const std::string command = "mrloc " + c.getProgramName();
        std::string missing;
        for (const TCLAP::Arg* a : c.getArgList())
            if (a->isRequired() && !a->isSet())
                missing += (missing.empty() ? "" : ", ") + a->shortID() + " (" +
                           withoutRequiredTag(a->getDescription()) + ")";
        std::string what = e.error();
        if (what.find("required arguments missing") != std::string::npos && !missing.empty())
            what = "missing " + missing;
        else if (!e.argId().empty() && e.argId() != " ")
            what += ": " + e.argId();
        std::cerr << command << ": " << what << "\n"
                  << "usage: " << command;
        for (const TCLAP::Arg* a : c.getArgList())
            if (a->isRequired()) std::cerr << " " << a->shortID();
        std::cerr << " [options]   (" << command << " --help)\n";
    }
};

}  // namespace

std::optional<int> parseArgs(TCLAP::CmdLine& cmd, int argc, char** argv) {
    static OneLineOutput output;
    // TCLAP deletes only the output it made itself, and only when none was set
    delete cmd.getOutput();
    cmd.setOutput(&output);
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
        output.addTo(cmd);
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
    c.output.applyThreads();
    Setup s = c.setup(registry);
    checkWorkOf(s, true, false, c.output.quiet.getValue());
    const std::string dir = c.output.dirOr(s.scenario.name);
    const StderrLog log(c.output.quiet.getValue());
    common::RunTransaction tx(dir, "simulate", log);
    std::string rawlog;
    try {
        rawlog = doSimulate(s, tx.staging(), log);
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
    o.addTo(cmd);
    if (const auto code = parseArgs(cmd, argc, argv)) return *code;
    o.applyThreads();
    if (looksLikeRawlog(iniArg.getValue()) && !looksLikeRawlog(rawlog.getValue())) {
        std::cerr << "mrloc localize: the arguments are swapped: the INI comes first, "
                     "mrloc localize <ini> <rawlog> ("
                  << iniArg.getValue() << " is a rawlog)\n";
        return 2;
    }
    checkNotAnIni(rawlog.getValue());
    Setup s = loadSetup(registry, iniArg.getValue(), std::nullopt, false, rawlog.getValue());
    checkWorkOf(s, false, true, o.quiet.getValue());
    const std::string dir = o.dirOr(s.scenario.name);
    const StderrLog log(o.quiet.getValue());
    common::RunTransaction tx(dir, "localize", log);
    common::Headline headline;
    try {
        headline = doLocalize(registry, s, rawlog.getValue(), tx.staging(), log, rawlog.getValue());
        writeProvenance(s, tx.staging(), "localize", commandLine(argc, argv));
        tx.commit();
    } catch (const Error& e) {
        throw Error(tx.inFolderTerms(e.what()));
    }
    // exit 0 whether or not the method reached its goal (the headline says which), unless it
    // failed on this input
    std::cout << dir << "\n" << common::headlineLine(s.method->name, headline) << "\n";
    return headline.failed ? common::kFailedExit : 0;
}

int report(const method::Registry& registry, int argc, char** argv) {
    TCLAP::CmdLine cmd(
        "mrloc report: render report.html and its pictures in a directory written by "
        "`mrloc localize`, or of a batch folder summed up by `mrloc batch --collect`",
        ' ', kVersion);
    TCLAP::UnlabeledValueArg<std::string> dir("run-dir", "run directory", true, "", "DIR", cmd);
    if (const auto code = parseArgs(cmd, argc, argv)) return *code;
    if (batch_dir::isBatch(dir.getValue())) {  // a batch folder: its summary, plotted
        common::FolderLock lock(dir.getValue());
        batch_dir::checkFolder(dir.getValue());
        std::cout << renderBatchReport(dir.getValue()) << "\n";
        return 0;
    }
    if (!fs::is_regular_file(fs::symlink_status(common::run_dir::metrics(dir.getValue()))))
        throw Error(dir.getValue() +
                    ": not a run directory (no metrics.json; run `mrloc localize` first)");
    // report reads the folder as it is: a link in it would be left out of the new run (the
    // transaction never follows one) and then missed as "no such file"; named instead
    common::checkFolderHoldsNoLink(dir.getValue(), "run folder", 100000);
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
    c.output.applyThreads();
    Setup s = c.setup(registry);
    checkWorkOf(s, true, true, c.output.quiet.getValue());
    const std::string dir = c.output.dirOr(s.scenario.name);
    const StderrLog log(c.output.quiet.getValue());
    common::RunTransaction tx(dir, "run", log);
    common::Headline headline;
    try {
        const std::string rawlog = doSimulate(s, tx.staging(), log);
        headline = doLocalize(registry, s, rawlog, tx.staging(), log,
                              (fs::path(dir) / fs::path(rawlog).filename()).string());
        writeProvenance(s, tx.staging(), "run", commandLine(argc, argv));
        doReport(registry, tx.staging());
        tx.commit();
    } catch (const Error& e) {
        // The files named in the message are the run's own, removed with the rest of it.
        throw Error(s.iniPath + " (" + dir + " left as it was): " + tx.inFolderTerms(e.what()));
    }
    std::cout << "report: " << common::run_dir::report(dir) << "\n"
              << common::headlineLine(s.method->name, headline) << "\n";
    return headline.failed ? common::kFailedExit : 0;
}

int index(int argc, char** argv) {
    TCLAP::CmdLine cmd(
        "mrloc index: index.html of a folder of run folders (./run.sh's tour): each run's "
        "headline beside the paper's figure, and a link to its report",
        ' ', kVersion);
    TCLAP::UnlabeledValueArg<std::string> dir("folder", "folder of run folders", true, "", "DIR",
                                              cmd);
    TCLAP::ValueArg<std::string> title("t", "title", "the page's title", false,
                                       "mrloc: five methods, five papers", "TEXT", cmd);
    if (const auto code = parseArgs(cmd, argc, argv)) return *code;
    if (!fs::is_directory(dir.getValue()))
        throw Error(common::pathInWords(dir.getValue()) + ": not a folder");
    std::cout << report::makeIndex(dir.getValue(), title.getValue()) << "\n";
    return 0;
}

int keys(const method::Registry& registry, int argc, char** argv) {
    TCLAP::CmdLine cmd(
        "mrloc keys: the INI keys of every section declared as a key table (name, default, "
        "unit, range, meaning), as doc/ini.md shows them",
        ' ', kVersion);
    TCLAP::UnlabeledValueArg<std::string> section("section", "one section only (polymap)", false,
                                                  "", "SECTION", cmd);
    TCLAP::ValueArg<std::string> update(
        "", "update", "rewrite the key tables between this Markdown file's markers", false, "",
        "FILE", cmd);
    TCLAP::ValueArg<std::string> check(
        "", "check", "exit 1 naming the file when its key tables differ from the code's", false, "",
        "FILE", cmd);
    if (const auto code = parseArgs(cmd, argc, argv)) return *code;
    for (auto* file : {&update, &check}) {
        if (!file->isSet()) continue;
        const std::string path = file->getValue();
        if (!fs::is_regular_file(path) || fs::file_size(path) > (16u << 20))
            throw Error(common::pathInWords(path) + ": not a Markdown file of at most 16 MiB");
        std::ifstream in(path, std::ios::binary);
        const std::string doc{std::istreambuf_iterator<char>(in), {}};
        const std::string updated = updateKeyDoc(registry, doc);
        if (file == &check) {
            if (updated != doc)
                throw Error(path + ": its key tables differ from the code's (mrloc keys --update " +
                            path + ")");
        } else if (updated != doc) {
            common::writeFileAtomically(path, updated);
            std::cout << path << "\n";
        }
        return 0;
    }
    std::cout << keysText(registry, section.getValue());
    return 0;
}

}  // namespace mrloc::app
