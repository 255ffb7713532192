#include <mrloc/beacons/PanTilt.h>
#include <mrpt/math/wrap2pi.h>

#include <algorithm>
#include <cmath>

namespace mrloc::beacons {

using mrpt::math::TPoint3D;

PanTiltHead::PanTiltHead(const TPoint3D& position, PanTiltLimits limits)
    : frame_(position.x, position.y, position.z, /*yaw=*/0, /*pitch=*/0, /*roll=*/M_PI),
      limits_(limits) {}

TPoint3D PanTiltHead::inFrame(const TPoint3D& target) const {
    // Seed 001 eq. (2) prints (x_p - x_Ob, -y_p - y_Ob, -z_p - z_Ob); the rotation about X
    // gives (x_p - x_Ob, -(y_p - y_Ob), -(z_p - z_Ob)), which is what is computed here (the
    // printed form holds if O_b's y and z are read in B's axes). See doc/beacons.md.
    return frame_.inverseComposePoint(target);
}

PanTiltAngles PanTiltHead::aimAt(const TPoint3D& target, double currentPan) const {
    const TPoint3D p = inFrame(target);
    PanTiltAngles a;
    // seed 001 eq. (3), theta1; straight below the head any pan aims right: keep the current.
    a.pan = std::hypot(p.x, p.y) < 1e-9 * (1.0 + std::abs(p.z)) ? currentPan : std::atan2(p.y, p.x);
    a.tilt = std::atan2(std::hypot(p.x, p.y), p.z);  // seed 001 eq. (3), theta2
    a.pan = std::clamp(a.pan, limits_.panMin, limits_.panMax);
    a.tilt = std::clamp(a.tilt, limits_.tiltMin, limits_.tiltMax);
    return a;
}

TPoint3D PanTiltHead::beamDirection(const PanTiltAngles& a) const {
    const TPoint3D inB(std::sin(a.tilt) * std::cos(a.pan), std::sin(a.tilt) * std::sin(a.pan),
                       std::cos(a.tilt));
    const mrpt::math::TVector3D w = frame_.rotateVector(mrpt::math::TVector3D(inB.x, inB.y, inB.z));
    return {w.x, w.y, w.z};
}

double PanTiltHead::offAxisAngle(const PanTiltAngles& a, const TPoint3D& target) const {
    const TPoint3D beam = beamDirection(a);
    const TPoint3D d = target - TPoint3D(frame_.x(), frame_.y(), frame_.z());
    const double n = std::sqrt(d.sqrNorm());
    if (n < 1e-12) return 0;
    const double c = (beam.x * d.x + beam.y * d.y + beam.z * d.z) / n;
    return std::acos(std::clamp(c, -1.0, 1.0));
}

namespace {
/** Pan difference to travel: a pan range of a full turn or more rotates continuously (the
 *  shorter way round); a narrower one cannot cross its ends (cables), so it goes straight. */
double panDelta(double from, double to, const PanTiltLimits& l) {
    const bool continuous = l.panMax - l.panMin >= 2 * M_PI - 1e-9;
    return continuous ? mrpt::math::wrapToPi(to - from) : to - from;
}
double step(double delta, double maxStep) { return std::clamp(delta, -maxStep, maxStep); }
}  // namespace

PanTiltAngles PanTiltHead::slew(const PanTiltAngles& from, const PanTiltAngles& to,
                                double dt) const {
    const double maxStep = limits_.slewRate * dt;
    PanTiltAngles out;
    out.pan = mrpt::math::wrapToPi(from.pan + step(panDelta(from.pan, to.pan, limits_), maxStep));
    out.tilt = from.tilt + step(to.tilt - from.tilt, maxStep);
    return out;
}

double PanTiltHead::slewTime(const PanTiltAngles& from, const PanTiltAngles& to) const {
    const double d =
        std::max(std::abs(panDelta(from.pan, to.pan, limits_)), std::abs(to.tilt - from.tilt));
    return d / limits_.slewRate;
}

}  // namespace mrloc::beacons
