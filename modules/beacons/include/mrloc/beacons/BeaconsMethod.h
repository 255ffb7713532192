#pragma once
// The "beacons" method (seed 001) as one registration: sections [beacons], [sensors] and
// [ultrasonic], the localizer, the scenario (robots from [robot.<name>], the beacon map,
// the payload) and the report section (reception beside seed 001 Tables 3/4).
#include <mrloc/method/Registry.h>

namespace mrloc::beacons {

/** The scenario of [scenario], [world], [robot.<name>], [sensors], [ultrasonic] and the
 *  beacon map; its payload is a BeaconPayload. */
method::Scenario loadScenario(const mrpt::config::CConfigFileBase& ini);

void registerMethod(method::Registry& registry);

}  // namespace mrloc::beacons
