#pragma once
// The methods this mrloc ships: the one list of them, used by the program and by the INI fuzz
// target, so that both know the same methods.
#include <mrloc/method/Registry.h>

namespace mrloc::app {

void registerAllMethods(method::Registry& registry);

}  // namespace mrloc::app
