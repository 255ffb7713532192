#pragma once
// The "polymap" method (seed 002) as one registration: section [polymap], the localizer,
// the scenario (one robot at the start in the floor plan, scanning it: PolymapPayload) and
// the report section (P, V and H per robot).
#include <mrloc/method/Registry.h>
#include <mrloc/sim/Payload.h>
#include <mrloc/sim/Scanner.h>

namespace mrloc::polymap {

/** 360-degree scans of the floor plan (`<robot>.scan`) at the start and then at the
 *  scanner's rate, with the simulator's generic scanner. */
class PolymapPayload : public sim::Payload {
 public:
    explicit PolymapPayload(sim::FloorPlan plan) : plan_(std::move(plan)) {}
    void sense(sim::Step& step) override;

 private:
    sim::FloorPlan plan_;
    long scanEvery_ = -1;  ///< steps between scans (0: only at the start); set at step 0
};

void registerMethod(method::Registry& registry);

}  // namespace mrloc::polymap
