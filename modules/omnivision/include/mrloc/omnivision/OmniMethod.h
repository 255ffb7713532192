#pragma once
// The "omnivision" method (seed 000) as one registration: section [omnivision], the
// localizer, the scenario (robots from [robot.<name>] or a generated swarm; OmniPayload:
// the stops, the cameras and the conventional method's LiDAR), the accuracy sweep as an
// experiment step, and the report section (layout and accuracy plots).
#include <mrloc/method/Registry.h>
#include <mrloc/omnivision/OmniCamera.h>
#include <mrloc/omnivision/OmniOptions.h>
#include <mrloc/sim/Payload.h>

#include <memory>

namespace mrloc::omnivision {

/** The cameras of every robot in the simulator: the pairs that stop stand still in their
 *  windows; at every snapshot each camera fires (rendered panorama or bearings), and the
 *  conventional method's LiDAR measures its one distance. */
class OmniPayload : public sim::Payload {
 public:
    OmniPayload(OmniSetup setup, sim::WorldOptions world);
    ~OmniPayload() override;
    void command(sim::Step& step) override;
    void sense(sim::Step& step) override;

 private:
    OmniSetup setup_;
    sim::WorldOptions world_;
    std::unique_ptr<OmniRenderer> renderer_;  ///< render mode
};

/** The camera run [omnivision] asks for; throws if it names a robot not in `robots`. */
OmniSetup omniSetupOf(const OmniOptions& options, const std::vector<std::string>& robots,
                      double duration, const std::string& origin);

/** [omnivision] swarm = N: N robots driving straight across the room at random headings,
 *  placed at random at least swarm_separation apart. */
std::vector<sim::RobotOptions> generateSwarm(const OmniOptions& options,
                                             const sim::WorldOptions& world);

void registerMethod(method::Registry& registry);

}  // namespace mrloc::omnivision
