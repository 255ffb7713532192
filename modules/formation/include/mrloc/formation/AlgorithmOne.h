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
#include <optional>
#include <vector>

namespace mrloc::formation {

/** How far a maneuver's execution strays: each turn's and drive's relative error (sd). The
 *  pixel mode's robots and Algorithm 1's own test loop execute maneuvers through
 *  `executed`, so both stray alike. */
struct ManeuverNoise {
    double turn = 0.02, drive = 0.02;
    /** Wheel slip: the share of a maneuver the wheels lose on the floor, half-normal with
     *  this sd (a slipping wheel falls short, never long); 0: none. */
    double slip = 0;
};

struct AlgorithmOneOptions {
    double side = 1.5;            ///< m, the triangles' side
    double pixelTolerance = 2.0;  ///< px: d_m1 = d_m2 and d_m1 = d_t within this (the far
                                  ///< anchor tag's centre is found within about 3 px)
    int maxManeuvers = 60;
    ManeuverNoise noise;         ///< of each maneuver's execution
    double cameraHeight = 0.13;  ///< m, the rear camera's height (the tags' centre)
    /** The lateral condition (doc/formation.md):
     *  - Paper: d_m1 = d_m2, the base beacons symmetric about the anchor in the image (seed
     *    003 Algorithm 1). The camera axis then bisects the angle between the base beacons,
     *    which meets the base beside its midpoint: an anchor off by d puts the vertex 2 d
     *    the other way, and chained moves amplify the errors.
     *  - Midpoint: the anchor in line with the base's midpoint M, whose image lies between
     *    the base tags' at their depths' ratio (read from the tags' sizes against the sizes
     *    the belief predicts). The vertex is then the reflection of the real anchor across
     *    the real base: an anchor off by d puts it d the other way. */
    enum class Lateral { Paper, Midpoint } lateral = Lateral::Paper;
    /** Every correction one frame asks for executed before the next frame (the centring
     *  turn, the sideways maneuver and the depth drive, each from the same frame to first
     *  order), rather than one per frame as the paper's steps are listed; the stop conditions
     *  are the paper's. The pixel march's gates and face-away step do the same (a turn and
     *  its drive from one frame). */
    bool together = false;
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

/** One motion of a unicycle: a turn on the spot (rad, positive counter-clockwise) or a drive
 *  along its heading (m, negative backwards). */
struct Maneuver {
    enum class Kind { Turn, Drive } kind = Kind::Turn;
    double amount = 0;
    static Maneuver turn(double angle) { return {Kind::Turn, angle}; }
    static Maneuver drive(double distance) { return {Kind::Drive, distance}; }
};

/** The maneuver as the wheels execute it: its amount times 1 + noise x N(0, 1), and times
 *  1 - |slip x N(0, 1)| when there is slip. */
Maneuver executed(Maneuver m, const ManeuverNoise& noise, mrpt::random::CRandomGenerator& rng);

/** A unicycle at `pose` after maneuver m (a turn on the spot or a drive along its heading). */
void applyManeuver(mrpt::poses::CPose2D& pose, const Maneuver& m);

/** The rear camera on the robot's back face, looking backwards, at `height`. */
mrpt::poses::CPose3D rearCameraPose(const mrpt::poses::CPose2D& robot, double bodySize,
                                    double height);
/** The front camera on the robot's front face, looking ahead, at `height`. */
mrpt::poses::CPose3D frontCameraPose(const mrpt::poses::CPose2D& robot, double bodySize,
                                     double height);

/** Seed 003 Algorithm 1's decisions, frame by frame: given the tags of the rear camera's
 *  frame, the maneuvers to execute before the next frame. */
class AlgorithmOneController {
 public:
    AlgorithmOneController(const BeaconTriangle& beacons, const mrpt::img::TCamera& k,
                           const MarkerOptions& markers, const AlgorithmOneOptions& options);
    /** Empty: every condition holds (converged). Nothing: a beacon is out of view. */
    std::optional<std::vector<Maneuver>> decide(const std::vector<MarkerSighting>& tags);
    /** Multiplies the pixel tolerance of the three conditions by `factor`. */
    void relaxTolerance(double factor) { o_.pixelTolerance *= factor; }
    double dm1() const { return dm1_; }  ///< px, the last lateral distances
    double dm2() const { return dm2_; }

 private:
    BeaconTriangle beacons_;
    mrpt::img::TCamera k_;
    AlgorithmOneOptions o_;
    double dt_ = 0, gain_ = 0, slope_ = 0;
    std::array<std::array<double, 4>, 3> shift_{};  ///< px per beacon and side, tag -> centre
    std::array<std::array<double, 4>, 3> size_{};   ///< px per beacon and side at the vertex
    double dm1_ = 0, dm2_ = 0;
};

/** Runs Algorithm 1 from `start` (the robot's centre and heading) among `beacons` in
 *  `scene` (the beacons already added; the moving robot is not in its own view); each frame
 *  seen through `lens` (CameraModel) when given, else searched as rendered. */
AlgorithmOneResult runAlgorithmOne(const mrpt::opengl::COpenGLScene& scene,
                                   const BeaconTriangle& beacons, mrpt::poses::CPose2D start,
                                   sim::PinholeCamera& camera, const MarkerOptions& markers,
                                   const AlgorithmOneOptions& options,
                                   mrpt::random::CRandomGenerator& rng,
                                   const class CameraModel* lens = nullptr);

}  // namespace mrloc::formation
