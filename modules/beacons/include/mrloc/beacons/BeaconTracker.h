#pragma once
// Tracking filter for one robot: an extended Kalman filter on the planar pose (x, y, phi)
// whose prediction is the odometry increment (composed with MRPT's CPosePDFGaussian) and
// whose updates are the beacon ranges, one at a time.
//
// Robustness: each range passes a chi-square gate on its normalised innovation before it is
// used, so one bad range (NLOS reflection, a late tone-decoder trigger) is rejected instead
// of dragging the estimate. If several epochs in a row have every range rejected, the filter
// re-initialises from a robust multilateration fix (the bias was in the filter, not the
// ranges). Start-up: from the known start pose if one is given; else position from a fix
// and heading from two fixes a baseline apart compared with the odometry between them.
#include <mrloc/beacons/BeaconMap.h>
#include <mrloc/beacons/Multilateration.h>
#include <mrpt/obs/CObservationBeaconRanges.h>
#include <mrpt/poses/CPosePDFGaussian.h>

#include <optional>

namespace mrloc::beacons {

struct TrackerOptions {
    double rangeSigma = 0.03;            ///< m
    double gateProbability = 0.999;      ///< chi-square(1) gate on each range innovation
    double odomSigmaPerMetre = 0.05;     ///< translation noise per metre travelled
    double odomSigmaPhiPerRad = 0.05;    ///< heading noise per radian turned
    double odomSigmaPhiPerMetre = 0.02;  ///< heading noise per metre travelled (rad/m)
    double randomWalkSigma = 0.5;        ///< m/sqrt(s), when the rawlog has no odometry
    double bootstrapBaseline = 0.3;      ///< m between the two fixes that give the heading
    int resetAfter = 5;                  ///< epochs with every range rejected before a reset
    /** The robot's pose at its first odometry reading, if known (MRPT's apps take it from
     *  [OdometryEstimation]): the filter starts there instead of from two fixes. */
    std::optional<mrpt::poses::CPose2D> startPose;
    double startSigmaXY = 0.1;   ///< m
    double startSigmaPhi = 0.1;  ///< rad
    MultilaterationOptions fix;  ///< for start-up and reset fixes (2-D: knownHeight set per epoch)
};

struct TrackerStats {
    size_t epochs = 0, rangesReceived = 0, rangesUsed = 0, rangesGated = 0, rangesUnknownBeacon = 0;
    size_t fixes = 0, fixFailures = 0, mirrorResolved = 0, resets = 0;

    TrackerStats& operator+=(const TrackerStats& o) {
        epochs += o.epochs, rangesReceived += o.rangesReceived, rangesUsed += o.rangesUsed;
        rangesGated += o.rangesGated, rangesUnknownBeacon += o.rangesUnknownBeacon;
        fixes += o.fixes, fixFailures += o.fixFailures, mirrorResolved += o.mirrorResolved;
        resets += o.resets;
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

    /** Seed 001 as published: one multilateration from this epoch's ranges alone (no
     *  filter, no outlier rejection); the filter state is left untouched. */
    std::optional<Fix> fixOnly(const mrpt::obs::CObservationBeaconRanges& obs);

    bool initialized() const { return initialized_; }
    const mrpt::poses::CPosePDFGaussian& pdf() const { return pdf_; }
    const TrackerStats& stats() const { return stats_; }

 private:
    struct Range {
        Eigen::Vector3d beacon, sensorOnRobot;
        double range;
    };
    std::vector<Range> usableRanges(const mrpt::obs::CObservationBeaconRanges& obs);
    std::optional<Fix> fixFrom(const std::vector<Range>& ranges, bool robust = true);
    bool updateWithRange(const Range& r, double gate);
    std::optional<mrpt::poses::CPose2D> bootstrap(const std::vector<Range>& ranges);
    void startAt(const mrpt::poses::CPose2D& pose);

    BeaconMap map_;
    TrackerOptions o_;
    double gate_;  // chi-square(1) threshold for o_.gateProbability
    mrpt::poses::CPosePDFGaussian pdf_;
    bool initialized_ = false;
    bool hasOdometry_ = false;
    std::optional<mrpt::poses::CPose2D> lastOdometry_;
    std::optional<double> lastT_;
    // Start-up: the first fix and the odometry reading at that moment.
    std::optional<std::pair<Eigen::Vector2d, mrpt::poses::CPose2D>> firstFix_;
    int epochsAllRejected_ = 0;
    std::optional<Eigen::Vector3d> lastFix_;
    TrackerStats stats_;
};

/** Chi-square quantile with one degree of freedom (the gate on a range's innovation). */
double chi2Quantile1(double probability);

}  // namespace mrloc::beacons
