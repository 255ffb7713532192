#pragma once
// How two views compare, or a view and a scan: the tests behind the elimination's verdicts
// (seed 002 steps 7 and 9) and the exact localizer's beams' second chance. Views are
// visibility polygons about their viewpoint (Visibility.h), scans a full turn of beams
// (ScanPolygon.h).
#include <mrloc/polymap/ScanPolygon.h>
#include <mrloc/polymap/Visibility.h>

namespace mrloc::polymap {

/** No wall of V is seen edge-on: its line passing nearer than `clearance` to the viewpoint
 *  beside the wall (not facing it), where a scanner's beams graze it and the sensed V is not
 *  worth comparing. */
bool wellConditioned(const VisibilityPolygon& V, double clearance);

/** How far `range`, seen along `angle`, is from V's boundary: along the beam itself, or,
 *  when that is over `tolerance`, the best of it and half a beam step either side (a beam
 *  next to a window's end sees the wall on its other side). */
double radialMismatch(const RadialProfile& V, double angle, double range, double step,
                      double tolerance);

/** The range error that a share `quantile` of a full-turn scan's beams (ScanPolygon's
 *  beamsOf) stay within against V's boundary, each beam along its direction or half a beam
 *  step either side (a window's end); a beam without return errs only by how far V stops
 *  short of its range. */
double beamMismatch(const ScanBeams& beams, const VisibilityPolygon& V, double quantile);
/** The share of a scan's beams a hypothesis' view must explain (1 %: consistentWithScan's). */
constexpr double kBeamsThatMustAgree = 0.99;

/** Over 2 % of `beams` directions see ranges differing by more than `margin`, ranges beyond
 *  `maxRange` being one (the scanner sees no return there). */
bool beamsTellApart(const VisibilityPolygon& a, const VisibilityPolygon& b, int beams,
                    double margin, double maxRange);

}  // namespace mrloc::polymap
