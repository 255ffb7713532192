#include <mrloc/sim/Sensors.h>

#include <cmath>

namespace mrloc::sim {

OdometrySensor::OdometrySensor(const RobotOptions& robot, mrpt::random::CRandomGenerator& rng,
                               double errorScale)
    : robot_(robot),
      odometry_(robot.start),
      scaleError_(robot.odometryScaleError * errorScale),
      headingDrift_(robot.odometryHeadingDrift * errorScale) {
    // scaled before the draw, as framesync's drift sweep scales the robots' keys: a scale
    // of d gives the same odometry as every key multiplied by d
    if (robot.odometryScaleErrorSigma * errorScale > 0)
        scaleError_ += rng.drawGaussian1D(0, robot.odometryScaleErrorSigma * errorScale);
    if (robot.odometryHeadingDriftSigma * errorScale > 0)
        headingDrift_ += rng.drawGaussian1D(0, robot.odometryHeadingDriftSigma * errorScale);
}

void OdometrySensor::accumulate(const mrpt::poses::CPose2D& d,
                                mrpt::random::CRandomGenerator& rng) {
    const double dist = std::hypot(d.x(), d.y());
    const double sxy = robot_.odometrySigmaXY * dist;
    const double sphi =
        robot_.odometrySigmaPhi * std::abs(d.phi()) + robot_.odometrySigmaPhiPerMetre * dist;
    const double ex = rng.drawGaussian1D(0, sxy), ey = rng.drawGaussian1D(0, sxy);
    const double ephi = rng.drawGaussian1D(0, sphi);
    const double scale = 1 + scaleError_;
    odometry_ = odometry_ + mrpt::poses::CPose2D(scale * d.x() + ex, scale * d.y() + ey,
                                                 d.phi() + headingDrift_ * dist + ephi);
}

mrpt::obs::CObservationOdometry::Ptr OdometrySensor::read(const std::string& label,
                                                          mrpt::Clock::time_point t) const {
    auto o = mrpt::obs::CObservationOdometry::Create();
    o->sensorLabel = label;
    o->timestamp = t;
    o->odometry = odometry_;
    return o;
}

}  // namespace mrloc::sim
