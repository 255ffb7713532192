// The verbs that make a run folder (simulate, localize, report, run), index and keys: their
// command lines, and their steps (RunSteps.h) run as one transaction on the run folder.
// Reading the INI is IniFile's, resolving it RunSetup's.
#include "Commands.h"

#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/FolderLock.h>
#include <mrloc/common/RunDirectory.h>
#include <mrloc/common/ShellWord.h>
#include <mrloc/report/Index.h>

#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "BatchPlan.h"
#include "BatchSummary.h"
#include "CommandLine.h"
#include "IniFile.h"
#include "KeysDoc.h"
#include "MrptSections.h"
#include "RunSetup.h"
#include "RunSteps.h"
#include "StderrLog.h"

namespace mrloc::app {

namespace fs = std::filesystem;

namespace {

/** "next: <command>" on stderr, unless --quiet: what a user runs after this step. */
void next(bool quiet, const std::string& command) {
    if (!quiet) std::cerr << "next: " << command << "\n";
}

/** The one line that says a default run folder made from another INI or rawlog is replaced. */
void noteReplacedRun(const StderrLog& log, const std::string& dir, const std::string& iniPath,
                     const std::string& rawlog = "") {
    if (const std::string note = replacedRunNote(dir, iniPath, rawlog); !note.empty())
        log.warning(note);
}

}  // namespace

int simulate(const method::Registry& registry, int argc, char** argv) {
    ScenarioCommand c(
        "mrloc simulate: simulate the INI's scenario into a rawlog "
        "(<out>/<name>.rawlog), ground truth (<out>/<name>.<robot>.gt.txt) and "
        "effective.ini");
    if (const auto code = parseArgs(c.cmd, argc, argv)) return *code;
    ThreadsArg::apply(c.output.threads);
    Setup s = loadSetup(registry, c.ini.getValue(), c.seedGiven(), true);
    checkWorkOf(s, true, false, c.output.quiet.getValue());
    const std::string dir = c.output.dirOr(s.scenario.name);
    const StderrLog log(c.output.quiet.getValue());
    for (const auto& w : s.warnings) log.warning(w);
    noteReplacedRun(log, dir, s.iniPath);
    std::string rawlog;
    inTransaction(dir, "simulate", log, [&](const std::string& staging) {
        rawlog = simulateStep(s, staging, log);
        writeProvenance(s, staging, "simulate", commandLine(argc, argv));
    });
    const std::string written = (fs::path(dir) / fs::path(rawlog).filename()).string();
    next(c.output.quiet.getValue(),
         "mrloc localize " + common::shellArgument(s.iniPath) + " " +
             common::shellArgument(written) +
             (c.output.out.isSet() ? " --out " + common::shellArgument(dir) : ""));
    std::cout << written << "\n";  // the last line: a script's
    return 0;
}

int localize(const method::Registry& registry, int argc, char** argv) {
    CommandLine cmd(
        "mrloc localize: run the INI's method ([scenario] method; without it, the "
        "method whose section the INI holds, or whose MRPT sections it holds) on any MRPT rawlog, "
        "in either rawlog format. Ground truth is taken from <rawlog stem>.<robot>.gt.txt when "
        "present.");
    TCLAP::UnlabeledValueArg<std::string> iniArg("ini", "INI file", true, "", "INI", cmd);
    TCLAP::UnlabeledValueArg<std::string> rawlog("rawlog", "rawlog file", true, "", "RAWLOG", cmd);
    OutputArgs o;
    o.addTo(cmd);
    if (const auto code = parseArgs(cmd, argc, argv)) return *code;
    ThreadsArg::apply(o.threads);
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
    for (const auto& w : s.warnings) log.warning(w);
    noteReplacedRun(log, dir, s.iniPath, rawlog.getValue());
    common::Headline headline;
    inTransaction(dir, "localize", log, [&](const std::string& staging) {
        headline = localizeStep(registry, s, rawlog.getValue(), staging, log, rawlog.getValue());
        writeProvenance(s, staging, "localize", commandLine(argc, argv), rawlog.getValue());
    });
    next(o.quiet.getValue(),
         "mrloc report " + common::shellArgument(dir) + "   (report.html and its pictures)");
    // exit 0 whether or not the method reached its goal (the headline says which), unless it
    // failed on this input; the headline stays the last line
    std::cout << dir << "\n" << common::headlineLine(s.method->name, headline) << "\n";
    return headline.failed ? common::kFailedExit : 0;
}

int report(const method::Registry& registry, int argc, char** argv) {
    CommandLine cmd(
        "mrloc report: render report.html and its pictures in a directory written by "
        "`mrloc localize`, or of a batch folder summed up by `mrloc batch --collect`");
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
    std::string page;
    inTransaction(dir.getValue(), "report", common::silentLog(),
                  [&](const std::string& staging) { page = reportStep(registry, staging); });
    std::cout << (fs::path(dir.getValue()) / fs::path(page).filename()).string() << "\n";
    return 0;
}

int run(const method::Registry& registry, int argc, char** argv) {
    ScenarioCommand c(
        "mrloc run: simulate, localize and report in a row; everything goes to "
        "<out> (default out/<scenario name>)");
    if (const auto code = parseArgs(c.cmd, argc, argv)) return *code;
    ThreadsArg::apply(c.output.threads);
    Setup s = loadSetup(registry, c.ini.getValue(), c.seedGiven(), true);
    checkWorkOf(s, true, true, c.output.quiet.getValue());
    const std::string dir = c.output.dirOr(s.scenario.name);
    const StderrLog log(c.output.quiet.getValue());
    for (const auto& w : s.warnings) log.warning(w);
    noteReplacedRun(log, dir, s.iniPath);
    common::Headline headline;
    // the files an error names are the run's own, removed with the rest of it
    inTransaction(
        dir, "run", log,
        [&](const std::string& staging) {
            const std::string rawlog = simulateStep(s, staging, log);
            headline = localizeStep(registry, s, rawlog, staging, log,
                                    (fs::path(dir) / fs::path(rawlog).filename()).string());
            writeProvenance(s, staging, "run", commandLine(argc, argv));
            reportStep(registry, staging);
        },
        s.iniPath + " (" + dir + " left as it was): ");
    std::cout << "report: " << common::run_dir::report(dir) << "\n"
              << common::headlineLine(s.method->name, headline) << "\n";
    return headline.failed ? common::kFailedExit : 0;
}

int index(int argc, char** argv) {
    CommandLine cmd(
        "mrloc index: index.html of a folder of run folders (./run.sh's tour): each run's "
        "headline beside the paper's figure, and a link to its report");
    TCLAP::UnlabeledValueArg<std::string> dir("folder", "folder of run folders", true, "", "DIR",
                                              cmd);
    TCLAP::ValueArg<std::string> title(
        "t", "title", "the page's title (default: what the folder holds: its runs and methods)",
        false, "", "TEXT", cmd);
    if (const auto code = parseArgs(cmd, argc, argv)) return *code;
    if (!fs::is_directory(dir.getValue()))
        throw Error(common::pathInWords(dir.getValue()) + ": not a folder");
    std::cout << report::makeIndex(dir.getValue(), title.getValue()) << "\n";
    return 0;
}

int keys(const method::Registry& registry, int argc, char** argv) {
    CommandLine cmd(
        "mrloc keys: the INI keys of every section declared as a key table (name, default, "
        "unit, range, meaning), as doc/ini.md shows them");
    TCLAP::UnlabeledValueArg<std::string> section(
        "section", "one section only (polymap), or mrpt: the keys mrloc reads from MRPT's sections",
        false, "", "SECTION", cmd);
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
    std::cout << (section.getValue() == "mrpt" ? mrptKeysText()
                                               : keysText(registry, section.getValue()));
    return 0;
}

}  // namespace mrloc::app
