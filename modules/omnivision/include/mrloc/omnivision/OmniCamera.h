#pragma once
// Omni-directional cameras on every robot (seed 000): each robot carries the same marker,
// a coloured band around the camera, so that a camera sees the others but cannot tell
// them apart.
//  - render mode: the panorama (omnivision::Panorama) rendered off screen with
//    sim::PinholeCamera in the world's scene, `views` pinhole views stitched into one strip, as a
//    CObservationImage <robot>.omni;
//  - bearings mode: the bearings of the visible markers with Gaussian noise, as a
//    CObservationBearingRange <robot>.omni_bearings (range and identity unknown), for
//    fast Monte Carlo.
// A marker is visible within max_range when no other marker blocks the line of sight.
#include <mrloc/omnivision/Panorama.h>
#include <mrloc/sim/World.h>
#include <mrpt/img/CImage.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CObservationImage.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/random/RandomGenerators.h>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace mrloc::omnivision {

struct OmniCameraOptions {
    bool render = true;                       ///< false: bearings mode
    Panorama panorama;                        ///< render mode
    double bearingSigma = 0.05 * M_PI / 180;  ///< bearings mode noise (rad)
    double maxRange = 0;                      ///< m; 0: unlimited
    double markerRadius = 0.15;               ///< m: the band's radius (and what blocks sight)
    double markerHeight = 0.2;                ///< m
    double cameraHeight = 0.5;                ///< m: camera and band centre above the floor
};

/** The omni-directional camera run of a scenario (seed 000), from [omnivision]: when every camera
 * fires, who stands still when, and (for the conventional method) one LiDAR distance measured at
 * each snapshot. */
struct OmniSetup {
    OmniCameraOptions camera;
    std::vector<double> snapshotTimes;  ///< s from the start; all cameras fire together
    struct Stop {
        std::string robot;
        double from = 0, to = 0;  ///< s: the robot stands still in [from, to]
    };
    std::vector<Stop> stops;
    struct Lidar {
        std::string from, to;  ///< `from` measures its distance to `to`: <from>.lidar.<to>
        double sigma = 0.01;   ///< m
    };
    std::optional<Lidar> lidar;
};

/** What robot `observer` would see: the true bearings (robot frame) of the visible
 *  robots, and which robot each is. */
struct TrueSighting {
    std::vector<double> bearings;
    std::vector<int> robots;
};
/** Whether nothing stands between two points (the world's walls and obstacles:
 *  sim::World::lineOfSight); empty: open space. */
using LineOfSight =
    std::function<bool(const mrpt::math::TPoint3D& from, const mrpt::math::TPoint3D& to)>;

/** Robots out of range, behind another robot's band, or (if `clear` is given) behind an
 *  obstacle between the two cameras are not seen. */
TrueSighting sightingsOf(const std::vector<mrpt::poses::CPose2D>& poses, size_t observer,
                         const OmniCameraOptions& o, const LineOfSight& clear = {});

/** Bearings mode: the sightings with noise, in a random order (the image carries no
 *  identity). */
mrpt::obs::CObservationBearingRange::Ptr senseBearings(
    const std::vector<mrpt::poses::CPose2D>& poses, size_t observer, const OmniCameraOptions& o,
    mrpt::random::CRandomGenerator& rng, const LineOfSight& clear = {});

/** Render mode: one rendering context reused for every robot and instant. */
class OmniRenderer {
 public:
    OmniRenderer(const OmniCameraOptions& o, const sim::WorldOptions& world);
    ~OmniRenderer();
    mrpt::img::CImage render(const std::vector<mrpt::poses::CPose2D>& poses, size_t observer);

 private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace mrloc::omnivision
