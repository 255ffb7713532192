#pragma once
// What every command's command line shares, below the commands themselves (Commands.cpp,
// Trial.cpp, Batch.cpp, Import.cpp, Info.cpp): TCLAP's parser with mrloc's one-line usage
// errors, and the arguments of the commands that write a run folder.
#include <mrpt/3rdparty/tclap/CmdLine.h>

#include <memory>
#include <optional>
#include <string>

namespace mrloc::app {

/** Exit codes, as every help text lists them (kExitCodes). */
constexpr int kExitUsage = 2;
constexpr const char* kExitCodes =
    "exit codes: 0 done (the method's goal reached or not: the last line says which), 1 error "
    "(one line names the file and what), 2 usage, 3 the method failed on its input, 130 "
    "interrupted (Ctrl-C), 143 terminated; the previous run in the folder is kept on any but 0 "
    "and 3";

/** mrloc's one help style for every command (top level included): usage line, what it does,
 *  arguments, options, exit codes; and TCLAP's usage errors in one line that names what is
 *  wrong ("missing <RAWLOG> (rawlog file)"), then the usage; TCLAP's own says "One or more
 *  required arguments missing!" without naming them. */
class OneLineOutput : public TCLAP::StdOutput {
 public:
    explicit OneLineOutput(const std::string& epilog) : epilog_(epilog) {}
    void failure(TCLAP::CmdLineInterface& c, TCLAP::ArgException& e) override;
    void usage(TCLAP::CmdLineInterface& c) override;
    void version(TCLAP::CmdLineInterface& c) override;

 private:
    const std::string& epilog_;
};

/** `mrloc --version`'s line: version, commit, MRPT's version. */
std::string versionLine();

/** Text wrapped to `width` columns, each line after the first indented by `indent`. */
std::string wrapped(const std::string& text, size_t indent, size_t width = 88);

/** A command's parser: TCLAP's, speaking through OneLineOutput. */
class CommandLine : public TCLAP::CmdLine {
 public:
    explicit CommandLine(const std::string& description);
    /** Printed by --help after the options (import: its formats). */
    std::string epilog;

 private:
    OneLineOutput oneLine_{epilog};
    // TCLAP makes an output of its own and frees it only when none is set: held here instead
    std::unique_ptr<TCLAP::CmdLineOutput> tclapsOwn_;
};

/** MRPT's TCLAP returns false from parse() after --help/--version (exit 0) and after a
 *  usage error it has printed (exit 2); nullopt means: go on. `--list-options` alone prints
 *  the command's options, one per line (the shell completion's words), and returns 0. */
std::optional<int> parseArgs(CommandLine& cmd, int argc, char** argv);

/** "mrloc <argv...>": the command line provenance.json records. */
std::string commandLine(int argc, char** argv);

/** --out, --quiet and --threads, shared by the commands that write a run folder. */
struct OutputArgs {
    TCLAP::ValueArg<std::string> out{
        "o",
        "out",
        "output folder (default: out/<[scenario] name>, or out/<the INI file's name> without one)",
        false,
        "",
        "DIR"};
    TCLAP::SwitchArg quiet{"q", "quiet", "no progress bar, only errors"};
    TCLAP::ValueArg<long> threads;
    OutputArgs();
    void addTo(TCLAP::CmdLine& cmd);
    /** The run folder: --out, else out/<name>; checked (common::checkRunFolderPath). */
    std::string dirOr(const std::string& name);
};

/** --threads N: every parallelFor of this process runs on N threads, and the work estimate
 *  divides by the same number (`mrloc run`, `mrloc trial`, ...). */
struct ThreadsArg {
    static constexpr long kMaxThreads = 1024;
    static constexpr const char* kHelp =
        "threads for the experiments and searches (default: every core); the work estimate "
        "divides by the same number";
    /** Sets common::setThreadCount when `threads` was given; throws mrloc::Error when it is
     *  outside 1..kMaxThreads. */
    static void apply(TCLAP::ValueArg<long>& threads);
};

/** The command line of the commands that simulate an INI: <ini> [--seed] [--out] [-q]. */
struct ScenarioCommand {
    CommandLine cmd;
    TCLAP::UnlabeledValueArg<std::string> ini{"ini", "scenario INI file", true, "", "INI", cmd};
    TCLAP::ValueArg<long> seed{"s", "seed", "random seed (overrides [scenario] seed)", false, 0,
                               "N", cmd};
    OutputArgs output;

    explicit ScenarioCommand(const std::string& description);
    /** --seed when given. */
    std::optional<long> seedGiven();
};

}  // namespace mrloc::app
