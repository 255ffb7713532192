#pragma once
// Tracking filter for one robot: an extended Kalman filter on the planar pose (x, y, phi)
// whose prediction is the odometry increment (MRPT's pose-composition Jacobians) and whose
// updates are the beacon ranges, one at a time.
//
// Range biases: real TOF links read long or short by a few centimetres that drift (a UWB
// antenna delay, the ultrasonic decoder's late trigger on a weak burst, the speed of sound
// with temperature). With bias estimation on, the state also holds one offset per beacon
// (a random walk) and one scale common to all (the speed of sound), and a range is
//   r = (1 + scale) |sensor - beacon| + offset_beacon + noise.
// Odometry between epochs and the beacons' spread make them observable.
//
// Long echoes (NLOS reflections, a late tone decoder): each range passes a chi-square gate
// on its normalised innovation, the most consistent first; a beacon that keeps failing it
// has its offset reopened; from a given start pose nothing is taken in until one epoch's
// ranges agree; a lost track (every range refused, or consistent fixes far outside the
// covariance) starts again. Start-up: from the known start pose if one is given, else from
// robust fixes that fit the odometry's path (consensus, then Umeyama). doc/beacons.md.
#include <mrloc/beacons/BeaconMap.h>
#include <mrloc/beacons/Multilateration.h>
#include <mrloc/beacons/OdometryNoise.h>
#include <mrloc/beacons/ParticleStart.h>
#include <mrloc/beacons/StartupTrack.h>
#include <mrloc/beacons/Ultrasonic.h>
#include <mrpt/obs/CObservationBeaconRanges.h>
#include <mrpt/poses/CPosePDFGaussian.h>

#include <deque>
#include <functional>
#include <map>
#include <optional>

namespace mrloc::beacons {

struct TrackerOptions {
    double rangeSigma = 0.03;            ///< m
    double bearingSigma = 0.02;          ///< rad, a camera's bearing to a landmark
    double gateProbability = 0.999;      ///< chi-square(1) gate on each range innovation
    /** Huber's loss on a measurement's normalised innovation beyond this many sigmas (it
     *  counts as if noisier); 0: the plain EKF update. */
    enum class RobustLoss { Huber, Mixture };
    /** After the gate: Huber's loss, or a Gaussian-plus-uniform mixture (robust_loss). */
    RobustLoss robustLoss = RobustLoss::Huber;
    double outlierShare = 0.3;           ///< the mixture's prior share of gross errors
    double huberK = 1.345;               ///< Huber's constant for 95 % efficiency on Gaussian noise
    double odomSigmaPerMetre = 0.05;     ///< translation noise per metre travelled
    double odomSigmaPhiPerRad = 0.05;    ///< heading noise per radian turned
    double odomSigmaPhiPerMetre = 0.02;  ///< heading noise per metre travelled (rad/m)
    /** The odometry's random walk (OdometryNoise.h): sd after 1 m (or 1 rad) whatever the
     *  reading rate; 0 by default, as the simulator's and MRPT's noise are per reading;
     *  `mrloc import` writes a real log's. */
    double odomWalkXY = 0;               ///< m/sqrt(m)
    double odomWalkPhiPerRad = 0;        ///< rad/sqrt(rad) turned
    double odomWalkPhiPerMetre = 0;      ///< rad/sqrt(m) travelled
    double randomWalkSigma = 0.5;        ///< m/sqrt(s), when the rawlog has no odometry
    double bootstrapBaseline = 0.3;      ///< m the start-up fixes must span along the path
    int resetAfter = 5;  ///< epochs in a row lost (every range rejected, or consistent
                         ///< fixes outside the filter's covariance) before a reset
    /** The robot's pose at its first odometry reading, if known (MRPT's apps take it from
     *  [OdometryEstimation]): the filter starts there instead of from two fixes. */
    std::optional<mrpt::poses::CPose2D> startPose;
    double startSigmaXY = 0.1;   ///< m
    double startSigmaPhi = 0.1;  ///< rad
    bool estimateBias = true;    ///< per-beacon offsets and a common scale in the state
    double biasSigma = 0.05;     ///< prior sd of the offset common to all beacons (m)
    double biasSpread = 0.01;    ///< prior sd of each beacon's own offset about it (m)
    double biasDrift = 0.002;    ///< random walk of each offset (m/sqrt(s))
    double scaleSigma = 0.01;    ///< prior sd of the common scale; 0 = no scale state
    MultilaterationOptions fix;  ///< for start-up and reset fixes (2-D: knownHeight set per epoch)
    /** The range error a shot from beacon `id` at `beacon` to a receiver at `receiver` is
     *  expected to carry (m), subtracted by the fixes of mode = fixes (refit twice from the
     *  fix before); empty: none (delay_compensation). */
    RangeDelay rangeDelay;
    /** With rangeDelay: the refits weight each range by the jitter its shot is expected to
     *  carry, sd^2 = (rangeSigma^2 + delay sd^2) / shots averaged (jitter_weights). */
    bool jitterWeights = false;
};

struct TrackerStats {
    size_t epochs = 0, rangesReceived = 0, rangesUsed = 0, rangesGated = 0, rangesUnknownBeacon = 0;
    size_t fixes = 0, fixFailures = 0, mirrorResolved = 0, resets = 0;
    size_t offsetsReopened = 0;  ///< a beacon's ranges failed the gate 8 times in 10
    size_t bearingsReceived = 0, bearingsUsed = 0, bearingsGated = 0;
    size_t particleStarts = 0;  ///< starts (and re-starts) from the particle start-up

