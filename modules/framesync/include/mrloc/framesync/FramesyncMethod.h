#pragma once
// Registration of the framesync method (seed 004: Yoshida, Ohya and Yuta, "Cooperative
// self-positioning system for multiple mobile robots", 2003): one shared frame for a team
// from flat walls seen by sonar.
#include <mrloc/method/Registry.h>

namespace mrloc::framesync {

void registerMethod(method::Registry& registry);

}  // namespace mrloc::framesync
