#pragma once
// The mrloc executable as a table of commands: name, arguments, one line of help and the
// function. The usage text and the shell completion's word list come from it; it sits above
// every command (Commands.cpp, Trial.cpp, Batch.cpp, Import.cpp, Info.cpp), which know
// nothing of one another's dispatch.
#include <mrloc/method/Registry.h>

#include <functional>
#include <string>
#include <vector>

namespace mrloc::app {

struct Command {
    std::string name;
    std::string arguments;  ///< "<ini> <rawlog>"
    std::string help;       ///< one line; a second, if any, after '\n'
    std::function<int(const method::Registry&, int, char**)> run;
};

/** Every command, in the order the usage lists them. */
const std::vector<Command>& commands();

/** "usage: mrloc <command> ...", then a line per command. */
std::string usage();

/** Dispatches `mrloc <command> ...` (argv[0] is the program); prints errors, returns the
 *  exit code: 0 done, 1 error, 2 usage. `mrloc --commands` lists the names (for completion:
 *  `complete -W "$(mrloc --commands)" mrloc`). */
int main(const method::Registry& registry, int argc, char** argv);

}  // namespace mrloc::app
