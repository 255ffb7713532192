#pragma once
// The commands of the mrloc executable, which CommandTable.cpp lists and dispatches. Each
// parses its own arguments (CommandLine.h) and returns the process exit code; mrloc::Error
// propagates to the caller. They know no method by name: everything method-specific comes
// from the registry. What they share lives below them: CommandLine.h (parsing), RunSetup.h
// (the INI resolved), RunSteps.h (the steps of a run folder and its transaction).
#include <mrloc/method/Registry.h>

#include <string>
#include <vector>

namespace mrloc::app {

int simulate(const method::Registry& registry, int argc, char** argv);  // Commands.cpp
int localize(const method::Registry& registry, int argc, char** argv);  // Commands.cpp
int report(const method::Registry& registry, int argc, char** argv);    // Commands.cpp
int run(const method::Registry& registry, int argc, char** argv);       // Commands.cpp
int index(int argc, char** argv);                                       // Commands.cpp
int keys(const method::Registry& registry, int argc, char** argv);      // Commands.cpp
int info(int argc, char** argv);                                        // Info.cpp
int import(int argc, char** argv);                                      // Import.cpp
std::vector<std::string> importFormatNames();                           // Import.cpp
int eval(int argc, char** argv);                                        // Eval.cpp
int trial(const method::Registry& registry, int argc, char** argv);     // Trial.cpp
int batch(const method::Registry& registry, int argc, char** argv);     // Batch.cpp

}  // namespace mrloc::app
