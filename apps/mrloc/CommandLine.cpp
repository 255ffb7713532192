#include "CommandLine.h"

#include <mrloc/common/Error.h>
#include <mrloc/common/ParallelFor.h>
#include <mrloc/common/RunTransaction.h>
#include <mrloc/common/Version.h>
#include <mrpt/system/os.h>

#include <algorithm>
#include <iostream>
#include <vector>

namespace mrloc::app {

extern const char* const kCommit;  // BuildInfo.cpp, generated at build time

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

namespace {
/** TCLAP's short id without the brackets of an optional argument: "[-o <DIR>]" -> "-o <DIR>",
 *  "[--opt <K>] ... " -> "--opt <K> ...". */
std::string bare(std::string id) {
    std::string more;
    while (!id.empty() && id.back() == ' ') id.pop_back();
    if (id.size() > 4 && id.compare(id.size() - 4, 4, " ...") == 0) {
        more = " ...";
        id.resize(id.size() - 4);
    }
    if (id.size() > 1 && id.front() == '[' && id.back() == ']') id = id.substr(1, id.size() - 2);
    return id + more;
}
/** A positional argument: its short id is "<INI>" or "[<INI>]", a flag's "-o ..." or "--x". */
bool unlabelled(const TCLAP::Arg& a) { return bare(a.shortID()).rfind("-", 0) != 0; }
}  // namespace

std::string wrapped(const std::string& text, size_t indent, size_t width) {
    std::string out, line;
    const auto flush = [&] {
        out += (out.empty() ? "" : "\n" + std::string(indent, ' ')) + line;
        line.clear();
    };
    size_t start = 0;
    while (start <= text.size()) {
        const size_t end = std::min(text.find_first_of(" \n", start), text.size());
        const std::string word = text.substr(start, end - start);
        if (!line.empty() && indent + line.size() + 1 + word.size() > width) flush();
        line += (line.empty() ? "" : " ") + word;
        if (end < text.size() && text[end] == '\n') flush();
        start = end + 1;
    }
    if (!line.empty()) flush();
    return out;
}

std::string versionLine() {
    // MRPT_getVersion() reads "MRPT 2.5.8"
    return std::string("mrloc ") + kVersion + " (commit " + kCommit + ", " +
           mrpt::system::MRPT_getVersion() + ")";
}

void OneLineOutput::version(TCLAP::CmdLineInterface&) { std::cout << versionLine() << "\n"; }

void OneLineOutput::usage(TCLAP::CmdLineInterface& c) {
    const std::string command = "mrloc " + c.getProgramName();
    // TCLAP's own: "--" (ignore the rest) is left out, help and version go last
    std::vector<const TCLAP::Arg*> positional, options;
    for (const TCLAP::Arg* a : c.getArgList()) {
        if (a->getName() == "ignore_rest") continue;
        (unlabelled(*a) ? positional : options).push_back(a);
    }
    std::cout << "usage: " << command;
    for (const auto* a : positional) std::cout << " " << a->shortID();  // "<INI>", "[<INI>]"
    std::cout << " [options]\n\n" << wrapped(c.getMessage(), 0) << "\n";
    constexpr size_t kColumn = 22;
    const auto row = [&](std::string head, const std::string& text) {
        head = "  " + head;
        if (head.size() + 1 > kColumn) {
            std::cout << head << "\n" << std::string(kColumn, ' ');
        } else {
            head.resize(kColumn, ' ');
            std::cout << head;
        }
        std::cout << wrapped(text, kColumn) << "\n";
    };
    if (!positional.empty()) std::cout << "\narguments:\n";
    for (const auto* a : positional)
        row(bare(a->shortID()), withoutRequiredTag(a->getDescription()));
    std::cout << "\noptions:\n";
    std::reverse(options.begin(), options.end());  // TCLAP keeps flags last declared first
    std::stable_sort(options.begin(), options.end(), [](const auto* a, const auto* b) {
        const auto last = [](const TCLAP::Arg* x) {
            return x->getName() == "help" || x->getName() == "version";
        };
        return !last(a) && last(b);
    });
    for (const auto* a : options) {
        // "-o, --out DIR": the value's name is the one in TCLAP's short id ("-o <DIR>")
        const std::string id = bare(a->shortID());
        const auto open = id.find('<'), close = id.rfind('>');
        const std::string value =
            (open != std::string::npos && close != std::string::npos
                 ? " " + id.substr(open + 1, close - open - 1)
                 : "") +
            (id.size() > 4 && id.compare(id.size() - 4, 4, " ...") == 0 ? " ..." : "");
        const std::string head = (a->getFlag().empty() ? "    " : "-" + a->getFlag() + ", ") +
                                 "--" + a->getName() + value;
        std::string text = withoutRequiredTag(a->getDescription());
        if (a->getName() == "help") text = "this help";
        if (a->getName() == "version") text = "mrloc's version, commit and MRPT's version";
        row(head, text + (a->isRequired() ? " (required)" : ""));
    }
    if (!epilog_.empty()) std::cout << "\n" << epilog_;
    std::cout << "\n" << wrapped(kExitCodes, 0) << "\n";
}

CommandLine::CommandLine(const std::string& description)
    : TCLAP::CmdLine(description, ' ', kVersion), tclapsOwn_(getOutput()) {
    setOutput(&oneLine_);
    // TCLAP remembers an optional positional argument in a process-wide flag: each command
    // line starts afresh (the completion builds every command's parser in one process)
    TCLAP::OptionalUnlabeledTracker<>::alreadyOptional() = false;
}

std::optional<int> parseArgs(CommandLine& cmd, int argc, char** argv) {
    if (argc == 2 && std::string(argv[1]) == "--list-options") {
        std::vector<std::string> names;
        for (const TCLAP::Arg* a : cmd.getArgList())
            if (a->getName() != "ignore_rest" && !unlabelled(*a))
                names.push_back("--" + a->getName());
        std::sort(names.begin(), names.end());
        for (const auto& n : names) std::cout << n << "\n";
        return 0;
    }
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
