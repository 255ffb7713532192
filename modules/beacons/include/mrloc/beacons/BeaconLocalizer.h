#pragma once
// The "beacons" localization method: beacon TOF ranges (+ odometry) -> robot trajectories.
// Runs on any MRPT rawlog that carries CObservationBeaconRanges, with or without odometry,
// in either rawlog format; robots are told apart by the sensor label prefix ("r1.beacons").
#include <mrloc/beacons/BeaconTracker.h>
#include <mrloc/common/BeaconMap.h>
#include <mrloc/common/Localizer.h>
#include <mrpt/config/CLoadableOptions.h>

#include <map>

namespace mrloc::beacons {

/** Options of section [beacons] (every key is listed in doc/ini.md). */
struct BeaconOptions : public mrpt::config::CLoadableOptions {
    enum class Mode { Tracker, Fixes };
    Mode mode = Mode::Tracker;
    bool threeD = false;  ///< 3-D fixes; default 2-D with the receiver height known
    common::BeaconMap map;
    TrackerOptions tracker;

    void loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                            const std::string& section) override;
    void saveToConfigFile(mrpt::config::CConfigFileBase& target,
                          const std::string& section) const override;
};

class BeaconLocalizer : public common::Localizer {
 public:
    void configure(const mrpt::config::CConfigFileBase& ini) override;
    void saveConfig(mrpt::config::CConfigFileBase& target) const override;
    void process(const mrpt::obs::CObservation::Ptr& obs) override;
    std::map<std::string, common::Trajectory> estimates() const override { return estimates_; }
    nlohmann::json methodMetrics() const override;

    const BeaconOptions& options() const { return options_; }

 private:
    void fixOnly(const std::string& robot, double t,
                 const mrpt::obs::CObservationBeaconRanges& obs);
    BeaconTracker& trackerOf(const std::string& robot);

    BeaconOptions options_;
    std::map<std::string, BeaconTracker> trackers_;
    std::map<std::string, common::Trajectory> estimates_;
    std::map<std::string, double> lastHeading_;  // from odometry, for fixes-only mode
};

void registerLocalizers(common::LocalizerRegistry& registry);

}  // namespace mrloc::beacons
