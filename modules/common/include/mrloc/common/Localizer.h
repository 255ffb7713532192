#pragma once
// What every localization method offers the apps, and the registry through which the INI's
// [scenario] method = <name> picks one. Methods are registered explicitly by the app
// (no static initialisers, no global state).
#include <mrloc/common/Trajectory.h>
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/obs/CObservation.h>

#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace mrloc::common {

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
    /** Estimated trajectories, per robot name. */
    virtual std::map<std::string, Trajectory> estimates() const = 0;
    /** The robot's newest estimate, if any: what it reports on board in a closed-loop
     *  simulation. The default searches estimates(); methods override it to be O(1). */
    virtual std::optional<mrpt::poses::CPose3D> latestEstimate(const std::string& robot) const;
    /** The method's own figures for metrics.json (fixes, rejected ranges, ...). */
    virtual nlohmann::json methodMetrics() const { return nlohmann::json::object(); }
    /** A relative method estimates in a frame of its own (seed 000: robot A at the origin,
     *  robot B on the x axis). Given every robot's ground truth in the world frame, this
     *  returns it in the estimates' frame, which the errors are computed in. Default: the
     *  world frame. Called once, after the rawlog, before groundTruthMetrics(). */
    virtual std::map<std::string, Trajectory> truthInEstimateFrame(
        const std::map<std::string, Trajectory>& groundTruth) const {
        return groundTruth;
    }
    /** Figures against a robot's ground truth beyond the position errors (e.g. whether the
     *  truth is among the hypotheses); merged into metrics.json's robots.<name>. */
    virtual nlohmann::json groundTruthMetrics(const std::string& /*robot*/,
                                              const Trajectory& /*groundTruth*/) const {
        return nlohmann::json::object();
    }
    /** Writes the method's own files into the run directory (atomically), for the report. */
    virtual void writeOutputs(const std::string& /*outDir*/) const {}
};

class LocalizerRegistry {
 public:
    using Factory = std::function<std::unique_ptr<Localizer>()>;

    void add(const std::string& name, Factory factory);
    /** Throws mrloc::Error listing the known names if `name` is not registered. */
    std::unique_ptr<Localizer> create(const std::string& name) const;
    std::vector<std::string> names() const;

 private:
    std::map<std::string, Factory> factories_;
};

}  // namespace mrloc::common
