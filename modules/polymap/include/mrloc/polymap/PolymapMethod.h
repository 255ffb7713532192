#pragma once
// The "polymap" method (seed 002) as one registration: section [polymap], the localizer,
// the scenario (one robot at the start in the floor plan, scanning it: PolymapPayload) and
// the report section (P, V and H per robot).
#include <mrloc/method/Registry.h>
#include <mrloc/polymap/PolymapLocalizer.h>
#include <mrloc/sim/Payload.h>
#include <mrloc/sim/Scanner.h>

namespace mrloc::polymap {

/** 360-degree scans of the floor plan (`<robot>.scan`) at the start and then at the
 *  scanner's rate, with the simulator's generic scanner. */
/** The scanner, and with [polymap] drive the on-board elimination: hypotheses from the
 *  first scan, then for each probe drive the planned route, turn back to the known heading,
 *  scan, eliminate (EliminationSession, the localizer's own code), until one is left. The
 *  route is followed in the robot's start frame by the simulator's waypoint follower (a
 *  controller that tracks it; odometry is recorded but not used to steer). */
class PolymapPayload : public sim::Payload {
 public:
    /** options: the run's [polymap] (a copy: the payload owns what it needs);
     *  probeRadius: polymap::probeRadius of the robot's speed and the simulator's step. */
    PolymapPayload(sim::FloorPlan plan, PolymapOptions options, double probeRadius)
        : plan_(std::move(plan)), options_(std::move(options)), probeRadius_(probeRadius) {}
    void command(sim::Step& step) override;
    void sense(sim::Step& step) override;
    void onObservation(const mrpt::obs::CObservation::Ptr& obs) override;

 private:
    enum class Phase { Start, Plan, Driving, Turning, Scan, Done };

    sim::FloorPlan plan_;
    PolymapOptions options_;
    double probeRadius_;
    long scanEvery_ = -1;  ///< steps between scans (0: only at the start); set at step 0
    Phase phase_ = Phase::Start;
    std::shared_ptr<EliminationSession> session_;
};

void registerMethod(method::Registry& registry);

}  // namespace mrloc::polymap