    TrackerStats& operator+=(const TrackerStats& o) {
        epochs += o.epochs, rangesReceived += o.rangesReceived, rangesUsed += o.rangesUsed;
        rangesGated += o.rangesGated, rangesUnknownBeacon += o.rangesUnknownBeacon;
        fixes += o.fixes, fixFailures += o.fixFailures, mirrorResolved += o.mirrorResolved;
        resets += o.resets, offsetsReopened += o.offsetsReopened;
        bearingsReceived += o.bearingsReceived, bearingsUsed += o.bearingsUsed;
        bearingsGated += o.bearingsGated, particleStarts += o.particleStarts;
        return *this;
    }
};

class BeaconTracker {
 public:
    BeaconTracker(BeaconMap map, TrackerOptions options);

    void onOdometry(const mrpt::poses::CPose2D& odometry);
    /** Returns the robot pose after this epoch, or nullopt while not yet localized. */
    std::optional<mrpt::poses::CPose2D> onRanges(double t,
                                                 const mrpt::obs::CObservationBeaconRanges& obs);

    using Sighting = ParticleStart::Sighting;
    /** Single sightings of known beacons or landmarks (ranges, bearings or both), as one
     *  observation gives them. Not yet started: they go to the particle start-up, which
     *  starts the filter once its particles gather (ParticleStart.h); started: each is an
     *  EKF update through its chi-square gate. Returns the pose once started. */
    std::optional<mrpt::poses::CPose2D> onSightings(double t, const std::vector<Sighting>& seen);
    /** Before the filter starts: the particle start-up takes the sightings (a range
     *  observation's, before any window gathers them); true if the filter started now. */
    bool feedStart(double t, const std::vector<Sighting>& seen);

    /** Seed 001 as published: one multilateration from this epoch's ranges alone (no
     *  filter, no outlier rejection); the filter state is left untouched. */
    std::optional<Fix> fixOnly(const mrpt::obs::CObservationBeaconRanges& obs);

    bool initialized() const { return initialized_; }
    /** The pose and its covariance (the pose block of the full state's). */
    const mrpt::poses::CPosePDFGaussian& pdf() const { return pdf_; }
    const TrackerStats& stats() const { return stats_; }
    /** Estimated range offset of each beacon (m); empty with bias estimation off. */
    std::map<int, double> rangeOffsets() const;
    /** Estimated common range scale (0 = none); 0 when not estimated. */
    double rangeScale() const { return scaleIndex_ ? state_(*scaleIndex_) : 0.0; }

