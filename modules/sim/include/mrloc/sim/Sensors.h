#pragma once
// The robots' own sensor: odometry. It draws from the generator it is given, in a fixed
// order, so that a seed reproduces a rawlog byte for byte. Methods add their sensors as
// payloads (Payload.h).
#include <mrloc/sim/Robot.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/random/RandomGenerators.h>

namespace mrloc::sim {

/** Integrates the true motion increments with multiplicative Gaussian noise and the
 *  robot's systematic errors (a wheel radius error scaling distances, a heading drift per
 *  metre). */
class OdometrySensor {
 public:
    /** Draws the systematic errors from rng, in that order, only for a positive sigma.
     *  `errorScale` multiplies the robot's four systematic error keys ([scenario]
     *  odometry_error_scale: one key sweeps a team's odometry quality). */
    OdometrySensor(const RobotOptions& robot, mrpt::random::CRandomGenerator& rng,
                   double errorScale = 1);
    double scaleError() const { return scaleError_; }
    double headingDrift() const { return headingDrift_; }  ///< rad/m
    void accumulate(const mrpt::poses::CPose2D& trueDelta, mrpt::random::CRandomGenerator& rng);
    mrpt::obs::CObservationOdometry::Ptr read(const std::string& label,
                                              mrpt::Clock::time_point t) const;

 private:
    const RobotOptions& robot_;
    mrpt::poses::CPose2D odometry_;
    double scaleError_ = 0, headingDrift_ = 0;
};

}  // namespace mrloc::sim
