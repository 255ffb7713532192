#pragma once
// The robots' own sensor: odometry. It draws from the generator it is given, in a fixed
// order, so that a seed reproduces a rawlog byte for byte. Methods add their sensors as
// payloads (Payload.h).
#include <mrloc/sim/Robot.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/random/RandomGenerators.h>

namespace mrloc::sim {

/** Integrates the true motion increments with multiplicative Gaussian noise. */
class OdometrySensor {
 public:
    explicit OdometrySensor(const RobotOptions& robot);
    void accumulate(const mrpt::poses::CPose2D& trueDelta, mrpt::random::CRandomGenerator& rng);
    mrpt::obs::CObservationOdometry::Ptr read(const std::string& label,
                                              mrpt::Clock::time_point t) const;

 private:
    const RobotOptions& robot_;
    mrpt::poses::CPose2D odometry_;
};

}  // namespace mrloc::sim
