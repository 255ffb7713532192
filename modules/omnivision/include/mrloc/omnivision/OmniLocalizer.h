#pragma once
// The omni-directional camera method as a common::Localizer (INI: [scenario] method =
// omnivision). It reads each robot's panoramas (<robot>.omni, detected here) or bearings
// (<robot>.omni_bearings), its odometry and, for the conventional method, the LiDAR
// distance (<A>.lidar.<B>); identifies the images at every snapshot (at t_b, with
// search_at_tb = localized, only eq. (11)-(12)'s triangle); and solves the layout at t_e
// (proposed) or at the snapshot (conventional) in the paper's frame: A at the origin, B on
// the x axis. Estimates (position and heading), and the truth they are compared with, are
// in that frame.
#include <mrloc/common/Localizer.h>
#include <mrloc/common/OdometryPath.h>
#include <mrloc/omnivision/Accuracy.h>
#include <mrloc/omnivision/OmniOptions.h>
#include <mrloc/omnivision/Refinement.h>
#include <mrloc/omnivision/RelativeLocation.h>
#include <mrloc/omnivision/RestartSearch.h>
#include <mrpt/poses/CPose2D.h>

#include <map>
#include <optional>

namespace mrloc::omnivision {

/** Everything one solve produced. */
struct OmniResult {
    std::vector<std::string> robots;    ///< index -> name
    std::vector<std::string> restarts;  ///< why earlier stopped pairs failed
    /** search_at_tb = localized: eq. (11)-(12)'s work in each round that got that far. */
    struct LocalizedCost {
        std::string pair;
        size_t witnessesTried = 0, triples = 0, triangles = 0;
        std::string fallback;  ///< why the full search ran instead (empty: it did not)
    };
    std::vector<LocalizedCost> localizedSearches;
    int a = -1, b = -1, moving = -1;
    double time = 0;                  ///< of the layout (t_e, or the conventional snapshot)
    double timeBefore = 0;            ///< t_b (proposed)
    double travelled = 0;             ///< l_C
    std::vector<Snapshot> snapshots;  ///< [t_b,] t_e
    std::vector<Identification> ids;
    Solution paper;  ///< at `time`
    std::optional<RefinedLayout> refined;
    std::vector<std::optional<Vec2>> final() const;           ///< refined if any, else paper
    std::vector<std::optional<double>> finalHeading() const;  ///< the same, headings (rad)
};

class OmniLocalizer : public common::Localizer {
 public:
    void configure(const mrpt::config::CConfigFileBase& ini) override;
    void saveConfig(mrpt::config::CConfigFileBase& target) const override;
    void process(const mrpt::obs::CObservation::Ptr& obs) override;
    /** Each robot's pose in the layout at its time, then carried on by its own odometry at
     *  every later reading (beyond paper 000, which solves one instant): the relative
     *  positions over the rest of the log, with the odometry's drift. */
    std::map<std::string, common::Trajectory> estimates() const override;
    /** The refinement's covariance of (x, y, heading) at the layout's time (A's x and y
     *  are zero: it is the frame's origin; B's y too). None without `refine`. */
    std::map<std::string, common::CovarianceTrack> covariances() const override;
    common::Trajectories truthInEstimateFrame(
        const common::Trajectories& worldTruth) const override;
    /** Each robot's view at a time: a panorama (<robot>.omni) or its bearings
     *  (<robot>.omni_bearings); every one enters the snapshot of its time. */
    common::ObservationUse observationUse() const override;
    nlohmann::json methodMetrics() const override;
    nlohmann::json truthMetrics(const common::Trajectories& truth) const override;
    /** layout.txt (OmniFiles.h). */
    void writeOutputs(const std::string& outDir, const common::Trajectories& truth) const override;
    /** The true layout at t_b and t_e (truth in the paper's frame) with this run's
     *  sightings: the input of the accuracy sweep. Throws if a robot has no truth. */
    AccuracyLayout accuracyLayout(const common::Trajectories& truth) const;

    /** Solves (once); throws mrloc::Error when no stopped pair works. */
    const OmniResult& result() const;
    const OmniOptions& options() const { return options_; }

 private:
    OmniOptions options_;
    std::string origin_;
    std::map<double, std::map<std::string, View>> views_;  ///< time -> robot -> view
    std::optional<double> firstTime_;  ///< the rawlog's first observation: t_b, t_e count from it
    /** Per robot, per odometry reading: t, path length, heading (unwrapped). */
    struct OdometerReading {
        double t, length, heading;
    };
    std::map<std::string, std::vector<OdometerReading>> odometer_;
    std::map<std::string, common::OdometryPath> odometryPaths_;
    /** Per robot, its odometry readings as poses: they carry the layout on after its time. */
    std::map<std::string, common::Trajectory> odometryPoses_;
    struct LidarReading {
        double time;
        std::string from, to;
        double distance;
    };
    std::vector<LidarReading> lidar_;
    mutable std::optional<OmniResult> result_;  ///< solved once, on first use

    /** The odometer's path length over [t0, t1] (m) and its heading change (rad; 0 for a
     *  robot without odometry). */
    double travelledBetween(const std::string& robot, double t0, double t1) const;
    double turnedBetween(const std::string& robot, double t0, double t1) const;
    Snapshot snapshotAt(double t, const std::vector<std::string>& robots) const;
    /** Each robot's true pose at the layout's time, in the paper's frame. */
    std::vector<std::optional<mrpt::poses::CPose2D>> truthAtLayout(
        const common::Trajectories& truth) const;
};

}  // namespace mrloc::omnivision
