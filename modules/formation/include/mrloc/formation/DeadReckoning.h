#pragma once
// The dead-reckoning baseline of seed 003 (sec. 4.2 and 5): a robot that integrates the
// speed of a wheel speed sensor along the heading of a low-cost heading sensor.
#include <mrpt/math/TPoint2D.h>
#include <mrpt/random/RandomGenerators.h>

#include <cmath>
#include <vector>

namespace mrloc::formation {

using mrpt::math::TPoint2D;

/** The dead-reckoning baseline (seed 003 sec. 4.2): heading from a sensor whose error is a
 *  Gauss-Markov process (correlation time, deviation; zero at the start, where the heading
 *  is aligned) plus white noise; speed from a wheel speed sensor (seed 003 eq. 3):
 *  v = (R + dR)(1 + s) w + n. */
struct DeadReckoningOptions {
    /** What the Gauss-Markov process is the error of (doc/formation.md):
     *  - Gyro: the gyro's rate, whose integral is the heading (seed 003 sec. 5: "errors in
     *    the heading angle accumulate because sensor noise is also integrated"); its
     *    deviation is headingSigma / headingTau, so that the heading error reaches
     *    headingSigma in one correlation time (75 deg/h: a low-cost MEMS gyro), and the rate
     *    error starts at zero (the bias is measured standing still). The default: the error
     *    grows with time, as the paper finds (1.64 times for twice the time).
     *  - Heading: the heading itself (seed 003 sec. 4.2 read literally), zero at the start;
     *    a bounded error, which averages out over long routes. */
    enum class HeadingModel { Gyro, Heading } headingModel = HeadingModel::Gyro;
    double headingTau = 120;                 ///< s
    double headingSigma = 2.5 * M_PI / 180;  ///< rad, the process's deviation
    double headingWhite = 0.8 * M_PI / 180;  ///< rad
    double radiusBias = 0;                   ///< m (seed 003: negligible, rigid wheels)
    double scaleFactor = 0.01;               ///< (the paper's value was lost)
    double speedNoise = 0.045;               ///< m/s
    double dt = 0.1;                         ///< s, the sensors' period
};

struct ErrorSample {
    double time = 0;   ///< s
    double error = 0;  ///< m
};

/** A robot driving `route` at wheelRadius x wheelSpeed, its position dead-reckoned; the
 *  error every dt (the last sample: at the destination). */
/** The dead-reckoning robot's sensors and its estimate, one period at a time: what the
 *  simulator's dead-reckoning robot carries, and what deadReckon runs. */
class DeadReckoner {
 public:
    /** Throws mrloc::Error for a non-positive period, correlation time or wheel radius. */
    DeadReckoner(const DeadReckoningOptions& options, double wheelRadius, const TPoint2D& start);
    /** One period: the robot's true heading at its end (rad) and the distance it truly
     *  drove (m). Reads the heading and wheel speed sensors, then advances the estimate. */
    void update(double trueHeading, double distance, mrpt::random::CRandomGenerator& rng);
    /** The estimate from readings alone: x += v dt cos(heading), y += v dt sin(heading). */
    static TPoint2D advance(const TPoint2D& from, double sensedHeading, double sensedSpeed,
                            double dt);
    const TPoint2D& estimate() const { return estimate_; }
    double sensedHeading() const { return sensedHeading_; }  ///< rad, the last reading
    double sensedSpeed() const { return sensedSpeed_; }      ///< m/s, the last reading

 private:
    DeadReckoningOptions o_;
    double wheelRadius_;
    bool gyro_;
    double phi_, drive_;  ///< the Gauss-Markov recursion's factor and driving deviation
    double gm_ = 0, headingError_ = 0;
    TPoint2D estimate_;
    double sensedHeading_ = 0, sensedSpeed_ = 0;
};

std::vector<ErrorSample> deadReckon(const std::vector<TPoint2D>& route, double wheelRadius,
                                    double wheelSpeed, const DeadReckoningOptions& options,
                                    mrpt::random::CRandomGenerator& rng);

}  // namespace mrloc::formation
