// mrloc: localization of low-cost mobile robots and robot teams on MRPT.
#include <mrloc/common/Error.h>
#include <mrpt/3rdparty/tclap/CmdLine.h>

#include <cstring>
#include <iostream>
#include <string>

#include "Commands.h"

namespace {

constexpr const char* kUsage =
    "usage: mrloc <command> [options]   (mrloc <command> --help for details)\n"
    "\n"
    "commands:\n"
    "  simulate <ini>           simulate the INI's scenario into a rawlog + ground truth\n"
    "  localize <ini> <rawlog>  run the INI's method on any MRPT rawlog\n"
    "  report <run-dir>         render report.html and pictures of a localize run\n"
    "  run <ini>                simulate, localize and report in a row\n"
    "  info <rawlog>            per robot and sensor label: class, count, rate, time span\n";

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h")) {
        std::cout << kUsage;
        return argc < 2 ? 2 : 0;
    }
    const std::string command = argv[1];
    try {
        if (command == "simulate") return mrloc::app::simulate(argc - 1, argv + 1);
        if (command == "localize") return mrloc::app::localize(argc - 1, argv + 1);
        if (command == "report") return mrloc::app::report(argc - 1, argv + 1);
        if (command == "run") return mrloc::app::run(argc - 1, argv + 1);
        if (command == "info") return mrloc::app::info(argc - 1, argv + 1);
        std::cerr << "mrloc: unknown command '" << command << "'\n" << kUsage;
        return 2;
    } catch (const TCLAP::ArgException& e) {
        std::cerr << "mrloc " << command << ": " << e.error() << " (" << e.argId() << ")\n"
                  << "see: mrloc " << command << " --help\n";
        return 2;
    } catch (const mrloc::Error& e) {
        std::cerr << "mrloc " << command << ": error: " << e.what() << "\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "mrloc " << command << ": unexpected error: " << e.what() << "\n";
        return 1;
    }
}
