// Pan-tilt kinematics of seed 001 eq. (1)-(3) against hand-computed angles.
#include <gtest/gtest.h>
#include <mrloc/beacons/PanTilt.h>
#include <mrpt/core/bits_math.h>

#include <cmath>

using namespace mrloc::beacons;
using mrpt::DEG2RAD;
using mrpt::math::TPoint3D;

TEST(PanTilt, FrameIsRotated180AboutX) {
    // eq. (2): ^B R_p = (x_p - x_Ob, -(y_p - y_Ob), -(z_p - z_Ob)).
    const PanTiltHead head({1.5, 1.5, 2.5});
    const TPoint3D p = head.inFrame({0.5, 2.5, 0.5});
    EXPECT_NEAR(p.x, -1.0, 1e-12);
    EXPECT_NEAR(p.y, -1.0, 1e-12);
    EXPECT_NEAR(p.z, 2.0, 1e-12);
}

TEST(PanTilt, Eq3AgainstHandComputedAngles) {
    // Head on the ceiling at the room centre; seed 001 Table 2 points at 500 mm height.
    const PanTiltHead head({1.5, 1.5, 2.5});
    struct Case {
        TPoint3D target;
        double panDeg, tiltDeg;
    };
    // In B: dx = x - 1.5, dy = -(y - 1.5), dz = 2. theta1 = atan2(dy, dx),
    // theta2 = atan2(sqrt(dx^2 + dy^2), dz) = atan(sqrt(2) / 2) = 35.2644 deg at the corners.
    const double t = mrpt::RAD2DEG(std::atan(std::sqrt(2.0) / 2.0));
    for (const Case& c : {Case{{0.5, 2.5, 0.5}, -135, t}, Case{{0.5, 0.5, 0.5}, 135, t},
                          Case{{2.5, 0.5, 0.5}, 45, t}, Case{{2.5, 2.5, 0.5}, -45, t},
                          Case{{1.5, 1.5, 0.5}, 0, 0}, Case{{3.5, 1.5, 0.5}, 0, 45}}) {
        const auto a = head.aimAt(c.target);
        EXPECT_NEAR(mrpt::RAD2DEG(a.pan), c.panDeg, 1e-9) << c.target.asString();
        EXPECT_NEAR(mrpt::RAD2DEG(a.tilt), c.tiltDeg, 1e-9) << c.target.asString();
        // Forward kinematics points the beam exactly at the target.
        EXPECT_NEAR(head.offAxisAngle(a, c.target), 0.0, 1e-7) << c.target.asString();
    }
    // The corner's tilt from the code itself, against the number: atan(sqrt(2) / 2).
    EXPECT_NEAR(head.aimAt({2.5, 2.5, 0.5}).tilt, DEG2RAD(35.26438968), 1e-9);
}

TEST(PanTilt, OffAxisAngleOfAFixedHead) {
    // Aimed at the centre point 5 of Table 2, the beam misses corner point 4 by the angle
    // between the two lines of sight.
    const PanTiltHead head({0.0, 0.0, 2.5});
    const auto a = head.aimAt({1.5, 1.5, 0.5});
    const TPoint3D u(1.5, 1.5, -2.0), v(2.5, 2.5, -2.0);
    const double expected =
        std::acos((u.x * v.x + u.y * v.y + u.z * v.z) / std::sqrt(u.sqrNorm() * v.sqrNorm()));
    EXPECT_NEAR(head.offAxisAngle(a, {2.5, 2.5, 0.5}), expected, 1e-9);
}

TEST(PanTilt, JointLimitsAndSlew) {
    PanTiltLimits lim;
    lim.tiltMax = DEG2RAD(60);
    lim.slewRate = DEG2RAD(90);
    const PanTiltHead head({0, 0, 2.5}, lim);
    // A target almost level with the head would need a tilt near 90 degrees: clamped.
    EXPECT_NEAR(head.aimAt({10, 0, 2.4}).tilt, DEG2RAD(60), 1e-12);
    // Slew: 0.5 s at 90 deg/s moves each joint 45 degrees towards its goal.
    const PanTiltAngles from{0, 0}, to{DEG2RAD(120), DEG2RAD(30)};
    const auto mid = head.slew(from, to, 0.5);
    EXPECT_NEAR(mid.pan, DEG2RAD(45), 1e-12);
    EXPECT_NEAR(mid.tilt, DEG2RAD(30), 1e-12);
    EXPECT_NEAR(head.slewTime(from, to), 120.0 / 90.0, 1e-12);
    // A continuous pan goes the short way round across +-180 degrees ...
    const PanTiltAngles a{DEG2RAD(170), 0}, b{DEG2RAD(-170), 0};
    EXPECT_NEAR(head.slewTime(a, b), 20.0 / 90.0, 1e-12);
    EXPECT_NEAR(head.slew(a, b, 1.0).pan, DEG2RAD(-170), 1e-12);
    // ... a pan limited to +-175 degrees cannot cross its ends and goes the long way.
    PanTiltLimits narrow = lim;
    narrow.panMin = DEG2RAD(-175), narrow.panMax = DEG2RAD(175);
    const PanTiltHead limited({0, 0, 2.5}, narrow);
    EXPECT_NEAR(limited.slewTime(a, b), 340.0 / 90.0, 1e-12);
    // Straight below the head, the pan stays where it is.
    EXPECT_NEAR(head.aimAt({0, 0, 0.5}, 1.25).pan, 1.25, 1e-12);
}
