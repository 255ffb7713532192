#pragma once
// The panoramic strip an omni-directional camera gives (seed 000 Fig. 3-4), made of
// `views` pinhole views with a horizontal field of view of 360/views degrees each, stitched
// left to right with the azimuth decreasing: view k looks at azimuth -k * 360/views, so
// column 0 is at +180/views degrees and the strip wraps around. Shared by the simulator,
// which renders the views, and the detector, which turns columns back into bearings.
#include <cmath>

namespace mrloc::omnivision {

struct Panorama {
    int views = 4;
    int viewWidth = 512;  ///< px per view
    int height = 64;      ///< px

    int width() const { return views * viewWidth; }
    double viewFov() const { return 2 * M_PI / views; }
    /** Focal length in pixels (square pixels). */
    double focal() const { return 0.5 * viewWidth / std::tan(0.5 * viewFov()); }
    /** Azimuth of view k's optical axis in the robot frame (rad). */
    double viewAzimuth(int k) const { return -k * viewFov(); }
    /** Angle (rad) of a bearing off the axis of the view it falls in. */
    double offAxis(double bearing) const { return std::remainder(bearing, viewFov()); }
    /** Azimuth (rad) one column spans at a bearing: a pinhole view's columns are even in
     *  the image, not in azimuth (cos^2 of the angle off the axis, over the focal). */
    double columnAngleAt(double bearing) const {
        return std::pow(std::cos(offAxis(bearing)), 2) / focal();
    }
    /** Bearing (robot frame, rad) of the centre of pixel column u (may be fractional). */
    double bearingOfColumn(double u) const {
        const int k = std::min(views - 1, std::max(0, int(std::floor(u / viewWidth))));
        const double x = u - k * viewWidth + 0.5 - 0.5 * viewWidth;  // from the view centre
        return viewAzimuth(k) - std::atan2(x, focal());
    }
};

}  // namespace mrloc::omnivision
