#pragma once
// The "beacons" method (seed 001) as one registration: sections [beacons], [sensors] and
// [ultrasonic], the localizer, the scenario (robots from [robot.<name>], the beacon map,
// the payload) and the report section (reception beside seed 001 Tables 3/4).
#include <mrloc/method/Registry.h>

namespace mrloc::beacons {

void registerMethod(method::Registry& registry);

}  // namespace mrloc::beacons
