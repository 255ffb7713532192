#include "CommandTable.h"

#include <mrloc/common/Error.h>
#include <mrloc/common/Names.h>
#include <mrloc/common/RunTransaction.h>
#include <mrpt/3rdparty/tclap/CmdLine.h>

#include <algorithm>
#include <cstring>
#include <iostream>
#include <sstream>

#include "CommandLine.h"
#include "Commands.h"

namespace mrloc::app {

namespace {
/** A command that needs no method. */
template <int (*F)(int, char**)>
int withoutRegistry(const method::Registry&, int argc, char** argv) {
    return F(argc, argv);
}
}  // namespace

const std::vector<Command>& commands();

namespace {
/** ": did you mean 'run'?" for a near miss of a command's name, else "". */
std::string nearestCommand(const std::string& typed) {
    std::vector<std::string> names;
    for (const auto& c : commands()) names.push_back(c.name);
    const auto near = common::nearMiss(typed, names);
    return near ? ": did you mean '" + *near + "'?" : "";
}
}  // namespace

const std::vector<Command>& commands() {
    static const std::vector<Command> table{
        {"simulate", "<ini>", "simulate the INI's scenario into a rawlog + ground truth", simulate},
        {"localize", "<ini> <rawlog>", "run the INI's method on any MRPT rawlog", localize},
        {"report", "<run-dir>", "render report.html and pictures of a localize run", report},
        {"run", "<ini>", "simulate, localize and report in a row", run},
        {"info", "<rawlog>", "per robot and sensor label: class, count, rate, time span",
         withoutRegistry<info>},
        {"index", "<folder>", "index.html of a folder of runs: headlines beside the papers'",
         withoutRegistry<index>},
        {"trial", "<ini> --seed N", "one seed of the INI's experiment: one JSON line of figures",
         trial},
        {"batch", "<ini> --seeds A..B",
         "trials over seeds (and a --grid of keys) through GNU parallel,\n"
         "or a Slurm script; --collect sums them up (doc/batch.md)",
         batch},
        {"import", "<format> <in...>",
         "a log recorded by others into a rawlog + ground truth:\nformats below "
         "(mrloc import <format> --help)",
         withoutRegistry<import>},
        {"eval", "<estimate> <truth>",
         "an estimate scored against the truth on the truth's stamps:\n"
         "APE with its coverage, RPE (doc/evaluation.md)",
         withoutRegistry<eval>},
        {"keys", "[section]", "the INI keys: default, unit, range, meaning (doc/ini.md)", keys},
    };
    return table;
}

std::string usage() {
    std::string out =
        "usage: mrloc <command> [options]   (mrloc <command> --help for details)\n\n" +
        wrapped(
            "Localization of low-cost mobile robots and robot teams on MRPT: "
            "simulate or read a rawlog, run a method from an INI file, read "
            "the report.",
            0) +
        "\n\ncommands:\n";
    constexpr size_t kColumn = 27;
    for (const auto& c : commands()) {
        std::string head = "  " + c.name + " " + c.arguments;
        head.resize(std::max(kColumn, head.size() + 1), ' ');
        std::string help = c.help;
        for (size_t p = 0; (p = help.find('\n', p)) != std::string::npos; p += 1 + kColumn)
            help.replace(p, 1, "\n" + std::string(kColumn, ' '));
        out += head + help + "\n";
    }
    std::string formats;
    for (const auto& f : importFormatNames()) formats += (formats.empty() ? "" : ", ") + f;
    out += "\nimport formats: " + formats +
           "\n\noptions:\n"
           "  -h, --help                this help\n"
           "  --version                 mrloc's version, commit and MRPT's version\n"
           "  --commands                the command names, one per line\n"
           "  --completion bash         a bash completion script: source <(mrloc --completion "
           "bash)\n"
           "  --man                     this and every command's help as a man page (roff)\n\n" +
           wrapped(kExitCodes, 0) + "\n";
    return out;
}

namespace {

/** What a command prints for `args` on stdout (its help, its options), asked of its own
 *  parser in this process. */
std::string commandOutput(const method::Registry& registry, const Command& c,
                          const std::string& argument) {
    std::ostringstream text;
    auto* const saved = std::cout.rdbuf(text.rdbuf());
    std::vector<std::string> words{c.name, argument};
    std::vector<char*> argv{words[0].data(), words[1].data()};
    try {
        c.run(registry, 2, argv.data());
    } catch (...) {
        std::cout.rdbuf(saved);
        throw;
    }
    std::cout.rdbuf(saved);
    return text.str();
}

/** Text as roff lines kept as they are (.nf): a backslash doubled, a line that starts with a
 *  dot or a quote escaped, so no word of a help text becomes a roff request. */
std::string roffVerbatim(const std::string& text) {
    std::string out, line;
    std::istringstream lines(text);
    while (std::getline(lines, line)) {
        std::string escaped;
        for (const char ch : line) escaped += ch == '\\' ? std::string("\\e") : std::string(1, ch);
        if (!escaped.empty() && (escaped[0] == '.' || escaped[0] == '\''))
            escaped = "\\&" + escaped;
        out += escaped + "\n";
    }
    return out;
}

}  // namespace

std::string bashCompletion(const method::Registry& registry) {
    // each command's options, asked of its own parser (parseArgs' --list-options), so the
    // script cannot drift from the commands
    std::string cases;
    for (const auto& c : commands()) {
        std::string list = commandOutput(registry, c, "--list-options");
        std::replace(list.begin(), list.end(), '\n', ' ');
        cases += "    " + c.name + ") opts=\"" + list + "\" ;;\n";
    }
    std::string names, formats;
    for (const auto& c : commands()) names += c.name + " ";
    for (const auto& f : importFormatNames()) formats += f + " ";
    return "# bash completion for mrloc (mrloc --completion bash; source it or put it in\n"
           "# /usr/share/bash-completion/completions/mrloc)\n"
           "_mrloc() {\n"
           "  local cur=${COMP_WORDS[COMP_CWORD]} opts\n"
           "  if [ \"$COMP_CWORD\" -eq 1 ]; then\n"
           "    COMPREPLY=($(compgen -W \"" +
           names +
           "--help --version\" -- \"$cur\")); return\n"
           "  fi\n"
           "  case ${COMP_WORDS[1]} in\n" +
           cases +
           "  esac\n"
           "  if [[ $cur == -* ]]; then COMPREPLY=($(compgen -W \"$opts\" -- \"$cur\")); return; "
           "fi\n"
           "  if [ \"${COMP_WORDS[1]}\" = import ] && [ \"$COMP_CWORD\" -eq 2 ]; then\n"
           "    COMPREPLY=($(compgen -W \"" +
           formats +
           "\" -- \"$cur\")); return\n"
           "  fi\n"
           "  COMPREPLY=($(compgen -f -- \"$cur\"))\n"
           "}\n"
           "complete -o filenames -F _mrloc mrloc\n";
}

std::string manPage(const method::Registry& registry) {
    std::string page =
        ".TH MRLOC 1 \"\" \"" + versionLine() +
        "\" \"User Commands\"\n"
        ".SH NAME\nmrloc \\- localization of low-cost mobile robots and robot teams on MRPT\n"
        ".SH SYNOPSIS\n.B mrloc\n.I command\n[\n.I options\n]\n"
        ".SH DESCRIPTION\n.nf\n" +
        roffVerbatim(usage()) + ".fi\n.SH COMMANDS\n";
    for (const auto& c : commands())
        page += ".SS " + c.name + "\n.nf\n" + roffVerbatim(commandOutput(registry, c, "--help")) +
                ".fi\n";
    return page +
           ".SH FILES\nThe INIs, maps and sample rawlogs: share/mrloc/ under the prefix; the "
           "documentation (doc/ini.md, doc/evaluation.md, one page per method): share/doc/mrloc/.\n"
           ".SH SEE ALSO\n.BR pf-localization (1),\n.BR ro-localization (1),\n"
           ".BR rawlog-edit (1)\n";
}

int main(const method::Registry& registry, int argc, char** argv) {
    common::installSignalCleanup();
    if (argc < 2) {
        std::cerr << usage();
        return kExitUsage;
    }
    if (!std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h")) {
        std::cout << usage();
        return 0;
    }
    if (!std::strcmp(argv[1], "--version")) {
        std::cout << versionLine() << "\n";
        return 0;
    }
    if (!std::strcmp(argv[1], "--commands")) {
        for (const auto& c : commands()) std::cout << c.name << "\n";
        return 0;
    }
    if (!std::strcmp(argv[1], "--man")) {
        std::cout << manPage(registry);
        return 0;
    }
    if (!std::strcmp(argv[1], "--completion")) {
        if (argc != 3 || std::strcmp(argv[2], "bash")) {
            std::cerr << "mrloc --completion: give the shell: mrloc --completion bash\n";
            return kExitUsage;
        }
        std::cout << bashCompletion(registry);
        return 0;
    }
    const std::string command = argv[1];
    try {
        for (const auto& c : commands())
            if (c.name == command) return c.run(registry, argc - 1, argv + 1);
        std::cerr << "mrloc: unknown command '" << command << "'" << nearestCommand(command)
                  << " (mrloc --help lists them)\n";
        return kExitUsage;
    } catch (const TCLAP::ArgException& e) {
        std::cerr << "mrloc " << command << ": " << e.error() << " (" << e.argId() << ")\n"
                  << "see: mrloc " << command << " --help\n";
        return kExitUsage;
    } catch (const mrloc::Error& e) {
        std::cerr << "mrloc " << command << ": error: " << oneLine(e.what()) << "\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "mrloc " << command << ": unexpected error: " << oneLine(e.what()) << "\n";
        return 1;
    }
}

}  // namespace mrloc::app
