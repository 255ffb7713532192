#pragma once
// Subcommands of the mrloc executable. Each parses its own arguments (TCLAP, shipped with
// MRPT) and returns the process exit code; mrloc::Error propagates to the caller. They
// know no method by name: everything method-specific comes from the registry.
#include <mrloc/method/Registry.h>
#include <mrpt/3rdparty/tclap/CmdLine.h>

#include <optional>

#include "RunSetup.h"

namespace mrloc::app {

/** MRPT's TCLAP returns false from parse() after --help/--version (exit 0) and after a
 *  usage error it has printed (exit 2); nullopt means: go on. */
std::optional<int> parseArgs(TCLAP::CmdLine& cmd, int argc, char** argv);

int simulate(const method::Registry& registry, int argc, char** argv);
int localize(const method::Registry& registry, int argc, char** argv);
int report(const method::Registry& registry, int argc, char** argv);
int run(const method::Registry& registry, int argc, char** argv);
int info(int argc, char** argv);
int index(int argc, char** argv);
int import(int argc, char** argv);
int trial(const method::Registry& registry, int argc, char** argv);  // Trial.cpp
int batch(const method::Registry& registry, int argc, char** argv);  // Batch.cpp
int keys(const method::Registry& registry, int argc, char** argv);

/** Reads and validates everything an INI asks for, as `simulate`, `localize` and `run` do
 *  before they write anything (the scenario built when it has [scenario]), and renders its
 *  effective.ini; throws mrloc::Error naming file, section, key or line. Writes nothing. */
std::string checkIni(const method::Registry& registry, const std::string& iniPath);

/** Simulates the setup's scenario into `dir`, localizes it and runs the method's experiment,
 *  quietly, as `mrloc run` does without its report: `mrloc trial` of a method that registers
 *  no trial of its own (its headline holds its experiment's figures). */
common::Headline simulateAndLocalize(const method::Registry& registry, Setup& s,
                                     const std::string& dir);

}  // namespace mrloc::app
