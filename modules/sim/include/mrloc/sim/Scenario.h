#pragma once
// Everything a simulation run needs, read and validated from one INI:
// [scenario], [world], [sensors], [ultrasonic], [robot.<name>] and the beacon map; or, for a
// floor-plan scenario, the polygon, its scanner and the robot's start, which the app reads
// from the method's section and hands over (the simulator knows no method).
#include <mrloc/common/BeaconMap.h>
#include <mrloc/sim/OmniCamera.h>
#include <mrloc/sim/Robot.h>
#include <mrloc/sim/Scanner.h>
#include <mrloc/sim/Sensors.h>
#include <mrloc/sim/Ultrasonic.h>
#include <mrloc/sim/World.h>

#include <optional>

namespace mrloc::sim {

/** Section [scenario]. */
struct ScenarioOptions : public mrpt::config::CLoadableOptions {
    std::string name = "run";        ///< names the output folder and files
    std::string method = "beacons";  ///< localization method (registry name)
    unsigned long seed = 1;
    double duration = 60;             ///< s
    double dt = 0.01;                 ///< simulation step (s)
    double startTime = 1.7e9;         ///< time stamp of t = 0 (seconds since 1970)
    double groundTruthRate = 20;      ///< Hz
    std::vector<std::string> robots;  ///< robots = r1 r2 ... ; each has [robot.<name>]

    void loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                            const std::string& section) override;
    void saveToConfigFile(mrpt::config::CConfigFileBase& target,
                          const std::string& section) const override;
};

struct ScenarioConfig {
    ScenarioOptions scenario;
    WorldOptions world;
    SensorOptions sensors;
    UltrasonicOptions ultrasonic;
    std::vector<RobotOptions> robots;
    common::BeaconMap beacons;           ///< empty in a floor-plan scenario
    std::optional<FloorPlan> floorPlan;  ///< walls to scan; one robot
    std::optional<OmniSetup> omni;       ///< omni-directional cameras on every robot

    /** Reads and validates; errors name the file, section and key. withBeacons = false
     *  skips the beacon map (a scenario without beacon ranging). With a floor plan,
     *  [scenario] robots defaults to r1, [robot.<name>] is optional, the robot starts at
     *  `start` (which must lie in the polygon) and no beacon map is read. */
    static ScenarioConfig load(const mrpt::config::CConfigFileBase& ini, bool withBeacons = true);
    static ScenarioConfig load(const mrpt::config::CConfigFileBase& ini, FloorPlan plan,
                               const mrpt::poses::CPose2D& start);
    /** A scenario whose robots the app made (a generated swarm): [scenario] robots must
     *  then be empty; each robot must start inside the room. No beacon map is read. */
    static ScenarioConfig load(const mrpt::config::CConfigFileBase& ini,
                               std::vector<RobotOptions> robots);
    /** Writes the effective options (the beacon map is the method's to write). */
    void save(mrpt::config::CConfigFileBase& target) const;
};

}  // namespace mrloc::sim
