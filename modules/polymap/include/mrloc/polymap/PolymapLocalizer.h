#pragma once
// The polygon-map method as a common::Localizer (INI: [scenario] method = polymap). Each
// robot's first 360-degree scan (<robot>.scan) gives its sensed visibility polygon V and
// the hypothesis set H (seed 002, hypothesis generation). The robot is localized when H has
// one member. With [polymap] drive, the robot then eliminated hypotheses scan by scan
// (seed 002 steps 4-10): the localizer replays that elimination on the later scans, with the
// on-board part's own code, and once one hypothesis is left estimates the pose at every
// scan.
#include <mrloc/common/Localizer.h>
#include <mrloc/polymap/GridTrace.h>
#include <mrloc/polymap/PolymapOptions.h>
#include <mrloc/polymap/ScanLocalizer.h>
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

/** The pictures the scan localizer writes into the run folder. */
inline constexpr const char* kTracePicture = "polymap.trace.png";
inline std::string scanPicture(const std::string& robot) {
    return "polymap." + robot + ".scan.png";
}

/** A robot localized from real scans ([polymap] localizer = scan). */
struct ScanRobot {
    std::vector<PoseHypothesis> first;  ///< from the first scan, best first
    SearchStats stats;
    double tolerance = 0;  ///< the beams' (m)
    double firstTime = 0;
    std::shared_ptr<PassiveElimination> elimination;
    std::optional<mrpt::math::TPose2D> odometry, odometryAtScan;
    double travelled = 0;  ///< odometry path since the first scan (m)
    /** A step-indexed reference's time base: step i is the i-th action (odometry reading)
     *  with the sensory frame after it, as MRPT's apps pair them (getActionObservationPair),
     *  so its time is that of the first scan after the i-th odometry reading. */
    std::vector<double> stepTimes;
    size_t stepsWaiting = 0;  ///< odometry readings not yet followed by a scan
};

/** The estimates beside a reference path (another localizer's), over the estimates at times
 *  the reference covers. */
struct ReferenceComparison {
    size_t n = 0;
    double mean = 0, median = 0, max = 0, last = 0;  ///< position (m)
    double headingMean = 0, headingMax = 0;          ///< deg
    double from = 0;  ///< the first compared time (s since the first scan)
};

class PolymapLocalizer : public common::Localizer {
 public:
    void configure(const mrpt::config::CConfigFileBase& ini) override;
    void saveConfig(mrpt::config::CConfigFileBase& target) const override;
    void process(const mrpt::obs::CObservation::Ptr& obs) override;
    /** Hypotheses mode: once one hypothesis is left, the start it gives, then that start
     *  carried by the robot's odometry to each of its readings from the first scan on (the
     *  path from the start found, after the fact); without odometry, the start and each probe
     *  the robot scanned at. Scan mode: the hypothesis left at every scan it lived. */
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
    /** False for a grid map or a .poly beyond common::Polygon's vertex bound (scan
     *  localizer only): no simulation. */
    bool hasPolygon() const { return map_ != nullptr; }
    const PolymapOptions& options() const { return options_; }
    const std::map<std::string, RobotHypotheses>& results() const { return results_; }
    bool scanMode() const { return options_.scanMode; }
    const WallMap& wallMap() const { return *wallMap_; }
    const std::map<std::string, ScanRobot>& scanResults() const { return scanRobots_; }
    const TraceStats& traceStats() const { return traceStats_; }
    /** The reference path in the log's time (step-indexed rows at the odometry's times). */
    common::Trajectory referencePath(const std::string& robot) const;
    std::optional<ReferenceComparison> compareWithReference(const std::string& robot) const;
    /** The grid a .gridmap / .simplemap map was traced from (nullptr otherwise). */
    const mrpt::maps::COccupancyGridMap2D* grid() const { return grid_.get(); }

 private:
    void configureScanMode();
    void processScanMode(const mrpt::obs::CObservation::Ptr& obs);
    std::map<std::string, common::Trajectory> scanEstimates() const;
    nlohmann::json scanMetrics() const;

    PolymapOptions options_;
    std::unique_ptr<WallMap> wallMap_;
    std::shared_ptr<mrpt::maps::COccupancyGridMap2D> grid_;
    TraceStats traceStats_;
    std::map<std::string, ScanRobot> scanRobots_;
    common::Trajectory reference_;  ///< step-indexed: t is the step until mapped
    bool referenceByStep_ = false;
    nlohmann::json referenceNotes_;  ///< the reference file's comment lines
    double probeRadius_ = 0;         ///< from the INI's [scenario] dt and its robot's speed
    std::unique_ptr<GeneratedMap> map_;
    std::map<std::string, RobotHypotheses> results_;
    /** Per robot, its odometry readings (hypotheses mode): they carry the start found on to
     *  every reading. */
    std::map<std::string, common::Trajectory> odometry_;
    size_t scansSeen_ = 0, scansUsed_ = 0;
};

}  // namespace mrloc::polymap
