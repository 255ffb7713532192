#pragma once
// Start-up of the beacon tracker from whatever the log gives: a particle filter over the
// planar pose (x, y, phi) fed with every single range and bearing to a known beacon or
// landmark and moved by the odometry (or a random walk without it), until its particles
// gather into one pose. The tracker's EKF then starts from their mean and covariance.
//
// Why particles: one range at a time (a radio beacon ranged in turn, a camera seeing one
// landmark) never makes a multilateration fix, and the pose that explains a sequence of
// single ranges along the odometry's path is multimodal until the path has turned and the
// ranges separate the hypotheses. doc/beacons.md, "Start-up from one range at a time":
//  - seeding (sensor resetting, Lenser and Veloso 2000): the first measurement draws every
//    particle on its annulus (range) or ray (bearing), heading uniform; each later one
//    replaces a share of them on its own annulus, so a start from a gross outlier, or a
//    start far off after a lost track, recovers;
//  - weights: a mixture of the sensor's Gaussian (widened by the particles' spacing) and a
//    uniform density over the ranges the map allows, so 40-50 % gross errors weigh little;
//  - converged: after enough measurements, one mode holds 90 % of the weight and its position
//    sd (the larger axis) is below kConvergedSd (and its heading's circular sd below
//    kConvergedPhiSd when odometry gives a heading): tight enough for the EKF's linearisation;
//    the EKF starts at the mode's mean with twice its sd.
//  - the odometry between two sightings moves the particles once, composed (the noise of
//    the composed increment): the particles cost nothing while no sighting comes.
#include <mrloc/beacons/BeaconMap.h>
#include <mrloc/beacons/OdometryNoise.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/random/RandomGenerators.h>

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace mrloc::beacons {

struct ParticleStartOptions {
    double rangeSigma = 0.03;      ///< m, the sensor's
    double bearingSigma = 0.02;    ///< rad, the sensor's
    double randomWalkSigma = 0.5;  ///< m/sqrt(s) without odometry
    uint64_t seed = 1;             ///< the particles' random stream (same log, same start)
};

class ParticleStart {
 public:
    static constexpr size_t kParticles = 6000;
    /** Share of gross errors the likelihood allows for (the uniform part of the mixture). */
    static constexpr double kOutlierShare = 0.5;
    /** Share of particles each measurement redraws from its own annulus or ray. */
    static constexpr double kResetShare = 0.02;
    /** Extra spread of the likelihood and of each step: the particles' spacing (m, rad). */
    static constexpr double kRougheningXY = 0.05, kRougheningPhi = 0.01;
    static constexpr double kConvergedSd = 0.3;     ///< m, or 3 range sigmas if larger
    static constexpr double kConvergedPhiSd = 0.1;  ///< rad
    static constexpr size_t kMinMeasurements = 10;
    /** The mode: particles within this of its centre (m, or 10 range sigmas if larger)
     *  must hold this share of the weight. */
    static constexpr double kModeRadius = 1.0, kModeShare = 0.9;
    /** The EKF starts with this times the mode's sd (see converged). */
    static constexpr double kStartInflation = 2.0;

    /** `noise`: the tracker's odometry noise, for each increment. */
    ParticleStart(const BeaconMap& map, ParticleStartOptions options, OdometryNoise noise);

    /** The robot moved by `delta` (its own frame), from its odometry. */
    void onOdometry(const mrpt::poses::CPose2D& delta);
    /** Time passes without odometry: a random walk of randomWalkSigma. */
    void onTime(double dt);
    /** One sighting of a known beacon or landmark: a range, a bearing, or both. */
    struct Sighting {
        Eigen::Vector3d beacon;         ///< its position in the map
        Eigen::Vector3d sensorOnRobot;  ///< x, y, z of the sensor on the robot
        double sensorYaw = 0;           ///< rad, the sensor's heading on the robot
        std::optional<double> range;    ///< m, sensor to beacon (3-D)
        std::optional<double> bearing;  ///< rad, in the sensor's frame
        double rangeSigma = 0.03, bearingSigma = 0.02;
        int beaconId = -1;  ///< the map's id (the tracker's per-beacon offset)
    };
    void onSighting(const Sighting& s);
    /** The span a gross range error is spread over: twice the map's extent plus 20 m. */
    static double rangeSpanOf(const BeaconMap& map);

    /** Draws the particles about a pose (a lost track's last estimate), instead of from the
     *  next measurement. */
    void seedAround(const mrpt::poses::CPose2D& mean, double sigmaXY, double sigmaPhi);
    void clear();

    struct Start {
        mrpt::poses::CPose2D mean;
        Eigen::Matrix3d cov;
    };
    /** The pose to start the EKF from, once the particles have gathered (see above);
     *  `headingKnown`: odometry turns the particles, so their heading is evidence. */
    std::optional<Start> converged(bool headingKnown) const;
    size_t measurements() const { return measurements_; }

 private:
    struct Particle {
        double x, y, phi, logWeight;
    };
    /** Redraws `count` particles (all if none exist) on the measurement's locus. */
    template <class Draw>
    void reseed(size_t count, Draw&& draw);
    void weigh(const std::vector<double>& logLikelihood);
    void resampleIfDegenerate();
    Eigen::Vector2d sensorAt(const Particle& p, const Eigen::Vector3d& sensorOnRobot) const;

    BeaconMap map_;
    ParticleStartOptions o_;
    OdometryNoise noise_;
    double rangeSpan_;  ///< m: the uniform part's support (twice the map's extent + 20 m)
    std::vector<Particle> particles_;
    size_t measurements_ = 0;
    mrpt::random::CRandomGenerator rng_;
};

}  // namespace mrloc::beacons
