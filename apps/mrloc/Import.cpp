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

}  // namespace

std::vector<std::string> importFormatNames() {
    std::vector<std::string> names;
    for (const auto& [name, format] : formats().all()) names.push_back(name);
    return names;
}

int import(int argc, char** argv) {
    CommandLine cmd(
        "mrloc import: converts a log recorded by others into an MRPT rawlog (observations only, "
        "labels <robot>.<sensor>, the log's own time stamps), each robot's ground truth as "
        "<out stem>.<robot>.gt.txt (TUM), and prints what it wrote. Nothing is written under a "
        "final name unless all of it converts. doc/import.md: what each format maps to which "
        "MRPT class, units, frames, what is dropped.");
    // `mrloc import <format> --help`: that format's inputs and options only
    const auto named = formats().all().find(argc > 1 ? argv[1] : "");
    cmd.epilog = named != formats().all().end()
                     ? "format:\n" + logimport::formatHelp(named->second) + "doc/import.md#" +
                           named->first + " says more.\n"
                     : logimport::formatsHelp(formats());
    TCLAP::UnlabeledValueArg<std::string> format("format", "import format (below)", true, "",
                                                 "FORMAT", cmd);
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
