#pragma once
// Subcommands of the mrloc executable. Each parses its own arguments (TCLAP, shipped with
// MRPT) and returns the process exit code; mrloc::Error propagates to main().
#include <mrpt/3rdparty/tclap/CmdLine.h>

#include <optional>

namespace mrloc::app {

/** MRPT's TCLAP returns false from parse() after --help/--version (exit 0) and after a
 *  usage error it has printed (exit 2); nullopt means: go on. */
std::optional<int> parseArgs(TCLAP::CmdLine& cmd, int argc, char** argv);

int simulate(int argc, char** argv);
int localize(int argc, char** argv);
int report(int argc, char** argv);
int run(int argc, char** argv);
int info(int argc, char** argv);

}  // namespace mrloc::app
