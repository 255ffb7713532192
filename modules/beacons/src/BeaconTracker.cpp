#include <mrloc/beacons/BeaconTracker.h>
#include <mrpt/math/wrap2pi.h>

#include <Eigen/Dense>
#include <cmath>

namespace mrloc::beacons {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using mrpt::poses::CPose2D;

double chi2Quantile1(double p) {
    // For one degree of freedom the quantile is the square of the normal quantile:
    // invert erf by bisection (runs once per configuration).
    double lo = 0, hi = 40;
    for (int i = 0; i < 100; ++i) {
        const double mid = 0.5 * (lo + hi);
        (std::erf(mid / std::sqrt(2.0)) < p ? lo : hi) = mid;
    }
    return lo * lo;
}

BeaconTracker::BeaconTracker(BeaconMap map, TrackerOptions options)
    : map_(std::move(map)), o_(std::move(options)), gate_(chi2Quantile1(o_.gateProbability)) {}

void BeaconTracker::onOdometry(const CPose2D& odo) {
    hasOdometry_ = true;
    if (!initialized_ && !lastOdometry_ && o_.startPose) startAt(*o_.startPose);
    if (initialized_ && lastOdometry_) {
        const CPose2D delta = odo - *lastOdometry_;  // increment in the robot frame
        const double d = std::hypot(delta.x(), delta.y());
        const double sxy = o_.odomSigmaPerMetre * d + 1e-4;
        const double sphi =
            o_.odomSigmaPhiPerRad * std::abs(delta.phi()) + o_.odomSigmaPhiPerMetre * d + 1e-4;
        mrpt::math::CMatrixDouble33 Q;
        Q.setZero();
        Q(0, 0) = Q(1, 1) = sxy * sxy;
        Q(2, 2) = sphi * sphi;
        pdf_ += mrpt::poses::CPosePDFGaussian(delta, Q);  // pose composition with Jacobians
    }
    lastOdometry_ = odo;
}

void BeaconTracker::startAt(const CPose2D& pose) {
    // a known start pose is the pose where the log starts (its first odometry reading or
    // its first ranges, whichever comes first)
    pdf_.mean = pose;
    pdf_.cov.setZero();
    pdf_.cov(0, 0) = pdf_.cov(1, 1) = o_.startSigmaXY * o_.startSigmaXY;
    pdf_.cov(2, 2) = o_.startSigmaPhi * o_.startSigmaPhi;
    initialized_ = true;
}

std::vector<BeaconTracker::Range> BeaconTracker::usableRanges(
    const mrpt::obs::CObservationBeaconRanges& obs) {
    std::vector<Range> out;
    for (const auto& m : obs.sensedData) {
        ++stats_.rangesReceived;
        const auto it = map_.find(m.beaconID);
        if (it == map_.end()) {
            ++stats_.rangesUnknownBeacon;
            continue;
        }
        if (!std::isfinite(m.sensedDistance) || m.sensedDistance <= 0) continue;
        const auto& b = it->second;
        const auto& s = m.sensorLocationOnRobot;
        out.push_back(
            {Vector3d(b.x, b.y, b.z), Vector3d(s.x(), s.y(), s.z()), double(m.sensedDistance)});
    }
    return out;
}

std::optional<Fix> BeaconTracker::fixFrom(const std::vector<Range>& ranges, bool robust) {
    if (ranges.size() < 3) return std::nullopt;
    std::vector<RangeMeasurement> m;
    for (const auto& r : ranges) m.push_back({r.beacon, r.range});
    MultilaterationOptions fo = o_.fix;
    fo.rangeSigma = o_.rangeSigma;
    if (fo.knownHeight) fo.knownHeight = ranges.front().sensorOnRobot.z();  // robot on the floor
    if (lastFix_) fo.hint = *lastFix_;
    ++stats_.fixes;
    Fix f = robust ? robustMultilaterate(m, fo, 3.0 * o_.rangeSigma) : multilaterate(m, fo);
    // With a spare range the residual tells an inconsistent set (two late echoes, say)
    // that leave-one-out could not repair: the filter must not start or restart from it.
    const size_t unknowns = fo.knownHeight ? 2 : 3;
    const bool inconsistent =
        robust && f.ok() && m.size() > unknowns && f.rmsResidual > 5.0 * o_.rangeSigma;
    if (!f.ok() || inconsistent) {
        ++stats_.fixFailures;
        return std::nullopt;
    }
    if (f.mirrorAmbiguous) ++stats_.mirrorResolved;
    lastFix_ = f.position;
    return f;
}

bool BeaconTracker::updateWithRange(const Range& r, double gate) {
    const CPose2D mean = pdf_.mean;
    const double c = std::cos(mean.phi()), s = std::sin(mean.phi());
    const Vector3d sensor(mean.x() + c * r.sensorOnRobot.x() - s * r.sensorOnRobot.y(),
                          mean.y() + s * r.sensorOnRobot.x() + c * r.sensorOnRobot.y(),
                          r.sensorOnRobot.z());
    const Vector3d d = sensor - r.beacon;
    const double predicted = d.norm();
    if (predicted < 1e-9) return false;
    // h(x) = |sensor(x) - beacon|; H = dh/d(x, y, phi).
    Eigen::RowVector3d H;
    H << d.x() / predicted, d.y() / predicted,
        (d.x() * (-s * r.sensorOnRobot.x() - c * r.sensorOnRobot.y()) +
         d.y() * (c * r.sensorOnRobot.x() - s * r.sensorOnRobot.y())) /
            predicted;
    const Matrix3d P = pdf_.cov.asEigen();
    const double innovation = r.range - predicted;
    const double S = H * P * H.transpose() + o_.rangeSigma * o_.rangeSigma;
    if (innovation * innovation / S > gate) return false;
    const Vector3d K = P * H.transpose() / S;
    const Matrix3d IKH = Matrix3d::Identity() - K * H;
    // Joseph form keeps P symmetric positive definite.
    const Matrix3d newP =
        IKH * P * IKH.transpose() + K * K.transpose() * (o_.rangeSigma * o_.rangeSigma);
    pdf_.mean = CPose2D(mean.x() + K(0) * innovation, mean.y() + K(1) * innovation,
                        mrpt::math::wrapToPi(mean.phi() + K(2) * innovation));
    pdf_.cov = mrpt::math::CMatrixDouble33(newP);
    return true;
}

std::optional<CPose2D> BeaconTracker::bootstrap(const std::vector<Range>& ranges) {
    const auto f = fixFrom(ranges);
    if (!f) return std::nullopt;
    const Eigen::Vector2d p = f->position.head<2>();
    const CPose2D odo = lastOdometry_.value_or(CPose2D());
    const auto start = [&](double phi, double sigmaPhi) {
        pdf_.mean = CPose2D(p.x(), p.y(), phi);
        Matrix3d P = Matrix3d::Zero();
        P.topLeftCorner<2, 2>() = f->covariance.topLeftCorner<2, 2>();
        P(2, 2) = sigmaPhi * sigmaPhi;
        pdf_.cov = mrpt::math::CMatrixDouble33(P);
        initialized_ = true;
    };
    if (!hasOdometry_) {
        start(0.0, M_PI);  // heading unobservable without odometry; ranges fix position only
    } else if (!firstFix_) {
        firstFix_ = {p, odo};
    } else {
        const Eigen::Vector2d moved = p - firstFix_->first;
        const CPose2D& odo0 = firstFix_->second;
        const double odoMoved = std::hypot(odo.x() - odo0.x(), odo.y() - odo0.y());
        if (moved.norm() >= o_.bootstrapBaseline && odoMoved >= 0.5 * o_.bootstrapBaseline) {
            // The world-frame direction of travel minus the odometry-frame one is the
            // rotation between the frames; add it to the odometry heading.
            const double offset = std::atan2(moved.y(), moved.x()) -
                                  std::atan2(odo.y() - odo0.y(), odo.x() - odo0.x());
            const double sigmaPhi = 2.0 * o_.rangeSigma * 2.0 / moved.norm() + 0.05;
            start(mrpt::math::wrapToPi(odo.phi() + offset), sigmaPhi);
        }
    }
    return CPose2D(p.x(), p.y(), odo.phi());
}

std::optional<Fix> BeaconTracker::fixOnly(const mrpt::obs::CObservationBeaconRanges& obs) {
    ++stats_.epochs;
    const auto ranges = usableRanges(obs);
    stats_.rangesUsed += ranges.size();
    return fixFrom(ranges, /*robust=*/false);
}

std::optional<CPose2D> BeaconTracker::onRanges(double t,
                                               const mrpt::obs::CObservationBeaconRanges& obs) {
    ++stats_.epochs;
    const auto ranges = usableRanges(obs);
    if (!initialized_ && !lastOdometry_ && o_.startPose) startAt(*o_.startPose);
    if (!initialized_) {
        lastT_ = t;
        return bootstrap(ranges);
    }
    if (!hasOdometry_ && lastT_) {
        const double q = o_.randomWalkSigma * o_.randomWalkSigma * std::max(0.0, t - *lastT_);
        pdf_.cov(0, 0) += q;
        pdf_.cov(1, 1) += q;
    }
    lastT_ = t;

    size_t used = 0;
    for (const auto& r : ranges) {
        if (updateWithRange(r, gate_)) {
            ++used;
        } else {
            ++stats_.rangesGated;
        }
    }
    stats_.rangesUsed += used;
    epochsAllRejected_ = (used == 0 && ranges.size() >= 3) ? epochsAllRejected_ + 1 : 0;
    if (epochsAllRejected_ >= o_.resetAfter) {
        if (const auto f = fixFrom(ranges)) {
            pdf_.mean = CPose2D(f->position.x(), f->position.y(), pdf_.mean.phi());
            pdf_.cov(0, 0) = f->covariance(0, 0) + 1e-4;
            pdf_.cov(1, 1) = f->covariance(1, 1) + 1e-4;
            pdf_.cov(0, 1) = pdf_.cov(1, 0) = f->covariance(0, 1);
            pdf_.cov(0, 2) = pdf_.cov(2, 0) = pdf_.cov(1, 2) = pdf_.cov(2, 1) = 0;
            ++stats_.resets;
            epochsAllRejected_ = 0;
        }
    }
    return pdf_.mean;
}

}  // namespace mrloc::beacons
