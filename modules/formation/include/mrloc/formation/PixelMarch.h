#pragma once
// The formation marching along a route from pixels alone, off the simulator's clock: every
// move is steered by the moving robot's cameras (CameraMove) among the robots' real poses,
// each maneuver executed with its errors (executed) in one piece, each frame rendered from the
// scene built once for the march (FormationScene) and seen through the camera model
// (CameraModel). The pixel experiment (Table 1 from pixels) runs it; the simulator's pixel mode
// steers the same CameraMove step by step.
#include <mrloc/formation/CameraModel.h>
#include <mrloc/formation/CameraMove.h>
#include <mrloc/formation/FormationConfig.h>
#include <mrloc/formation/March.h>
#include <mrloc/sim/PinholeCamera.h>

#include <string>
#include <vector>

namespace mrloc::formation {

struct PixelMarchOptions {
    MarchOptions march;        ///< side, wheel radius and speed, move bound
    CameraMoveOptions camera;  ///< cameras, tags, Algorithm 1, gates; maneuver noise in
                               ///< camera.algorithmOne.noise
    CameraModelOptions lens;   ///< the camera model
    double maxTurnRate = 1.5;  ///< rad/s, for the march's time
};

struct PixelMarchResult {
    MarchResult march;  ///< every move (believed and true vertex, time), arrived
    size_t frames = 0;  ///< pictures rendered and searched
    /** Moves whose beacons the camera lost for good (finished by the belief), and gates
     *  driven by the belief (a gate's beacons not both in view). */
    size_t lostMoves = 0, blindGates = 0;
    /** Per move: the formation's rotation against the believed lattice (rad; the angle of
     *  the least-squares rotation of every robot's believed position onto its true one), and
     *  the step's own error along and across the true base (m; the true end against the
     *  true anchor reflected across the true base, as formation.run.txt's). */
    std::vector<double> rotation, lateral, longitudinal;
};

/** The pixel mode's cameras and control from [formation]. */
CameraMoveOptions cameraMoveOptions(const FormationConfig& config);
/** A pixel march's options from [formation] at wheel speed `wheelSpeed` (rad/s). */
PixelMarchOptions pixelMarchOptions(const FormationConfig& config, double wheelSpeed);

/** What the march's camera renders: the cameras' intrinsics, enlarged for the lens
 *  (CameraModel::renderIntrinsics). Create the march's sim::PinholeCamera with it. */
mrpt::img::TCamera renderIntrinsics(const PixelMarchOptions& options);

/** The least-squares rotation (rad) that takes `believed` onto `truth`, both about their
 *  centroids (2-D Kabsch): the formation's heading error. */
double latticeRotation(const std::vector<TPoint2D>& believed, const std::vector<TPoint2D>& truth);

/** N robots from initialStrip march through `route` (as march()), each move from `camera`'s
 *  frames. Time: each turn at maxTurnRate, each drive at the robots' speed (frames are taken
 *  at rest and not timed). `camera` (of renderIntrinsics(options)) must draw no other scene
 *  during the march. */
PixelMarchResult pixelMarch(size_t robots, const std::vector<TPoint2D>& route,
                            const std::vector<Obstacle>& obstacles,
                            const PixelMarchOptions& options, sim::PinholeCamera& camera,
                            mrpt::random::CRandomGenerator& rng);

}  // namespace mrloc::formation
