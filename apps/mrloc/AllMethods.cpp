// One line per method: the rest of the program knows none of them by name.
#include "AllMethods.h"

#include <mrloc/beacons/BeaconsMethod.h>
#include <mrloc/formation/FormationMethod.h>
#include <mrloc/framesync/FramesyncMethod.h>
#include <mrloc/omnivision/OmniMethod.h>
#include <mrloc/polymap/PolymapMethod.h>

namespace mrloc::app {

void registerAllMethods(method::Registry& registry) {
    beacons::registerMethod(registry);
    polymap::registerMethod(registry);
    omnivision::registerMethod(registry);
    formation::registerMethod(registry);
    framesync::registerMethod(registry);
}

}  // namespace mrloc::app
