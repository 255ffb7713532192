#pragma once
// The polygon-map method as a common::Localizer (INI: [scenario] method = polymap). Each
// robot's first 360-degree scan (<robot>.scan) gives its sensed visibility polygon V and
// the hypothesis set H (seed 002, hypothesis generation). The robot is localized when H has
// one member. With [polymap] drive, the robot then eliminated hypotheses scan by scan
// (seed 002 steps 4-10): the localizer replays that elimination on the later scans, with the
// on-board part's own code, and once one hypothesis is left estimates the pose at every
// scan.
#include <mrloc/common/Localizer.h>
#include <mrloc/polymap/PolymapOptions.h>
#include <mrpt/obs/CObservation2DRangeScan.h>

#include <map>
#include <memory>

namespace mrloc::polymap {

/** How much farther than the simulator's follower stops (sim::arrivalRadius) a robot may be
 *  found from its probe (m). */
constexpr double kArrivalMargin = 0.01;

struct RobotHypotheses {
    double time = 0;           ///< of the scan
    VisibilityPolygon sensed;  ///< V, robot frame
    double tolerance = 0;      ///< used for this scan
    std::vector<Hypothesis> hypotheses;
    HypothesisStats stats;
    std::shared_ptr<EliminationSession> session;  ///< with [polymap] drive
    std::vector<double> probeTimes;               ///< of the scans at the probes
};

/** Hypothesis generation from a robot's first scan, as the localizer and the simulated
 *  robot's on-board part both do it; `arrivalRadius`: how far from a probe the robot may be
 *  found (probeRadius). */
RobotHypotheses hypothesesFromScan(const PolymapOptions& options, const common::Polygon& map,
                                   const mrpt::obs::CObservation2DRangeScan& scan,
                                   double arrivalRadius);
/** The radius around a probe where the robot is found, for a robot of `speed` at step `dt`:
 *  where the simulator's follower stops, plus kArrivalMargin. */
double probeRadius(double speed, double dt);

class PolymapLocalizer : public common::Localizer {
 public:
    void configure(const mrpt::config::CConfigFileBase& ini) override;
    void saveConfig(mrpt::config::CConfigFileBase& target) const override;
    void process(const mrpt::obs::CObservation::Ptr& obs) override;
    std::map<std::string, common::Trajectory> estimates() const override;
    /** 2-D scans: the first of each robot (its hypotheses) and those at the probes the
     *  elimination planned; a scan after the robot is localized is not needed. */
    common::ObservationUse observationUse() const override;
    nlohmann::json methodMetrics() const override;
    nlohmann::json groundTruthMetrics(const std::string& robot,
                                      const common::Trajectory& gt) const override;
    void writeOutputs(const std::string& outDir, const common::Trajectories& truth) const override;

    const common::Polygon& map() const { return map_->polygon; }
    const GeneratedMap& generatedMap() const { return *map_; }
    const PolymapOptions& options() const { return options_; }
    const std::map<std::string, RobotHypotheses>& results() const { return results_; }

 private:
    PolymapOptions options_;
    double probeRadius_ = 0;  ///< from the INI's [scenario] dt and its robot's speed
    std::unique_ptr<GeneratedMap> map_;
    std::map<std::string, RobotHypotheses> results_;
    size_t scansSeen_ = 0, scansUsed_ = 0;
};

}  // namespace mrloc::polymap
