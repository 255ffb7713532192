#pragma once
// Seed 003's camera path, first half: each robot carries an AprilTag (family 36h11) on each
// of its four sides; a camera renders the scene off screen (sim::PinholeCamera) and the
// AprilTag 3 library finds the tags and their centres (OpenCV's ArUco for comparison).
// Algorithm 1 then works on the centres' lateral pixel distances.
#include <mrpt/img/CImage.h>
#include <mrpt/img/TCamera.h>
#include <mrpt/math/TPoint2D.h>
#include <mrpt/math/TPoint3D.h>
#include <mrpt/opengl/COpenGLScene.h>
#include <mrpt/opengl/CSetOfObjects.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/poses/CPose3D.h>

#include <array>
#include <optional>
#include <vector>

namespace mrloc::formation {

struct MarkerOptions {
    double bodySize = 0.20;    ///< m, between opposite tags (the body is 4 cm narrower)
    double bodyHeight = 0.25;  ///< m
    double tagSize = 0.16;     ///< m, the tag's black square (its white margin is drawn around it)
    double tagHeight = 0.13;   ///< m, the tag's centre above the floor
};

/** Sides of a robot, counter-clockwise from its front. */
enum class Side { Front = 0, Left = 1, Back = 2, Right = 3 };

/** The tag id of robot r's side: 4 r + side (36h11 has 587 ids: up to 146 robots). */
int markerId(size_t robot, Side side);

/** The centre of a side's tag in the world (m). */
mrpt::math::TPoint3D markerCentre(const mrpt::poses::CPose2D& robot, Side side,
                                  const MarkerOptions& options);

/** Robot r as the cameras see it, about its own centre (facing +X): its body and its four
 *  tags, each facing outwards; place it with setPose. */
mrpt::opengl::CSetOfObjects::Ptr robotObjects(size_t robot, const MarkerOptions& options);

/** Adds robot r at `pose` to the scene (robotObjects, placed). */
void addRobot(mrpt::opengl::COpenGLScene& scene, const mrpt::poses::CPose2D& pose, size_t robot,
              const MarkerOptions& options);

/** A tag found in a picture: its id, its centre (the crossing of its diagonals) and its
 *  size (the square root of its area), in pixels. */
struct MarkerSighting {
    int id = -1;
    double u = 0, v = 0;
    double size = 0;
    /** The mean of its two most vertical edges' heights (px): f tagSize / depth for an
     *  upright tag, whatever the angle it is seen at (a turn foreshortens its width, not its
     *  height). */
    double height = 0;
    /** Its corners (px), in the detector's order. */
    std::array<mrpt::math::TPoint2D, 4> corners{};
};

/** A sighting from its corners alone: the centre where the diagonals cross (perspective keeps
 *  straight lines straight), the size and the height as the detectors give them. */
MarkerSighting sightingFromCorners(int id, const std::array<mrpt::math::TPoint2D, 4>& corners);

/** `decimate`: the detector's quad decimation (2: its quads found on a half-size picture,
 *  faster; 1: small tags too, such as a far robot seen edge-on).
 *  The AprilTag 36h11 tags in a picture, ordered by id, by the AprilTag 3 library (the
 *  centre: the tag's homography at its origin). It measured better than ArUco on our frames:
 *  5x smaller centre errors, more tags found, faster (doc/formation.md). */
std::vector<MarkerSighting> detectMarkers(const mrpt::img::CImage& picture, float decimate = 2);
/** The same by OpenCV's ArUco module (DICT_APRILTAG_36h11; the centre: the crossing of the
 *  diagonals), kept to measure the two against each other. */
std::vector<MarkerSighting> detectMarkersArUco(const mrpt::img::CImage& picture);

/** The mean height (px) of the two edges of a quad (corners in order) that rise most. */
double verticalEdgeHeight(const std::array<mrpt::math::TPoint2D, 4>& corners);

/** Where a world point falls in a picture from a camera at `cameraPose`
 *  (sim::cameraPoseLooking) with intrinsics k (no distortion); nothing if behind it or
 *  outside the picture. */
std::optional<MarkerSighting> project(const mrpt::img::TCamera& k,
                                      const mrpt::poses::CPose3D& cameraPose,
                                      const mrpt::math::TPoint3D& point);

}  // namespace mrloc::formation
