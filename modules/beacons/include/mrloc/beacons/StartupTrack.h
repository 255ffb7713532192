#pragma once
// The beacon tracker's start-up without a start pose: robust multilateration fixes with the
// odometry at their time, until they fit the odometry's path moved rigidly into the world.
// A fix may be wrong (two late echoes that agree with each other make a consistent mirror of
// the truth), so the motion is found by consensus: every pair of fixes far enough apart
// proposes one, the one most fixes fit wins, and Umeyama (no scale) on those fixes refines
// it. doc/beacons.md, "Tracking filter".
#include <mrpt/poses/CPose2D.h>

#include <Eigen/Core>
#include <deque>
#include <optional>

namespace mrloc::beacons {

class StartupTrack {
 public:
    struct Point {
        Eigen::Vector2d fix;            ///< world, m
        mrpt::poses::CPose2D odometry;  ///< the odometry reading at the fix's time
        double tolerance;               ///< m: how far the aligned odometry may be from the fix
    };
    static constexpr size_t kMaxPoints = 15;   ///< the oldest go first
    static constexpr size_t kMinAgreeing = 4;  ///< fixes that must agree before a start

    void clear() { points_.clear(); }
    void add(const Point& p);
    size_t size() const { return points_.size(); }

    /** The rigid motion from the odometry frame to the world (3x3, homogeneous) that most
     *  fixes fit, once at least kMinAgreeing of them, a majority, agree and span `baseline`
     *  metres of the odometry's path; only those fixes are kept. Nothing otherwise. */
    std::optional<Eigen::Matrix3d> align(double baseline);

    /** The newest fix agrees with every earlier one on how far apart they are (the
     *  odometry's distance, which needs no heading), and there is an earlier one. */
    bool newestAgrees() const;

    /** Sum of the squared distances of the fixes' odometry positions from their centroid
     *  (m^2): how well a line through them fixes a rotation. */
    double odometrySpread() const;

 private:
    std::deque<Point> points_;
};

}  // namespace mrloc::beacons
