// `mrloc import <format> <inputs...> --out <file.rawlog>`: a log recorded by others into an
// MRPT rawlog, its ground truth as TUM beside it, and what it wrote (logimport::runImport).
#include <mrloc/common/Error.h>
#include <mrloc/logimport/Format.h>

#include <cstring>
#include <iostream>

#include "CommandLine.h"
#include "Commands.h"

namespace mrloc::app {

namespace {

const logimport::FormatRegistry& formats() {
    static const logimport::FormatRegistry registry = [] {
        logimport::FormatRegistry r;
        logimport::registerAllFormats(r);
        return r;
    }();
    return registry;
}

constexpr const char* kImportUsage =
    "usage: mrloc import <format> <inputs...> --out <file.rawlog> [--opt key=value ...]\n"
    "Converts a log into an MRPT rawlog (observations only, labels <robot>.<sensor>, the\n"
    "log's own time stamps), each robot's ground truth as <out stem>.<robot>.gt.txt (TUM), and\n"
    "prints what it wrote. Nothing is written under a final name unless all of it converts.\n"
    "doc/import.md: what each format maps to which MRPT class, units, frames, what is dropped.\n\n";

}  // namespace

int import(int argc, char** argv) {
    for (int i = 1; i < argc; ++i)
        if (!std::strcmp(argv[i], "--help") || !std::strcmp(argv[i], "-h") || argc == 1) {
            // `mrloc import <format> --help`: that format's options only
            const auto named = formats().all().find(argc > 2 ? argv[1] : "");
            std::cout << kImportUsage
                      << (named != formats().all().end()
                              ? "format:\n" + logimport::formatHelp(named->second) +
                                    "doc/import.md#" + named->first + " says more.\n"
                              : logimport::formatsHelp(formats()));
            return 0;
        }
    if (argc < 2) {
        std::cerr << kImportUsage << logimport::formatsHelp(formats());
        return 2;
    }
    CommandLine cmd("mrloc import");
    TCLAP::UnlabeledValueArg<std::string> format("format", "import format", true, "", "FORMAT",
                                                 cmd);
    TCLAP::UnlabeledMultiArg<std::string> inputs("inputs", "input files", true, "INPUT", cmd);
    TCLAP::ValueArg<std::string> out("o", "out", "the rawlog to write", true, "", "RAWLOG", cmd);
    TCLAP::MultiArg<std::string> opts("", "opt", "a format's option, key=value", false, "KEY=VALUE",
                                      cmd);
    if (const auto code = parseArgs(cmd, argc, argv)) return *code;
    const auto& f = formats().get(format.getValue());
    const auto summary =
        logimport::runImport(f, inputs.getValue(), opts.getValue(), out.getValue());
    std::cout << logimport::summaryText(summary);
    return 0;
}

}  // namespace mrloc::app
