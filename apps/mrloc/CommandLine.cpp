#include "CommandLine.h"

#include <mrloc/common/Error.h>
#include <mrloc/common/ParallelFor.h>
#include <mrloc/common/RunTransaction.h>
#include <mrloc/common/Version.h>

#include <iostream>

namespace mrloc::app {

namespace {

/** TCLAP's "(required)  INI file" without its tag: the message says "missing" already. */
std::string withoutRequiredTag(std::string description) {
    const std::string tag = "(required)";
    if (description.rfind(tag, 0) == 0) description.erase(0, tag.size());
    const auto text = description.find_first_not_of(' ');
    return text == std::string::npos ? description : description.substr(text);
}

}  // namespace

void OneLineOutput::failure(TCLAP::CmdLineInterface& c, TCLAP::ArgException& e) {
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

CommandLine::CommandLine(const std::string& description)
    : TCLAP::CmdLine(description, ' ', kVersion), tclapsOwn_(getOutput()) {
    setOutput(&oneLine_);
}

std::optional<int> parseArgs(CommandLine& cmd, int argc, char** argv) {
    if (cmd.parse(argc, argv)) return std::nullopt;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--help" || a == "-h" || a == "--version") return 0;
    }
    return 2;
}

std::string commandLine(int argc, char** argv) {
    std::string s = "mrloc";
    for (int i = 0; i < argc; ++i) s += std::string(" ") + argv[i];
    return s;
}

OutputArgs::OutputArgs() : threads("", "threads", ThreadsArg::kHelp, false, 0, "N") {}

void OutputArgs::addTo(TCLAP::CmdLine& cmd) {
    cmd.add(out);
    cmd.add(quiet);
    cmd.add(threads);
}

std::string OutputArgs::dirOr(const std::string& name) {
    const std::string dir = out.isSet() ? out.getValue() : "out/" + name;
    common::checkRunFolderPath(dir, out.isSet() ? "--out" : "[scenario] name");
    return dir;
}

void ThreadsArg::apply(TCLAP::ValueArg<long>& threads) {
    if (!threads.isSet()) return;
    if (threads.getValue() < 1 || threads.getValue() > kMaxThreads)
        throw Error("--threads must be 1 to " + std::to_string(kMaxThreads));
    common::setThreadCount(unsigned(threads.getValue()));
}

ScenarioCommand::ScenarioCommand(const std::string& description) : cmd(description) {
    output.addTo(cmd);
}

std::optional<long> ScenarioCommand::seedGiven() {
    return seed.isSet() ? std::optional<long>(seed.getValue()) : std::nullopt;
}

}  // namespace mrloc::app
