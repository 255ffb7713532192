#pragma once
// The generic part of a simulation, read and validated from one INI: [scenario], [world]
// and the robots. The robots come from [scenario] robots with a [robot.<name>] section
// each, or from the method's scenario builder (a generated swarm, a robot placed in a
// floor plan): the simulator knows no method.
#include <mrloc/common/GroundTruthFile.h>
#include <mrloc/sim/Robot.h>
#include <mrloc/sim/World.h>

#include <string>
#include <vector>

namespace mrloc::sim {

/** Section [scenario]. */
struct ScenarioOptions : public mrpt::config::CLoadableOptions {
    /** Upper bounds (doc/errors.md): 1e7 steps is 28 h at the default 10 ms step. */
    static constexpr double kMaxSteps = 1e7;
    static constexpr size_t kMaxRobots = 1000;
    std::string name = "run";  ///< names the output folder and files
    /** Localization method (registry name); empty when [scenario] names none: the app then
     *  takes the one method whose sections the INI holds. */
    std::string method;
    unsigned long seed = 1;
    double duration = 60;         ///< s
    double dt = 0.01;             ///< simulation step (s)
    double startTime = 1.7e9;     ///< time stamp of t = 0 (seconds since 1970)
    double groundTruthRate = 20;  ///< Hz
    /** Multiplies every robot's systematic odometry errors (odometry_scale_error, its sigma,
     *  odometry_heading_drift, its sigma): one key for a sweep of odometry quality, as
     *  framesync's experiment_drift sweeps it (`mrloc batch --grid`). */
    double odometryErrorScale = 1;
    std::vector<std::string> robots;  ///< robots = r1 r2 ... ; each has [robot.<name>]
    /** ground_truth, ground_truth_format, ground_truth_robot, ground_truth_offset: a file of
     *  ground truth for `mrloc localize` (a relative path is the INI's). */
    common::GroundTruthSource groundTruth;

    /** The keys `mrloc localize` reads (name, method, seed, the ground truth), then the
     *  simulation's; declared once (loading, effective.ini, doc/ini.md). */
    static const common::KeyTable<ScenarioOptions>& localizeKeys();
    static const common::KeyTable<ScenarioOptions>& simulationKeys();
    /** Both, as doc/ini.md shows [scenario]. */
    static common::SectionKeys keysDocs();
    void loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                            const std::string& section) override;
    void saveToConfigFile(mrpt::config::CConfigFileBase& target,
                          const std::string& section) const override;
    /** Only the keys `mrloc localize` reads (name, method, seed, the ground truth): the
     *  [scenario] of a run that simulated nothing. */
    void saveLocalizeKeys(mrpt::config::CConfigFileBase& target, const std::string& section) const;
    /** The section describes a simulation: it is empty, or it holds a key beyond
     *  saveLocalizeKeys' (an MRPT INI may get a [scenario] of those for `mrloc localize`). */
    static bool describesSimulation(const mrpt::config::CConfigFileBase& ini,
                                    const std::string& section);
};

struct ScenarioConfig {
    ScenarioOptions scenario;
    WorldOptions world;
    std::vector<RobotOptions> robots;
    /** The method made the robots from its own section (a swarm): effective.ini then
     *  keeps that section's recipe and lists no robot. */
    bool robotsGenerated = false;

    /** [scenario] and [world], no robots yet; errors name the file, section and key. */
    static ScenarioConfig loadWithoutRobots(const mrpt::config::CConfigFileBase& ini);
    /** Also the robots of [scenario] robots, each from its [robot.<name>] section, which
     *  must exist; each must start inside the room. `methodKeys` are keys of those
     *  sections that the method reads itself. */
    static ScenarioConfig load(const mrpt::config::CConfigFileBase& ini,
                               const std::vector<std::string>& methodKeys = {});
    /** Adds robots the method made; throws if [scenario] robots names any, or if one
     *  starts outside the room. */
    void addGeneratedRobots(const mrpt::config::CConfigFileBase& ini,
                            std::vector<RobotOptions> generated);
    /** Writes [scenario], [world] and every listed robot's section. */
    void save(mrpt::config::CConfigFileBase& target) const;
};

}  // namespace mrloc::sim
