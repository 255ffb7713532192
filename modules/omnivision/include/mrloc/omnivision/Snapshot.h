#pragma once
// What the robots' omni-directional cameras saw at one instant (seed 000 Fig. 4): per robot,
// the bearings of the images of the other robots in its own frame. Identities are unknown:
// every robot carries the same marker. Robots are numbered 0..N-1 (a robot knows its own
// camera); images are numbered within each view.
#include <mrpt/obs/CObservationBearingRange.h>

#include <string>
#include <vector>

namespace mrloc::omnivision {

/** One camera's images: bearings in the robot frame, radians in [-pi, pi), counter-
 *  clockwise positive, sorted ascending. */
struct View {
    std::vector<double> bearings;
    size_t size() const { return bearings.size(); }
};

struct Snapshot {
    double time = 0;          ///< seconds
    std::vector<View> views;  ///< index = robot
    size_t robots() const { return views.size(); }
};

/** Sorts and wraps raw bearings into a View; throws mrloc::Error on a non-finite value. */
View makeView(std::vector<double> bearings, const std::string& what);

/** The view in a CObservationBearingRange (<robot>.omni_bearings): its yaws. Throws
 *  mrloc::Error naming `what` if a yaw is not finite. */
View viewFromObservation(const mrpt::obs::CObservationBearingRange& obs, const std::string& what);

/** Signed angle from image p to image q, counter-clockwise, in (-pi, pi]. */
double signedAngle(const View& v, int p, int q);
/** The angle between images p and q at the observer, in [0, pi] (seed 000 Fig. 2). */
double interiorAngle(const View& v, int p, int q);

struct ImageAngle {
    int p = 0, q = 0;  ///< images, p < q
    double angle = 0;  ///< interior angle (rad)
};
/** The n(n-1)/2 angles of a view with n images (seed 000 section 2). */
std::vector<ImageAngle> anglesOf(const View& v);

}  // namespace mrloc::omnivision
