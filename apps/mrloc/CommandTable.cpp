#include "CommandTable.h"

#include <mrloc/common/Error.h>
#include <mrloc/common/RunTransaction.h>
#include <mrpt/3rdparty/tclap/CmdLine.h>

#include <cstring>
#include <iostream>

#include "Commands.h"

namespace mrloc::app {

namespace {
/** A command that needs no method. */
template <int (*F)(int, char**)>
int withoutRegistry(const method::Registry&, int argc, char** argv) {
    return F(argc, argv);
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
         "a log recorded by others (libRSF, sonar text, MRCLAM, CARMEN)\n"
         "into a rawlog + ground truth (mrloc import --help)",
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
        "usage: mrloc <command> [options]   (mrloc <command> --help for details)\n\ncommands:\n";
    constexpr size_t kColumn = 27;
    for (const auto& c : commands()) {
        std::string head = "  " + c.name + " " + c.arguments;
        head.resize(std::max(kColumn, head.size() + 1), ' ');
        std::string help = c.help;
        for (size_t p = 0; (p = help.find('\n', p)) != std::string::npos; p += 1 + kColumn)
            help.replace(p, 1, "\n" + std::string(kColumn, ' '));
        out += head + help + "\n";
    }
    return out;
}

int main(const method::Registry& registry, int argc, char** argv) {
    common::installSignalCleanup();
    if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h")) {
        std::cout << usage();
        return argc < 2 ? 2 : 0;
    }
    if (!std::strcmp(argv[1], "--commands")) {
        for (const auto& c : commands()) std::cout << c.name << "\n";
        return 0;
    }
    const std::string command = argv[1];
    try {
        for (const auto& c : commands())
            if (c.name == command) return c.run(registry, argc - 1, argv + 1);
        std::cerr << "mrloc: unknown command '" << command << "'\n" << usage();
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
