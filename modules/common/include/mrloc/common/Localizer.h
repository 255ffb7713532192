#pragma once
// What every localization method's estimator offers the apps. A method registers a factory
// for it in its registerMethod() (mrloc/method/Registry.h); [scenario] method = <name>
// picks it. Ground truth is handed to the calls that use it, never kept between calls.
#include <mrloc/common/Outcome.h>
#include <mrloc/common/Trajectory.h>
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/obs/CObservation.h>

#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>

namespace mrloc::common {

/** Per robot name. */
using Trajectories = std::map<std::string, Trajectory>;

class Localizer {
 public:
    virtual ~Localizer() = default;

    /** Reads and validates the method's INI section(s); throws mrloc::Error. */
    virtual void configure(const mrpt::config::CConfigFileBase& ini) = 0;
    /** Writes the effective options (defaults filled in) for out/<run>/effective.ini. */
    virtual void saveConfig(mrpt::config::CConfigFileBase& target) const = 0;
    /** Feeds one observation, in rawlog order. Observations the method does not use are
     *  ignored. */
    virtual void process(const mrpt::obs::CObservation::Ptr& obs) = 0;
    /** What the method took from the log so far: observations of the kind it localizes
     *  from, how many it matched to its map or robots, why the others were not. A run that
     *  used none fails (runLocalization); a partial match is a warning. */
    virtual ObservationUse observationUse() const = 0;
    /** Estimated trajectories, per robot name. */
    virtual Trajectories estimates() const = 0;
    /** Robots whose estimates are a baseline the method is compared with (formation's
     *  dead-reckoning robot), not the method's own: shown apart, never pooled into the run's
     *  error figures. */
    virtual std::set<std::string> baselineRobots() const { return {}; }
    /** The robot's newest estimate, if any: what it reports on board in a closed-loop
     *  simulation. The default searches estimates(); methods override it to be O(1). */
    virtual std::optional<mrpt::poses::CPose3D> latestEstimate(const std::string& robot) const;
    /** The covariance of each estimate (MRPT's CPosePDFGaussian), per robot, for the
     *  methods that have one; written as covariance.<robot>.txt. Default: none. */
    virtual std::map<std::string, CovarianceTrack> covariances() const { return {}; }
    /** The method's own figures for metrics.json (fixes, rejected ranges, ...). */
    virtual nlohmann::json methodMetrics() const { return nlohmann::json::object(); }
    /** A relative method estimates in a frame of its own (seed 000: robot A at the origin,
     *  robot B on the x axis). Given every robot's ground truth in the world frame, this
     *  returns it in the estimates' frame, which the errors are computed in. Default: the
     *  world frame. */
    virtual Trajectories truthInEstimateFrame(const Trajectories& worldTruth) const {
        return worldTruth;
    }
    /** The method's figures against the truth (in the estimates' frame), merged into
     *  metrics.json's method section: e.g. relative distance errors of a layout. */
    virtual nlohmann::json truthMetrics(const Trajectories& /*truth*/) const {
        return nlohmann::json::object();
    }
    /** Figures against one robot's truth (in the estimates' frame) beyond the position
     *  errors (e.g. whether the truth is among the hypotheses); merged into
     *  metrics.json's robots.<name>. */
    virtual nlohmann::json groundTruthMetrics(const std::string& /*robot*/,
                                              const Trajectory& /*truth*/) const {
        return nlohmann::json::object();
    }
    /** Writes the method's own files into the run directory (atomically), for its report
     *  section; `truth` is in the estimates' frame (empty without ground truth). */
    virtual void writeOutputs(const std::string& /*outDir*/, const Trajectories& /*truth*/) const {}
};

}  // namespace mrloc::common
