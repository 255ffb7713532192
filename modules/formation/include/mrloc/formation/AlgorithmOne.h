#pragma once
// Seed 003 Algorithm 1 from pixels: the moving robot, near its target vertex and facing away
// from the beacons, looks back at them with its rear camera and moves until the anchor is
// centred, the base beacons are symmetric about it (d_m1 = d_m2) and as far from it as a
// perfect triangle puts them (d_m1 = d_t). A unicycle with actuation noise executes each
// maneuver; the camera renders the scene and the tags are detected in every frame, so the
// vertex error emerges from pixels and control.
#include <mrloc/formation/Markers.h>
#include <mrloc/sim/PinholeCamera.h>
#include <mrpt/random/RandomGenerators.h>

#include <array>
#include <vector>

namespace mrloc::formation {

struct AlgorithmOneOptions {
    double side = 1.5;            ///< m, the triangles' side
    double pixelTolerance = 2.0;  ///< px: d_m1 = d_m2 and d_m1 = d_t within this (the far
                                  ///< anchor tag's centre is found within about 3 px)
    int maxManeuvers = 60;
    double turnNoise = 0.02;     ///< relative error of each turn (sd)
    double driveNoise = 0.02;    ///< relative error of each drive (sd)
    double cameraHeight = 0.13;  ///< m, the rear camera's height (the tags' centre)
};

/** The beacons: base b1, base b2 and the anchor as the formation believes them (the perfect
 *  triangle, their headings), with their robot indices (tag ids). A tag sits on a face, up to
 *  bodySize / 2 beside its robot's centre in the picture; the belief says by how much, so
 *  Algorithm 1 works on the robots' centres. */
struct BeaconTriangle {
    std::array<mrpt::poses::CPose2D, 3> pose;  ///< b1, b2, anchor
    std::array<size_t, 3> robot{0, 1, 2};
};

struct AlgorithmOneResult {
    mrpt::poses::CPose2D end;  ///< where the robot stopped (its centre, world frame)
    bool converged = false;    ///< every condition met within the tolerance
    int maneuvers = 0;         ///< turns and drives executed
    int frames = 0;            ///< pictures rendered and searched
    double dm1 = 0, dm2 = 0;   ///< the last lateral distances (px)
};

/** Seed 003 fig. 3g in an open world: base beacons 0 and 1 at (0, 0) and (side, 0), anchor 2
 *  at (side / 2, h), all facing east; the perfect vertex (side / 2, -h), facing away. */
struct BuildingStep {
    mrpt::opengl::COpenGLScene::Ptr scene;
    BeaconTriangle beacons;
    mrpt::poses::CPose2D vertex;
};
BuildingStep buildingStep(double side, const MarkerOptions& markers);

/** A 1280 x 720 camera of focal length f px, centred. */
mrpt::img::TCamera cameraIntrinsics(double f);

/** The lateral distance d_t (px) between the anchor's and a base beacon's centres in the rear
 *  camera of a robot at the perfect vertex (the camera on its back face, bodySize / 2 behind
 *  its centre): f (side / 2) / (h - bodySize / 2). */
double targetDisparity(const mrpt::img::TCamera& k, const MarkerOptions& markers, double side);

/** Runs Algorithm 1 from `start` (the robot's centre and heading) among `beacons` in
 *  `scene` (the beacons already added; the moving robot is not in its own view). */
AlgorithmOneResult runAlgorithmOne(const mrpt::opengl::COpenGLScene& scene,
                                   const BeaconTriangle& beacons, mrpt::poses::CPose2D start,
                                   sim::PinholeCamera& camera, const MarkerOptions& markers,
                                   const AlgorithmOneOptions& options,
                                   mrpt::random::CRandomGenerator& rng);

}  // namespace mrloc::formation
