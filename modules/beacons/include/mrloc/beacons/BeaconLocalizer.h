#pragma once
// The "beacons" localization method: beacon TOF ranges (+ odometry) -> robot trajectories.
// Runs on any MRPT rawlog that carries CObservationBeaconRanges, with or without odometry,
// in either rawlog format; robots are told apart by the sensor label prefix ("r1.beacons").
#include <mrloc/beacons/BeaconMap.h>
#include <mrloc/beacons/BeaconRanging.h>
#include <mrloc/beacons/BeaconStudy.h>
#include <mrloc/beacons/BeaconTracker.h>
#include <mrloc/beacons/RangeWindow.h>
#include <mrloc/beacons/RfBeacon.h>
#include <mrloc/common/KeyTable.h>
#include <mrloc/common/Localizer.h>
#include <mrloc/common/OdometryPath.h>
#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/obs/CObservationBearingRange.h>

#include <map>
#include <vector>

namespace mrloc::beacons {

/** Options of section [beacons] (every key is listed in doc/ini.md). */
struct BeaconOptions : public mrpt::config::CLoadableOptions {
    enum class Mode { Tracker, Fixes };
    Mode mode = Mode::Tracker;
    /** What the tracker takes of a camera's sightings (CObservationBearingRange). */
    enum class Sightings { Both, Range, Bearing };
    Sightings sightings = Sightings::Both;
    bool threeD = false;  ///< 3-D fixes; default 2-D with the receiver height known
    BeaconMap map;
    TrackerOptions tracker;
    RfBeaconOptions system;  ///< aiming, scheduling and sections (the RF beacon's side)
    /** paper_reception_<id> = % per robot: seed 001 Tables 3/4, for the report. */
    std::map<int, std::vector<double>> paperReception;
    /** s: ranges read one at a time (too few for a fix) are gathered over this span
     *  into one epoch until the tracker has started (RangeWindow); 0: never */
    double rangeWindow = 1.0;
    /** delay_compensation: the fixes subtract the delay the tone decoder is expected to add
     *  to each shot (the [ultrasonic] link's nominal model at the fix's distance and the
     *  head's off-axis angle: 0 when heads aim at the robot, from the section's aim point
     *  when fixed); sets tracker.rangeDelay. */
    bool delayCompensation = false;
    /** Where range_sigma came from when [beacons] does not give it: MRPT's key, or empty. */
    std::string rangeSigmaFrom;
    /** Where the start pose came from when [beacons] start is absent: MRPT's key, or empty. */
    std::string startFrom;

    /** Every key: name, member, bounds, unit, doc (doc/ini.md's table is made from it). */
    static const common::KeyTable<BeaconOptions>& keys();
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
    /** Tracker mode: the filter's covariance at each estimate; fixes mode: the fix's
     *  position covariance, the heading's terms unknown (nan: it comes from odometry). */
    std::map<std::string, common::CovarianceTrack> covariances() const override {
        return covariances_;
    }
    std::optional<mrpt::poses::CPose3D> latestEstimate(const std::string& robot) const override;
    nlohmann::json methodMetrics() const override;
    /** Beacon ranges: used are those matched to a beacon of the map that reached a fix or
     *  the filter; the others came from unknown beacons or from epochs whose fix failed. */
    common::ObservationUse observationUse() const override;

    const BeaconOptions& options() const { return options_; }
    /** [beacons_study] and the hardware it simulates ([ultrasonic], [sensors]); its
     *  options' `enabled` is false without the section. */
    const StudyOptions& study() const { return study_; }
    const UltrasonicOptions& studyUltrasonic() const { return studyUltrasonic_; }
    const SensorOptions& studySensors() const { return studySensors_; }

 private:
    void fixOnly(const std::string& robot, double t,
                 const mrpt::obs::CObservationBeaconRanges& obs);
    BeaconTracker& trackerOf(const std::string& robot);

    BeaconOptions options_;
    StudyOptions study_;
    UltrasonicOptions studyUltrasonic_;
    SensorOptions studySensors_;
    std::map<std::string, BeaconTracker> trackers_;
    std::map<std::string, common::Trajectory> estimates_;
    std::map<std::string, common::CovarianceTrack> covariances_;
    /** The epoch the tracker is given: the observation itself, or, while the tracker has not
     *  started and the observation has fewer ranges than a fix needs, the window's epoch
     *  (nothing until the window has enough beacons). */
    std::optional<mrpt::obs::CObservationBeaconRanges> windowed(
        const std::string& robot, double t, const mrpt::obs::CObservationBeaconRanges& obs);
    /** The ranges of a window epoch counted once each (observationUse). */
    void countWindowed(const TrackerStats& before, const TrackerStats& after, size_t newRanges);
    std::map<std::string, RangeWindow> windows_;
    std::map<std::string, size_t> mostRanges_;  ///< per robot: the most ranges one observation held
    size_t windowEpochs_ = 0;                   ///< epochs made of ranges read one at a time
    struct WindowCount {
        size_t seen = 0, used = 0;            ///< each range once
        size_t fedReceived = 0, fedUsed = 0;  ///< as the tracker counted them, repeats included
    } windowCount_;
    /** Ranges as they would have been read at the epoch's time stamp (see doc/beacons.md). */
    mrpt::obs::CObservationBeaconRanges compensateMotion(
        const std::string& robot, const mrpt::obs::CObservationBeaconRanges& obs);
    /** An estimate and its covariance (unknown terms nan); `measured`: at a sighting or an
     *  epoch, not bridged by odometry between them (the spacing counts those only). */
    void addEstimate(const std::string& robot, double t, const mrpt::poses::CPose3D& pose,
                     const std::optional<mrpt::math::CMatrixDouble33>& cov, bool measured);
    void addEstimate(const std::string& robot, double t, const BeaconTracker& tracker,
                     bool measured);
    /** A camera's sightings of landmarks (range and bearing, BeaconOptions::sightings). */
    void sighted(const std::string& robot, double t,
                 const mrpt::obs::CObservationBearingRange& camera);
    size_t sightingObservations_ = 0, sightingsNotInMap_ = 0;
    std::map<std::string, double> firstSeen_;  ///< per robot: its first observation's time

    /** How far apart (by odometry) and how long apart a robot's estimates are. */
    struct Spacing {
        double sinceLast = 0;  ///< odometry path length since the last estimate (m)
        std::optional<double> lastMeasured;  ///< time of the last estimate from a sighting
        double maxDistance = 0, sumDistance = 0, maxTime = 0;
        size_t gaps = 0;
    };

    std::map<std::string, common::OdometryPath> odometry_;  ///< per robot
    std::map<std::string, Spacing> spacing_;
};

/** What runs on board in a closed-loop simulation of the beacon system: the robots'
 *  estimator and the RF beacon that aims and schedules from what they report (used by the
 *  method's payload, BeaconPayload.h). */
struct OnboardBeacons {
    explicit OnboardBeacons(const mrpt::config::CConfigFileBase& ini);
    BeaconLocalizer localizer;
    RfBeacon rfBeacon;
};

}  // namespace mrloc::beacons
