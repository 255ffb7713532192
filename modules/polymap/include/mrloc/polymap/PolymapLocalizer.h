#pragma once
// The polygon-map method as a common::Localizer (INI: [scenario] method = polymap). Each
// robot's first 360-degree scan (<robot>.scan) gives its sensed visibility polygon V and
// the hypothesis set H (seed 002, hypothesis generation). The robot is localized when H has
// one member; with more, it is not (part 2, elimination, moves it until one is left), and
// no estimate is written.
#include <mrloc/common/Localizer.h>
#include <mrloc/polymap/PolymapOptions.h>

#include <map>
#include <memory>

namespace mrloc::polymap {

struct RobotHypotheses {
    double time = 0;           ///< of the scan
    VisibilityPolygon sensed;  ///< V, robot frame
    double tolerance = 0;      ///< used for this scan
    std::vector<Hypothesis> hypotheses;
    HypothesisStats stats;
};

class PolymapLocalizer : public common::Localizer {
 public:
    void configure(const mrpt::config::CConfigFileBase& ini) override;
    void saveConfig(mrpt::config::CConfigFileBase& target) const override;
    void process(const mrpt::obs::CObservation::Ptr& obs) override;
    std::map<std::string, common::Trajectory> estimates() const override;
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
    std::unique_ptr<GeneratedMap> map_;
    std::map<std::string, RobotHypotheses> results_;
};

}  // namespace mrloc::polymap
