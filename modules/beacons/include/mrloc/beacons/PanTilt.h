#pragma once
// Kinematics of a pan-tilt head carrying an ultrasonic transmitter (seed 001 section 3).
//
// The head's frame B sits at the beacon position O_b, rotated 180 degrees about the world's
// X axis (seed 001 Fig. 5), so that B's z axis points down into the room. Pan theta1 turns
// about B's z axis, measured from B's x axis; tilt theta2 is the beam's angle from B's z axis.
// Shared by the simulator (the beam direction of a head) and the beacons method (aiming).
#include <mrpt/math/TPoint3D.h>
#include <mrpt/poses/CPose3D.h>

namespace mrloc::beacons {

struct PanTiltAngles {
    double pan = 0;   ///< theta1, rad
    double tilt = 0;  ///< theta2, rad, 0 = straight down
};

struct PanTiltLimits {
    double panMin = -M_PI, panMax = M_PI;    ///< rad; a full turn or more: continuous rotation
    double tiltMin = 0, tiltMax = M_PI / 2;  ///< rad
    double slewRate = 2 * M_PI;              ///< rad/s, each joint (INI slew_rate, 360 deg/s)
};

class PanTiltHead {
 public:
    PanTiltHead(const mrpt::math::TPoint3D& position, PanTiltLimits limits = {});

    /** Frame B: translation O_b, rotation 180 degrees about X (seed 001 eq. 1). */
    const mrpt::poses::CPose3D& frame() const { return frame_; }
    const PanTiltLimits& limits() const { return limits_; }
    /** The head's position O_b (the transmitter). */
    mrpt::math::TPoint3D base() const { return {frame_.x(), frame_.y(), frame_.z()}; }

    /** The target in frame B, seed 001 eq. (1)-(2): ^B R_p = (^A T_B)^-1 ^A R_p. */
    mrpt::math::TPoint3D inFrame(const mrpt::math::TPoint3D& target) const;
    /** Joint angles that aim the beam at the target, seed 001 eq. (3), clamped to the
     *  joint limits. Straight below the head the pan is free: `currentPan` is kept. */
    PanTiltAngles aimAt(const mrpt::math::TPoint3D& target, double currentPan = 0) const;
    /** Unit beam direction in the world for the given joint angles (forward kinematics). */
    mrpt::math::TPoint3D beamDirection(const PanTiltAngles& a) const;
    /** Angle between the beam and the line from the head to the target (rad). */
    double offAxisAngle(const PanTiltAngles& a, const mrpt::math::TPoint3D& target) const;
    /** Joint angles after moving from `from` towards `to` for dt seconds at the slew rate
     *  (pan takes the shorter way round when the limits allow it). */
    PanTiltAngles slew(const PanTiltAngles& from, const PanTiltAngles& to, double dt) const;
    /** Time to move from `from` to `to` at the slew rate (the slower joint decides). */
    double slewTime(const PanTiltAngles& from, const PanTiltAngles& to) const;

 private:
    mrpt::poses::CPose3D frame_;
    PanTiltLimits limits_;
};

}  // namespace mrloc::beacons
