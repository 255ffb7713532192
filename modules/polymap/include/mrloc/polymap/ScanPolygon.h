#pragma once
// The sensed visibility polygon: a 360-degree CObservation2DRangeScan turned into a polygon
// in the robot's frame (axes along the map's: the robot knows its heading).
//
// Depth jumps between neighbouring beams (Borges-Aldon adaptive breakpoints) are windows;
// each run of beams between jumps is split into straight walls (iterative end-point fit),
// each wall is fitted by total least squares, and neighbouring walls meet at their lines'
// intersection. A window lies on the ray halfway between the two beams of its jump, so it
// is exactly radial, as in an exact visibility polygon.
#include <mrloc/polymap/Visibility.h>
#include <mrpt/obs/CObservation2DRangeScan.h>

namespace mrloc::polymap {

struct ScanPolygonOptions {
    double rangeSigma = 0.005;            ///< range noise (m): sets the split distance
    double breakAngle = 10 * M_PI / 180;  ///< wall incidence below which beams are a jump (rad)
    double mergeAngle = 2 * M_PI / 180;   ///< neighbouring walls closer in direction are one
};

/** A full turn's beams in the map's axes: direction (rad) and range (m) of each, and the
 *  angle between neighbours. */
struct ScanBeams {
    std::vector<double> angle, range;
    std::vector<bool> noReturn;  ///< no wall within the scanner's max range (range = max range)
    double step = 0;
};

/** Throws mrloc::Error naming the scan if it is not a full turn of at least 8 beams or a
 *  beam has no finite range, or, unless `noReturnAllowed`, a beam has no return (V must be
 *  closed: set the scanner's max range above the map's size). */
ScanBeams beamsOf(const mrpt::obs::CObservation2DRangeScan& scan, double heading,
                  bool noReturnAllowed = false);

/** Throws mrloc::Error naming the scan if a beam has no return (V must be closed: set the
 *  scanner's max range above the map's size) or the scan is not a full turn. */
VisibilityPolygon visibilityFromScan(const mrpt::obs::CObservation2DRangeScan& scan, double heading,
                                     const ScanPolygonOptions& options);

}  // namespace mrloc::polymap
