#pragma once
// Sensor models of the simulator. Each draws from the generator it is given, in a fixed
// order, so that a seed reproduces a rawlog byte for byte.
#include <mrloc/sim/Robot.h>
#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/random/RandomGenerators.h>

namespace mrloc::sim {

/** Section [sensors]: TOF noise and failures on top of the ultrasonic link. */
struct SensorOptions : public mrpt::config::CLoadableOptions {
    double rangeSigma = 0.01;          ///< Gaussian TOF range noise (m)
    double rangeMax = 10;              ///< no reading beyond (m)
    double dropout = 0.02;             ///< probability a line-of-sight range is missed
    double outlierProbability = 0.01;  ///< probability a range reads long (late trigger)
    double outlierMax = 1.0;           ///< such a range is long by U(0.1, outlierMax) m
    bool nlosReflect = true;           ///< blocked path: a long reflected range (else none)

    void loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                            const std::string& section) override;
    void saveToConfigFile(mrpt::config::CConfigFileBase& target,
                          const std::string& section) const override;
};

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
