#pragma once
// The "formation" method (seed 003) as one registration: section [formation], the localizer
// (FormationLocalizer), the scenario (robots f1 .. fN on the strip and the dead-reckoning
// robot dr, FormationPayload), the Monte Carlo experiment and the report section.
#include <mrloc/method/Registry.h>

namespace mrloc::formation {

void registerMethod(method::Registry& registry);

}  // namespace mrloc::formation
