#pragma once
// What every command's command line shares, below the commands themselves (Commands.cpp,
// Trial.cpp, Batch.cpp, Import.cpp, Info.cpp): TCLAP's parser with mrloc's one-line usage
// errors, and the arguments of the commands that write a run folder.
#include <mrpt/3rdparty/tclap/CmdLine.h>

#include <memory>
#include <optional>
#include <string>

namespace mrloc::app {

/** TCLAP's usage errors in one line that names what is wrong ("missing <RAWLOG> (rawlog
 *  file)"), then the usage; TCLAP's own says "One or more required arguments missing!"
 *  without naming them. */
class OneLineOutput : public TCLAP::StdOutput {
 public:
    void failure(TCLAP::CmdLineInterface& c, TCLAP::ArgException& e) override;
};

/** A command's parser: TCLAP's, speaking through OneLineOutput. */
class CommandLine : public TCLAP::CmdLine {
 public:
    explicit CommandLine(const std::string& description);

 private:
    OneLineOutput oneLine_;
    // TCLAP makes an output of its own and frees it only when none is set: held here instead
    std::unique_ptr<TCLAP::CmdLineOutput> tclapsOwn_;
};

/** MRPT's TCLAP returns false from parse() after --help/--version (exit 0) and after a
 *  usage error it has printed (exit 2); nullopt means: go on. */
std::optional<int> parseArgs(CommandLine& cmd, int argc, char** argv);

/** "mrloc <argv...>": the command line provenance.json records. */
std::string commandLine(int argc, char** argv);

/** --out, --quiet and --threads, shared by the commands that write a run folder. */
struct OutputArgs {
    TCLAP::ValueArg<std::string> out{
        "o", "out", "output directory (default: out/<scenario name>)", false, "", "DIR"};
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
