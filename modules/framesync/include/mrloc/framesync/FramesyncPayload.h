#pragma once
// The framesync method in the simulator (sim::Payload). The robots follow their waypoints
// ([robot.<name>]) with drifting odometry (the robot's odometry_scale_error and
// odometry_heading_drift keys); each step:
//   sense          every 1 / sonar_rate s, each robot's sonar rig reads the world's OctoMap
//                  (<robot>.sonar, a CObservationRange with one entry per sonar); each
//                  redefinition the decision layers were told of since the last step is
//                  written down as a comment, "framesync: <robot> redefined its frame ...";
//   onObservation  the team's on-board systems (FrameTeam) on odometry and sonar.
#include <mrloc/framesync/FramesyncConfig.h>
#include <mrloc/framesync/Sonar.h>
#include <mrloc/framesync/Team.h>
#include <mrloc/sim/Payload.h>

#include <map>
#include <memory>

namespace mrloc::framesync {

/** The world cut at every mount's height. */
using FloorSlices = std::map<double, FloorSlice>;
std::shared_ptr<const FloorSlices> sliceWorld(const sim::World& world, const SonarRigOptions& rig);
/** sliceWorld, computed once while a process asks for the same world and the same mount
 *  heights (a batch job's trials; sim::sharedWorld gives the same world); thread-safe. */
std::shared_ptr<const FloorSlices> sharedSlices(const std::shared_ptr<const sim::World>& world,
                                                const SonarRigOptions& rig);

/** The comment a decision layer writes for a redefinition. */
std::string redefinitionText(const RedefinitionEvent& e);
bool isRedefinitionText(const std::string& text);

class FramesyncPayload : public sim::Payload {
 public:
    /** `slices`: the world already cut (a Monte Carlo's runs share it); null: cut at the
     *  first step. */
    FramesyncPayload(const FramesyncConfig& config, double dt,
                     std::shared_ptr<const FloorSlices> slices = nullptr);
    void sense(sim::Step& step) override;
    void onObservation(const mrpt::obs::CObservation::Ptr& obs) override { team_.process(obs); }
    const FrameTeam& team() const { return team_; }

 private:
    FramesyncConfig config_;
    FrameTeam team_;
    long every_ = 1;  ///< steps between sonar readings
    std::shared_ptr<const FloorSlices> slices_;
};

}  // namespace mrloc::framesync
