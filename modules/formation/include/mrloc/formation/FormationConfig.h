#pragma once
// Section [formation]: the formation method's options (keys and defaults in doc/ini.md).
// The team, its route and its sensors for the simulator and the localizer, and the Monte
// Carlo experiment of seed 003 sec. 5 (Table 1, figs. 14-15).
#include <mrloc/common/KeyTable.h>
#include <mrloc/common/Seeds.h>
#include <mrloc/formation/AlgorithmOne.h>
#include <mrloc/formation/CameraModel.h>
#include <mrloc/formation/DeadReckoning.h>
#include <mrloc/formation/March.h>
#include <mrloc/sim/Scanner.h>
#include <mrpt/config/CLoadableOptions.h>

#include <string>
#include <vector>

namespace mrloc::formation {

struct FormationConfig : public mrpt::config::CLoadableOptions {
    /** Upper bounds (doc/errors.md): robots by the 36h11 family's ids (4 tags per robot),
     *  moves and Monte Carlo runs by time. */
    static constexpr long kMaxRobots = 146, kMaxMoves = 100000, kMaxRuns = 100000;
    /** Table 1 from pixels: a pixel march takes seconds (doc/errors.md, "Work"). */
    static constexpr long kMaxPixelRuns = 1000;

    /** Where a move ends: drawn from the paper's per-step errors (Model), or where the
     *  robot's cameras steer it, frame by frame (Pixel: CameraMove). */
    enum class Mode { Model, Pixel } mode = Mode::Model;
    size_t robots = 4;                     ///< N >= 4, on initialStrip
    FormationOptions formation;            ///< side, safety margin
    TPoint2D origin{3, 3};                 ///< world position of the paper's (0, 0)
    std::string routeName = "many_turns";  ///< many_turns | patrol | custom (waypoints)
    std::vector<TPoint2D> waypoints;       ///< the route, paper frame (from routeName or the INI)
    double wheelRadius = 0.035, wheelSpeed = paper::kWheelSpeedFast;  ///< m, rad/s
    double maxTurnRate = 1.5;                                         ///< rad/s
    MarchOptions::Carry carry = MarchOptions::Carry::Base;
    VertexErrorModel vertexErrors;
    DeadReckoningOptions deadReckoning;
    // The pixel mode's cameras and control (CameraMove, AlgorithmOne)
    /** The front and rear cameras: camera_width x camera_rows px, the rows a band about the
     *  horizon (the tags stand at the cameras' height: the rows above and below never hold
     *  one), focal length camera_focal px (a 105-degree horizontal field of view). */
    size_t cameraWidth = 640, cameraRows = 200;
    double cameraFocal = 242.5;
    double pixelTolerance = 2;  ///< px, Algorithm 1's conditions
    /** Each frame's corrections executed together (AlgorithmOneOptions::together), or one
     *  per frame (the paper's steps as listed). */
    bool together = true;
    CameraModelOptions lens;  ///< the camera model: distortion, blur, noise, exposure
    /** Algorithm 1's lateral condition: ours by default (the paper's amplifies errors when
     *  moves are chained; doc/formation.md). */
    AlgorithmOneOptions::Lateral lateral = AlgorithmOneOptions::Lateral::Midpoint;
    /** After Algorithm 1, the pose fitted to every robot in the rear view and the vertex
     *  corrected by it (CameraMoveOptions::latticeFit; N >= 5; ours, doc/formation.md: off,
     *  since it measured no better). */
    bool latticeFit = false;
    double gateStop = 0.8;                                 ///< m before a gate to centre again
    ManeuverNoise maneuverNoise;                           ///< turn_noise, drive_noise
    sim::ScannerOptions obstacleSensor{72, 0.01, 4.0, 0};  ///< rays, sigma, range (rate unused)
    double obstacleSensorHeight = 0.1;                     ///< m
    double obstacleCell = 0.1;  ///< m: detections are shared one per cell
    size_t maxMoves = 10000;
    // The experiment (seed 003 Table 1, figs. 14-15): 0 runs, none.
    size_t runs = 100;
    std::vector<double> experimentSpeeds{paper::kWheelSpeedFast, paper::kWheelSpeedSlow};
    std::vector<std::string> experimentRoutes{"many_turns", "patrol"};
    size_t experimentRobotsMax = 10;  ///< fig. 15: N = 4 .. this
    size_t cameraStarts = 27;         ///< Algorithm 1 from pixels: a 3 x 3 x 3 grid, or 0
    /** Table 1 from pixels: pixel marches per route and speed (0: none), on every core. */
    size_t pixelRuns = 0;
    /** experiment_seed: run r of Table 1 draws from experimentSeed + r; without the key, the
     *  run's seed (common/Seeds.h). */
    common::SubSeed experimentSeed{1, false};

    /** The route in the world frame (waypoints + origin), starting at the strip's centre. */
    std::vector<TPoint2D> worldRoute() const;
    /** The robots' starts in the world frame (initialStrip + origin). */
    std::vector<TPoint2D> worldStrip() const;
    double speed() const { return wheelRadius * wheelSpeed; }  ///< m/s
    /** The front and rear cameras' intrinsics (camera_width, camera_rows, camera_focal). */
    mrpt::img::TCamera cameraIntrinsics() const;

    /** Every key of [formation], declared once (loading, effective.ini, doc/ini.md). */
    static const common::KeyTable<FormationConfig>& keys();

    void loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                            const std::string& section) override;
    void saveToConfigFile(mrpt::config::CConfigFileBase& target,
                          const std::string& section) const override;
};

/** The formation robots' names, f1 .. fN, and the dead-reckoning robot's. */
std::vector<std::string> formationRobotNames(size_t robots);
inline const std::string kDeadReckoningRobot = "dr";

}  // namespace mrloc::formation
