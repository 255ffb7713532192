#pragma once
// A 360-degree range scanner in a floor plan (a polygon map): each beam is a ray cast
// against the polygon's edges, with Gaussian range noise. This is what the polygon-map
// method senses its visibility polygon with. The same scanner in the world's OctoMap: what
// the formation robots find obstacles with.
#include <mrloc/common/Polygon.h>
#include <mrloc/sim/World.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/random/RandomGenerators.h>

namespace mrloc::sim {

struct ScannerOptions {
    int rays = 1440;            ///< beams over the full turn, evenly spaced
    double rangeSigma = 0.005;  ///< Gaussian range noise (m)
    double maxRange = 100;      ///< no return beyond (m)
    double rate = 0;            ///< Hz; 0: one scan, at the start
};

/** A floor plan: the walls a scanner sees. */
struct FloorPlan {
    common::Polygon polygon;
    ScannerOptions scanner;
};

/** One scan from `pose` (the sensor at the robot's origin, beams in the robot frame).
 *  MRPT spaces beams by aperture / (N - 1); the aperture is 2 pi (N - 1) / N so that the N
 *  beams are 2 pi / N apart with none repeated. Draws N normals from rng. */
mrpt::obs::CObservation2DRangeScan::Ptr scanFloorPlan(const common::Polygon& plan,
                                                      const mrpt::poses::CPose2D& pose,
                                                      const ScannerOptions& options,
                                                      mrpt::random::CRandomGenerator& rng);

/** One horizontal scan in the world's OctoMap from `pose` at `height` above the floor, the
 *  same beams and noise; a beam's range is the distance to the first occupied voxel's
 *  centre. Draws N normals from rng. */
mrpt::obs::CObservation2DRangeScan::Ptr scanWorld(const World& world,
                                                  const mrpt::poses::CPose2D& pose, double height,
                                                  const ScannerOptions& options,
                                                  mrpt::random::CRandomGenerator& rng);

}  // namespace mrloc::sim