 private:
    struct Range {
        Eigen::Vector3d beacon, sensorOnRobot;
        double range;
        int beaconId;
        int shots = 1;     ///< averaged into `range` (shots_per_beacon)
        double sigma = 0;  ///< its own sd for a weighted fix (m); 0: rangeSigma
    };
    struct Innovation {
        bool valid = false;
        double value = 0, S = 0;  ///< measured minus predicted range, and its variance
        Eigen::RowVectorXd H;     ///< d(predicted)/d(state)
    };
    std::vector<Range> usableRanges(const mrpt::obs::CObservationBeaconRanges& obs);
    /** One range per beacon: the mean of its ranges in the epoch, in first-seen order. */
    static std::vector<Range> meanPerBeacon(std::vector<Range> ranges);
    Innovation innovationOf(const Range& r) const;
    /** d(fix position)/d(bias states) of a fix at `fix` from `used` (2 x extras). */
    Eigen::MatrixXd fixBiasSensitivity(const Eigen::Vector3d& fix,
                                       const std::vector<Range>& used) const;
    /** A consistent fix from the ranges, corrected by the bias estimates, lies outside the
     *  filter's position covariance (the divergence gate). */
    bool disagreesWithFix(const std::vector<Range>& ranges);
    /** The ranges of a consistent fix from these with two to spare (one left out at
     *  most); none if there is no such fix. */
    std::vector<Range> consistentSubset(const std::vector<Range>& ranges);
    /** The ranges with the estimated offsets and scale taken out. */
    std::vector<Range> correctedByBias(const std::vector<Range>& ranges) const;
    /** Records a range's gate outcome; reopens the beacon's offset when it keeps failing. */
    void noteGate(int beacon, bool accepted);
    /** A multilateration fix; `counted` in the stats (the consistency check's are not). */
    std::optional<Fix> fixFrom(const std::vector<Range>& ranges, bool robust = true,
                               std::vector<Range>* used = nullptr, bool counted = true);
    bool updateWithRange(const Range& r, double gate);
    /** The odometry's noise model, from the options. */
    OdometryNoise odometryNoise() const;
    Innovation bearingInnovation(const Sighting& s) const;
    /** The EKF's update with one scalar measurement of variance R, if it passes `gate`. */
    /** `span`: the support of the gross errors' uniform density (m or rad), for the mixture. */
    bool scalarUpdate(const Innovation& in, double R, double gate, double span);
    /** Without odometry: the random walk over the time since the last measurement; the
     *  offsets' drift either way. */
    void predictToTime(double t);
    /** Counts a single measurement's normalised innovation squared (before its update);
     *  lost when kLostFar of the last kLostWindow were over kLostNis, chi-square(1)'s 95 %:
     *  a filter right but for 45 % gross errors has 48 % of them there, and 25 of 30 about
     *  once in 16,000 windows; a filter confidently wrong has most of them there, whether the
     *  gate takes them or not. */
    bool lostBySingleMeasurements(double nis);
    static double normalisedSquare(const Innovation& in);
    /** Lost: start again, from fixes (ranges enough) or the particles about the last pose. */
    void restart();
    std::optional<mrpt::poses::CPose2D> bootstrap(const std::vector<Range>& ranges);
    /** Starts at o_.startPose, once, before the first odometry reading. */
    void startIfGiven();
    void startAt(const mrpt::poses::CPose2D& pose);
    /** Unknowns of a fix: x, y, and z unless the receiver's height is known. */
    size_t unknowns() const { return o_.fix.knownHeight ? 2 : 3; }
    /** A consistent fix from the ranges with the bias estimates taken out, not counted in
     *  the stats, using at least `needed` of them (`used`); nothing otherwise. */
    std::optional<Fix> checkingFix(const std::vector<Range>& ranges, size_t needed,
                                   std::vector<Range>& used);
    /** Sets the pose and its covariance; the bias states go back to their prior. */
    void initialize(const mrpt::poses::CPose2D& pose, const Eigen::Matrix3d& poseCov);
    /** Starts at a multilateration fix; the fix's error due to the bias states goes into
     *  the position's covariance and its correlation with them. */
    void initializeFromFix(const Fix& fix, const std::vector<Range>& used, double phi,
                           double phiVariance);
    void syncPdf();

    BeaconMap map_;
    TrackerOptions o_;
    double gate_;            // chi-square(1) threshold for o_.gateProbability
    double divergenceGate_;  // chi-square(2) threshold, fix against filter
    mrpt::poses::CPosePDFGaussian pdf_;
    // The full state: x, y, phi (kept in pdf_.mean), then the scale and the offsets.
    Eigen::VectorXd state_;
    Eigen::MatrixXd cov_;
    std::optional<Eigen::Index> scaleIndex_;
    std::map<int, Eigen::Index> offsetIndex_;  // beacon id -> state index
    bool initialized_ = false;
    std::optional<mrpt::poses::CPose2D> lastOdometry_;
    std::optional<double> lastT_;
    // Start-up without a start pose; the heading offset of the last held track, for the
    // estimates meanwhile.
    StartupTrack track_;
    static constexpr double kMaxBootstrapGdop = 5.0;  ///< a poorer fix is no start
    double headingOffset_ = 0;
    static constexpr size_t kGateWindow = 10, kGateReopen = 8;
    static constexpr size_t kLostWindow = 30, kLostFar = 25;
    static constexpr double kLostNis = 3.84;
    std::deque<bool> recentGated_;  // the last single measurements: over kLostNis
    double rangeSpan_;              // m: the ranges' uniform part (ParticleStart::rangeSpanOf)
    ParticleStart start_;
    std::optional<double> lastStartT_;             // the particles' last random walk (no odometry)
    mrpt::poses::CPose2D pendingStartMotion_;      // odometry since the particles last moved
    std::map<int, std::deque<bool>> gateHistory_;  // beacon -> gated, its last ranges
    bool settled_ = true;  // false from a given start pose until one consistent epoch
    int epochsLost_ = 0;   // epochs in a row with every range rejected or the fix apart
    std::optional<Eigen::Vector3d> lastFix_;
    TrackerStats stats_;
};

/** Chi-square quantile with one degree of freedom (the gate on a range's innovation). */
double chi2Quantile1(double probability);

}  // namespace mrloc::beacons
