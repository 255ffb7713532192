#pragma once
// Ultrasonic sonars in the simulated world (seed 004's sensor). The world's OctoMap is cut at
// the sonar's height into a 2D grid (FloorSlice), and each reading casts a fan of rays over
// the sensor's cone through it. What comes back is the nearest echo:
//   - specular: a flat face (a wall, a box's side) returns an echo only along its normal,
//     so a wall inside the cone gives the perpendicular distance, and a wall seen only
//     obliquely gives nothing;
//   - diffuse: an exposed corner of the grid (a door jamb, a box's edge, the many small
//     steps of a pillar or a person) returns an echo from any direction;
// plus Gaussian range noise; nothing beyond the maximum range (the reading is then 0, as
// MRPT's CObservationRange documents "no echo").
#include <mrloc/sim/World.h>
#include <mrpt/obs/CObservationRange.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/random/RandomGenerators.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace mrloc::framesync {

/** The world's OctoMap at one height: a cell is occupied if its voxel is. */
class FloorSlice {
 public:
    FloorSlice(const sim::World& world, double height);
    double resolution() const { return resolution_; }
    double height() const { return height_; }
    bool occupied(long i, long j) const;

    struct Hit {
        double distance = 0;  ///< m along the ray to the face it entered
        int axis = 0;         ///< the face's normal axis: 0 x, 1 y
        bool corner = false;  ///< the cell is an exposed corner (diffuse reflector)
    };
    /** The first occupied cell along the ray (Amanatides-Woo traversal), if within reach. */
    std::optional<Hit> cast(double x, double y, double direction, double reach) const;

 private:
    double resolution_, height_;
    long i0_, j0_, nx_, ny_;  ///< the grid's first cell and size
    std::vector<uint8_t> cells_;
};

struct SonarMount {
    std::string name;
    mrpt::poses::CPose3D pose;  ///< on the robot: x y z and the axis's yaw
};

struct SonarRigOptions {
    std::vector<SonarMount> mounts;
    double aperture = 25 * M_PI / 180;  ///< rad, the cone's full width
    double minRange = 0.05;             ///< m
    double maxRange = 4.0;              ///< m
    double sigma = 0.01;                ///< m, range noise
    double rate = 10;                   ///< Hz, every sonar of the rig
    double fanStep = 0.5 * M_PI / 180;  ///< rad between the rays cast over the cone
};

/** The nearest echo (m, before noise) of a sonar at `sensor` (world frame), if any within
 *  the maximum range. */
std::optional<double> nearestEcho(const FloorSlice& slice, const mrpt::poses::CPose2D& sensor,
                                  const SonarRigOptions& rig);

/** One reading of the whole rig from the robot at `robot` (world frame): a
 *  CObservationRange with one entry per mount (its id, its pose, the range). Draws one
 *  normal per mount from rng, in mount order. */
mrpt::obs::CObservationRange::Ptr readSonars(const std::vector<const FloorSlice*>& slices,
                                             const mrpt::poses::CPose2D& robot,
                                             const SonarRigOptions& rig,
                                             mrpt::random::CRandomGenerator& rng);

}  // namespace mrloc::framesync
