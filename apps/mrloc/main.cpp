// mrloc: localization of low-cost mobile robots and robot teams on MRPT. One line per
// method: the rest of the program knows none of them by name.
#include <mrloc/beacons/BeaconsMethod.h>
#include <mrloc/omnivision/OmniMethod.h>
#include <mrloc/polymap/PolymapMethod.h>

#include "Commands.h"

int main(int argc, char** argv) {
    mrloc::method::Registry registry;
    mrloc::beacons::registerMethod(registry);
    mrloc::polymap::registerMethod(registry);
    mrloc::omnivision::registerMethod(registry);
    return mrloc::app::main(registry, argc, argv);
}
