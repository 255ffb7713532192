#pragma once
// Subcommands of the mrloc executable. Each parses its own arguments (TCLAP, shipped with
// MRPT) and returns the process exit code; mrloc::Error propagates to main().
namespace mrloc::app {

int simulate(int argc, char** argv);
int localize(int argc, char** argv);
int report(int argc, char** argv);
int run(int argc, char** argv);
int info(int argc, char** argv);

}  // namespace mrloc::app
