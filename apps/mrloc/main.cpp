// mrloc: localization of low-cost mobile robots and robot teams on MRPT. The methods are
// registered in AllMethods.cpp, one line each.
#include "AllMethods.h"
#include "CommandTable.h"

int main(int argc, char** argv) {
    mrloc::method::Registry registry;
    mrloc::app::registerAllMethods(registry);
    return mrloc::app::main(registry, argc, argv);
}
