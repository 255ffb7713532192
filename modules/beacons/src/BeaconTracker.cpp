#include <mrloc/beacons/BeaconTracker.h>
#include <mrpt/math/wrap2pi.h>

#include <Eigen/Dense>
#include <algorithm>
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
    : map_(std::move(map)),
      o_(std::move(options)),
      gate_(chi2Quantile1(o_.gateProbability)),
      divergenceGate_(-2.0 * std::log(1.0 - o_.gateProbability)),  // chi-square(2) quantile
      rangeSpan_(ParticleStart::rangeSpanOf(map_)),
      start_(map_, {o_.rangeSigma, o_.bearingSigma, o_.randomWalkSigma, 1}, odometryNoise()) {
    Eigen::Index n = 3;
    if (o_.estimateBias) {
        if (o_.scaleSigma > 0) scaleIndex_ = n++;
        for (const auto& [id, beacon] : map_) offsetIndex_[id] = n++;
    }
    state_ = Eigen::VectorXd::Zero(n);
    cov_ = Eigen::MatrixXd::Zero(n, n);
}

std::map<int, double> BeaconTracker::rangeOffsets() const {
    std::map<int, double> out;
    for (const auto& [id, i] : offsetIndex_) out[id] = state_(i);
    return out;
}

void BeaconTracker::syncPdf() {
    state_(2) = mrpt::math::wrapToPi(state_(2));
    pdf_.mean = CPose2D(state_(0), state_(1), state_(2));
    pdf_.cov = mrpt::math::CMatrixDouble33(Matrix3d(cov_.topLeftCorner<3, 3>()));
}

void BeaconTracker::initialize(const CPose2D& pose, const Matrix3d& poseCov) {
    state_.setZero();
    state_.head<3>() = Vector3d(pose.x(), pose.y(), pose.phi());
    cov_.setZero();
    cov_.topLeftCorner<3, 3>() = poseCov;
    if (scaleIndex_) cov_(*scaleIndex_, *scaleIndex_) = o_.scaleSigma * o_.scaleSigma;
    // every beacon's offset shares a common part (the same hardware on every link) and
    // has its own: cov(b_i, b_j) = common^2 + [i = j] own^2
    for (const auto& [id, i] : offsetIndex_)
        for (const auto& [id2, j] : offsetIndex_)
            cov_(i, j) =
                o_.biasSigma * o_.biasSigma + (i == j ? o_.biasSpread * o_.biasSpread : 0.0);
    initialized_ = true;
    settled_ = true;
    syncPdf();
}

OdometryNoise BeaconTracker::odometryNoise() const {
    return {o_.odomSigmaPerMetre, o_.odomSigmaPhiPerRad, o_.odomSigmaPhiPerMetre,
            o_.odomWalkXY,        o_.odomWalkPhiPerRad,  o_.odomWalkPhiPerMetre};
}

void BeaconTracker::onOdometry(const CPose2D& odo) {
    startIfGiven();
    if (!lastOdometry_) {  // the first reading: no motion yet
        lastOdometry_ = odo;
        return;
    }
    const CPose2D delta = odo - *lastOdometry_;  // increment in the robot frame
    lastOdometry_ = odo;
    // not started: the particles take the motion at their next sighting, composed
    if (!initialized_) return void(pendingStartMotion_ = pendingStartMotion_ + delta);
    const Matrix3d Q = odometryNoise().of(delta);
    // pose (+) delta, as CPosePDFGaussian's composition does, carried to the whole
    // state: the bias states do not move, their cross-covariance turns with the pose
    mrpt::math::CMatrixDouble33 dfDx, dfDu;
    mrpt::poses::CPosePDF::jacobiansPoseComposition(pdf_.mean, delta, dfDx, dfDu);
    const Matrix3d Jx = dfDx.asEigen(), Ju = dfDu.asEigen();
    const CPose2D moved = pdf_.mean + delta;
    state_.head<3>() = Vector3d(moved.x(), moved.y(), moved.phi());
    const Eigen::Index m = cov_.rows() - 3;
    cov_.topLeftCorner<3, 3>() =
        Jx * cov_.topLeftCorner<3, 3>() * Jx.transpose() + Ju * Q * Ju.transpose();
    if (m > 0) {
        cov_.topRightCorner(3, m) = Jx * cov_.topRightCorner(3, m);
        cov_.bottomLeftCorner(m, 3) = cov_.topRightCorner(3, m).transpose();
    }
    syncPdf();
}

void BeaconTracker::startIfGiven() {
    // a known start pose is the pose where the log starts: its first odometry reading or
    // its first ranges, whichever comes first
    if (!initialized_ && !lastOdometry_ && o_.startPose) startAt(*o_.startPose);
}

void BeaconTracker::startAt(const CPose2D& pose) {
    initialize(pose, Vector3d(o_.startSigmaXY * o_.startSigmaXY, o_.startSigmaXY * o_.startSigmaXY,
                              o_.startSigmaPhi * o_.startSigmaPhi)
                         .asDiagonal());
    settled_ = false;  // a prior, not yet evidence: see onRanges
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
        out.push_back({Vector3d(b.x, b.y, b.z), Vector3d(s.x(), s.y(), s.z()),
                       double(m.sensedDistance), int(m.beaconID)});
    }
    return out;
}

std::optional<Fix> BeaconTracker::fixFrom(const std::vector<Range>& ranges, bool robust,
                                          std::vector<Range>* used, bool counted) {
    if (ranges.size() < 3) return std::nullopt;
    std::vector<RangeMeasurement> m;
    for (const auto& r : ranges) m.push_back({r.beacon, r.range, r.beaconId, r.sigma});
    MultilaterationOptions fo = o_.fix;
    fo.rangeSigma = o_.rangeSigma;
    if (fo.knownHeight) fo.knownHeight = ranges.front().sensorOnRobot.z();  // robot on the floor
    if (lastFix_) fo.hint = *lastFix_;
    if (counted) ++stats_.fixes;
    int rejected = -1;
    Fix f =
        robust ? robustMultilaterate(m, fo, 3.0 * o_.rangeSigma, &rejected) : multilaterate(m, fo);
    // With a spare range the residual tells an inconsistent set (two late echoes, say)
    // that leave-one-out could not repair: the filter must not start or restart from it.
    const bool inconsistent =
        robust && f.ok() && m.size() > unknowns() && f.rmsResidual > 5.0 * o_.rangeSigma;
    if (!f.ok() || inconsistent) {
        if (counted) ++stats_.fixFailures;
        return std::nullopt;
    }
    if (f.mirrorAmbiguous) ++stats_.mirrorResolved;
    lastFix_ = f.position;
    if (used) {
        *used = ranges;
        if (rejected >= 0) used->erase(used->begin() + rejected);
    }
    return f;
}

BeaconTracker::Innovation BeaconTracker::innovationOf(const Range& r) const {
    Innovation in;
    const double x = state_(0), y = state_(1), c = std::cos(state_(2)), s = std::sin(state_(2));
    const Vector3d sensor(x + c * r.sensorOnRobot.x() - s * r.sensorOnRobot.y(),
                          y + s * r.sensorOnRobot.x() + c * r.sensorOnRobot.y(),
                          r.sensorOnRobot.z());
    const Vector3d d = sensor - r.beacon;
    const double distance = d.norm();
    if (distance < 1e-9) return in;
    // h(state) = (1 + scale) |sensor(x, y, phi) - beacon| + offset_beacon
    const double scale = scaleIndex_ ? state_(*scaleIndex_) : 0.0;
    in.H = Eigen::RowVectorXd::Zero(state_.size());
    in.H(0) = (1 + scale) * d.x() / distance;
    in.H(1) = (1 + scale) * d.y() / distance;
    in.H(2) = (1 + scale) *
              (d.x() * (-s * r.sensorOnRobot.x() - c * r.sensorOnRobot.y()) +
               d.y() * (c * r.sensorOnRobot.x() - s * r.sensorOnRobot.y())) /
              distance;
    double predicted = (1 + scale) * distance;
    if (scaleIndex_) in.H(*scaleIndex_) = distance;
    if (const auto offset = offsetIndex_.find(r.beaconId); offset != offsetIndex_.end()) {
        in.H(offset->second) = 1;
        predicted += state_(offset->second);
    }
    in.value = r.range - predicted;
    in.S = (in.H * cov_ * in.H.transpose())(0, 0) + o_.rangeSigma * o_.rangeSigma;
    in.valid = true;
    return in;
}

bool BeaconTracker::updateWithRange(const Range& r, double gate) {
    return scalarUpdate(innovationOf(r), o_.rangeSigma * o_.rangeSigma, gate, rangeSpan_);
}

BeaconTracker::Innovation BeaconTracker::bearingInnovation(const Sighting& m) const {
    // h = atan2(by - sy, bx - sx) - phi - yaw, the sensor s at p + R(phi) o
    Innovation in;
    const double c = std::cos(state_(2)), s = std::sin(state_(2));
    const double ox = m.sensorOnRobot.x(), oy = m.sensorOnRobot.y();
    const double dx = m.beacon.x() - (state_(0) + c * ox - s * oy);
    const double dy = m.beacon.y() - (state_(1) + s * ox + c * oy);
    const double q = dx * dx + dy * dy;
    if (q < 1e-12 || !m.bearing) return in;
    in.H = Eigen::RowVectorXd::Zero(state_.size());
    in.H(0) = dy / q;
    in.H(1) = -dx / q;
    in.H(2) = dy / q * (-s * ox - c * oy) - dx / q * (c * ox - s * oy) - 1.0;
    const double predicted = std::atan2(dy, dx) - state_(2) - m.sensorYaw;
    in.value = mrpt::math::wrapToPi(*m.bearing - predicted);
    in.S = (in.H * cov_ * in.H.transpose())(0, 0) + m.bearingSigma * m.bearingSigma;
    in.valid = true;
    return in;
}

double BeaconTracker::normalisedSquare(const Innovation& in) {
    return in.valid ? in.value * in.value / in.S : 0.0;
}

bool BeaconTracker::scalarUpdate(const Innovation& given, double R, double gate, double span) {
    if (!given.valid || given.value * given.value / given.S > gate) return false;
    Innovation in = given;
    const double z = std::abs(in.value) / std::sqrt(in.S);
    // the measurement counts as if its innovation variance were S / w (R' = S / w - H P H^T)
    double w = 1;
    if (o_.robustLoss == TrackerOptions::RobustLoss::Huber && o_.huberK > 0 && z > o_.huberK) {
        // Huber's loss: beyond k sigmas the IRLS weight k / |z|, so one that passed the gate
        // by a little moves the state by k sigmas' worth at most
        w = o_.huberK / z;
    } else if (o_.robustLoss == TrackerOptions::RobustLoss::Mixture) {
        // a Gaussian and a uniform over the span of what the sensor can read: w is the
        // probability that this one is no gross error
        const double e = o_.outlierShare;
        const double inlier = (1 - e) * std::exp(-0.5 * z * z) / std::sqrt(2 * M_PI * in.S);
        w = inlier / (inlier + e / span);
        if (w < 1e-6) return false;
    }
    if (w < 1) {
        R += in.S / w - in.S;
        in.S /= w;
    }
    const Eigen::VectorXd K = cov_ * in.H.transpose() / in.S;
    const Eigen::MatrixXd IKH = Eigen::MatrixXd::Identity(state_.size(), state_.size()) - K * in.H;
    // Joseph form keeps the covariance symmetric positive definite.
    cov_ = IKH * cov_ * IKH.transpose() + K * K.transpose() * R;
    state_ += K * in.value;
    syncPdf();
    return true;
}

Eigen::MatrixXd BeaconTracker::fixBiasSensitivity(const Eigen::Vector3d& fix,
                                                  const std::vector<Range>& used) const {
    // A fix takes its ranges as unbiased, so its error is the bias carried through the
    // solver: fix - true = A G e, with A = (J^T J)^-1 J^T the least-squares map from range
    // errors to position and G the ranges' dependence on the bias states e.
    const Eigen::Index extras = state_.size() - 3;
    Eigen::MatrixXd J(used.size(), 2), G = Eigen::MatrixXd::Zero(used.size(), extras);
    for (size_t k = 0; k < used.size(); ++k) {
        const Vector3d d = fix - used[k].beacon;
        const double distance = std::max(d.norm(), 1e-9);
        J.row(Eigen::Index(k)) = d.head<2>().transpose() / distance;
        if (scaleIndex_) G(Eigen::Index(k), *scaleIndex_ - 3) = distance;
        const auto it = offsetIndex_.find(used[k].beaconId);
        if (it != offsetIndex_.end()) G(Eigen::Index(k), it->second - 3) = 1;
    }
    const Eigen::Matrix2d JtJ = J.transpose() * J;
    if (extras == 0 || std::abs(JtJ.determinant()) < 1e-12) return Eigen::MatrixXd::Zero(2, extras);
    return JtJ.inverse() * J.transpose() * G;
}

void BeaconTracker::initializeFromFix(const Fix& fix, const std::vector<Range>& used, double phi,
                                      double phiVariance) {
    Matrix3d P = Matrix3d::Zero();
    P.topLeftCorner<2, 2>() = fix.covariance.topLeftCorner<2, 2>();
    P(2, 2) = phiVariance;
    initialize(CPose2D(fix.position.x(), fix.position.y(), phi), P);
    const Eigen::Index extras = state_.size() - 3;
    if (extras == 0 || used.size() < 2) return;
    // The position inherits the bias states' prior through the fix (and its correlation
    // with them) instead of ignoring it: true = fix - A G e.
    const Eigen::MatrixXd AG = fixBiasSensitivity(fix.position, used);
    const Eigen::MatrixXd Se = cov_.bottomRightCorner(extras, extras);
    cov_.topLeftCorner<2, 2>() += AG * Se * AG.transpose();
    cov_.block(0, 3, 2, extras) = -AG * Se;
    cov_.block(3, 0, extras, 2) = cov_.block(0, 3, 2, extras).transpose();
    syncPdf();
}

std::optional<Fix> BeaconTracker::checkingFix(const std::vector<Range>& ranges, size_t needed,
                                              std::vector<Range>& used) {
    // the ranges as the filter believes them to be: its bias estimates taken out
    const auto f = fixFrom(correctedByBias(ranges), /*robust=*/true, &used, /*counted=*/false);
    if (!f || used.size() < needed) return std::nullopt;
    return f;
}

std::vector<BeaconTracker::Range> BeaconTracker::consistentSubset(
    const std::vector<Range>& ranges) {
    // two ranges to spare, or as many as the map has beacons (three UWB anchors: one)
    const size_t needed = std::max(unknowns() + 1, std::min(unknowns() + 2, map_.size()));
    std::vector<Range> used;
    if (!checkingFix(ranges, needed, used)) return {};  // nothing to check them with: wait
    std::vector<Range> out;
    for (const auto& u : used)
        for (const auto& r : ranges)
            if (r.beaconId == u.beaconId) out.push_back(r);
    return out;
}

std::vector<BeaconTracker::Range> BeaconTracker::correctedByBias(
    const std::vector<Range>& ranges) const {
    std::vector<Range> corrected = ranges;
    const double scale = scaleIndex_ ? state_(*scaleIndex_) : 0.0;
    for (auto& r : corrected) {
        const auto it = offsetIndex_.find(r.beaconId);
        r.range = (r.range - (it != offsetIndex_.end() ? state_(it->second) : 0.0)) / (1 + scale);
    }
    return corrected;
}

void BeaconTracker::noteGate(int beacon, bool accepted) {
    // A beacon whose ranges fail the gate again and again while the filter holds (late
    // echoes are random; ten in a row of one beacon are not) has an offset estimate gone
    // wrong, most likely from a long echo taken in before the filter had settled: it is
    // opened to its prior again, so its good ranges count and correct it.
    const auto offset = offsetIndex_.find(beacon);
    if (offset == offsetIndex_.end()) return;
    auto& history = gateHistory_[beacon];
    history.push_back(!accepted);
    if (history.size() > kGateWindow) history.pop_front();
    if (history.size() < kGateWindow ||
        size_t(std::count(history.begin(), history.end(), true)) < kGateReopen)
        return;
    const Eigen::Index i = offset->second;
    cov_(i, i) += o_.biasSpread * o_.biasSpread;
    history.clear();
    ++stats_.offsetsReopened;
}

bool BeaconTracker::disagreesWithFix(const std::vector<Range>& ranges) {
    // no consistent fix, or one that could not have dropped a bad range (leave-one-out
    // needs two ranges to spare): no evidence either way
    std::vector<Range> used;
    const auto f = checkingFix(ranges, unknowns() + 2, used);
    if (!f) return false;
    // fix - filter ~ N(0, filter's + fix's own + the fix's share of the bias uncertainty)
    const Eigen::Index extras = state_.size() - 3;
    Eigen::Matrix2d C = cov_.topLeftCorner<2, 2>() + f->covariance.topLeftCorner<2, 2>();
    if (extras > 0) {
        const Eigen::MatrixXd AG = fixBiasSensitivity(f->position, used);
        C += AG * cov_.bottomRightCorner(extras, extras) * AG.transpose();
    }
    const Eigen::Vector2d v = f->position.head<2>() - state_.head<2>();
    return v.dot(C.ldlt().solve(v)) > divergenceGate_;
}

std::optional<CPose2D> BeaconTracker::bootstrap(const std::vector<Range>& ranges) {
    std::vector<Range> used;
    const auto f = fixFrom(ranges, /*robust=*/true, &used);
    if (!f) return std::nullopt;
    const Eigen::Vector2d p = f->position.head<2>();
    if (!lastOdometry_) {
        // heading unobservable without odometry; ranges fix position only
        initializeFromFix(*f, used, 0.0, M_PI * M_PI);
        return CPose2D(p.x(), p.y(), 0.0);
    }
    const CPose2D odo = *lastOdometry_;
    // A fix may be wrong (two late echoes that agree with each other): it must fit, with
    // the others, the odometry's path moved rigidly into the world (its noise, plus the
    // few centimetres the ranges' unknown bias moves every fix alike).
    if (f->gdop > kMaxBootstrapGdop) return std::nullopt;  // too poor a geometry to start from
    // each fix within 3 sigma of the aligned path, plus the few centimetres the ranges'
    // unknown bias moves every fix alike
    const double sigma = std::sqrt(f->covariance.topLeftCorner<2, 2>().trace());
    track_.add({p, odo, 3.0 * sigma + 0.03});
    if (const auto T = track_.align(o_.bootstrapBaseline)) {
        // the fixes fit the odometry's path: the pose now is the odometry's, moved by T
        const double rotation = std::atan2((*T)(1, 0), (*T)(0, 0));
        Fix start = *f;
        start.position.head<2>() = T->topLeftCorner<2, 2>() * Eigen::Vector2d(odo.x(), odo.y()) +
                                   T->topRightCorner<2, 1>();
        // the rotation of a line of fixes of error sigma is sigma / sqrt(spread); three
        // range sigmas and 0.05 rad allow for the ranges' bias bending the line
        const double sigmaPhi = 3.0 * o_.rangeSigma / std::sqrt(track_.odometrySpread()) + 0.05;
        initializeFromFix(start, used, mrpt::math::wrapToPi(odo.phi() + rotation),
                          sigmaPhi * sigmaPhi);
        track_.clear();
        return pdf_.mean;
    }
    // Not yet localized: the fix is the estimate if it agrees with every earlier one, with
    // the heading of the last time the track was held. A lone fix may be a mirror image made
    // of two long echoes: it waits for a second.
    if (!track_.newestAgrees()) return std::nullopt;
    return CPose2D(p.x(), p.y(), mrpt::math::wrapToPi(odo.phi() + headingOffset_));
}

std::vector<BeaconTracker::Range> BeaconTracker::meanPerBeacon(std::vector<Range> ranges) {
    // a beacon fired several times in one epoch (shots_per_beacon): one range, their mean
    std::vector<Range> out;
    std::vector<int> count;
    for (const auto& r : ranges) {
        size_t i = 0;
        while (i < out.size() && out[i].beaconId != r.beaconId) ++i;
        if (i == out.size()) {
            out.push_back(r);
            count.push_back(1);
        } else {
            out[i].range += r.range;
            ++count[i];
        }
    }
    for (size_t i = 0; i < out.size(); ++i) {
        out[i].range /= count[i];
        out[i].shots = count[i];
    }
    return out;
}

std::optional<Fix> BeaconTracker::fixOnly(const mrpt::obs::CObservationBeaconRanges& obs) {
    ++stats_.epochs;
    const auto usable = usableRanges(obs);
    stats_.rangesUsed += usable.size();
    const auto ranges = meanPerBeacon(usable);
    auto f = fixFrom(ranges, /*robust=*/false);
    // Each range less the delay its shot is expected to carry from where the fix puts the
    // receiver; the delay changes slowly with distance, so two refits settle it.
    for (int pass = 0; f && o_.rangeDelay && pass < 2; ++pass) {
        auto corrected = ranges;
        for (auto& r : corrected) {
            const auto delay = o_.rangeDelay(r.beaconId, r.beacon, f->position);
            r.range -= delay.mean;
            // a weak burst's delay jitters with the fading: trust its range less
            if (o_.jitterWeights)
                r.sigma =
                    std::sqrt((o_.rangeSigma * o_.rangeSigma + delay.sd * delay.sd) / r.shots);
        }
        if (auto g = fixFrom(corrected, /*robust=*/false, nullptr, /*counted=*/false)) f = g;
    }
    return f;
}

void BeaconTracker::predictToTime(double t) {
    const double dt = lastT_ ? std::max(0.0, t - *lastT_) : 0.0;
    if (!lastOdometry_) {  // no odometry in this log: a random walk
        const double q = o_.randomWalkSigma * o_.randomWalkSigma * dt;
        cov_(0, 0) += q;
        cov_(1, 1) += q;
    }
    for (const auto& [id, i] : offsetIndex_) cov_(i, i) += o_.biasDrift * o_.biasDrift * dt;
    lastT_ = t;
}

bool BeaconTracker::lostBySingleMeasurements(double nis) {
    recentGated_.push_back(nis > kLostNis);
    if (recentGated_.size() > kLostWindow) recentGated_.pop_front();
    if (recentGated_.size() < kLostWindow ||
        size_t(std::count(recentGated_.begin(), recentGated_.end(), true)) < kLostFar)
        return false;
    recentGated_.clear();
    return true;
}

void BeaconTracker::restart() {
    // (without odometry there is no heading to keep: the estimates meanwhile say 0)
    if (lastOdometry_) headingOffset_ = state_(2) - lastOdometry_->phi();
    // the particles about the lost pose, as wide as the odometry may have drifted; the
    // sightings' own draws find the pose if it is farther
    const double sxy = std::max(2.0, 3.0 * std::sqrt(cov_(0, 0) + cov_(1, 1)));
    const double sphi = std::min(M_PI, std::max(0.5, 3.0 * std::sqrt(cov_(2, 2))));
    start_.seedAround(pdf_.mean, sxy, sphi);
    pendingStartMotion_ = CPose2D();
    lastStartT_ = lastT_;
    initialized_ = false;
    track_.clear();
    epochsLost_ = 0;
    recentGated_.clear();
    ++stats_.resets;
}

bool BeaconTracker::feedStart(double t, const std::vector<Sighting>& seen) {
    startIfGiven();
    if (initialized_ || seen.empty()) return false;
    if (!lastOdometry_ && lastStartT_) start_.onTime(t - *lastStartT_);
    lastStartT_ = t;
    start_.onOdometry(pendingStartMotion_);  // the particles move once per sighting
    pendingStartMotion_ = CPose2D();
    for (const auto& s : seen) start_.onSighting(s);
    const auto start = start_.converged(lastOdometry_.has_value());
    if (!start) return false;
    initialize(start->mean, start->cov);
    lastT_ = t;
    start_.clear();
    track_.clear();
    recentGated_.clear();
    ++stats_.particleStarts;
    return true;
}

std::optional<CPose2D> BeaconTracker::onSightings(double t, const std::vector<Sighting>& seen) {
    if (!initialized_) {
        size_t ranges = 0, bearings = 0;
        for (const auto& s : seen) ranges += bool(s.range), bearings += bool(s.bearing);
        stats_.rangesReceived += ranges, stats_.bearingsReceived += bearings;
        if (!feedStart(t, seen)) return std::nullopt;
        stats_.rangesUsed += ranges, stats_.bearingsUsed += bearings;  // all went to the start
        return pdf_.mean;
    }
    predictToTime(t);
    for (const auto& s : seen) {
        bool lost = false;
        if (s.range) {
            ++stats_.rangesReceived;
            const Range r{s.beacon, s.sensorOnRobot, *s.range, s.beaconId};
            const double nis = normalisedSquare(innovationOf(r));
            const bool accepted = updateWithRange(r, gate_);
            accepted ? ++stats_.rangesUsed : ++stats_.rangesGated;
            noteGate(s.beaconId, accepted);
            lost = lostBySingleMeasurements(nis);
        }
        if (s.bearing && !lost) {
            ++stats_.bearingsReceived;
            const Innovation in = bearingInnovation(s);
            const bool accepted =
                scalarUpdate(in, s.bearingSigma * s.bearingSigma, gate_, 2 * M_PI);
            accepted ? ++stats_.bearingsUsed : ++stats_.bearingsGated;
            lost = lostBySingleMeasurements(normalisedSquare(in));
        }
        if (lost) {
            restart();
            return std::nullopt;
        }
    }
    return pdf_.mean;
}

std::optional<CPose2D> BeaconTracker::onRanges(double t,
                                               const mrpt::obs::CObservationBeaconRanges& obs) {
    ++stats_.epochs;
    const auto ranges = usableRanges(obs);
    startIfGiven();
    if (!initialized_) {
        lastT_ = t;
        return bootstrap(ranges);
    }
    predictToTime(t);

    // Started from a given pose, the filter has a prior but no evidence yet: its gate is
    // wide enough to let two long echoes in, and the bias states would keep them. Until one
    // epoch's ranges agree with each other (a fix with two ranges to spare, one bad range
    // left out at most), it takes in no range; then only that epoch's agreeing ones.
    std::vector<Range> agreeing = ranges;
    if (!settled_) {
        agreeing = consistentSubset(ranges);
        settled_ = !agreeing.empty();
    }
    // The most consistent ranges first: they tighten the state before a doubtful one is
    // gated, so a long echo is judged against the epoch's good ranges, not the prior.
    std::vector<std::pair<double, const Range*>> order;
    for (const auto& r : agreeing) {
        const Innovation in = innovationOf(r);
        order.emplace_back(in.valid ? in.value * in.value / in.S : HUGE_VAL, &r);
    }
    std::stable_sort(order.begin(), order.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    size_t used = 0;
    bool lostBySingles = false;
    for (const auto& [nis, r] : order) {
        const bool accepted = updateWithRange(*r, gate_);
        accepted ? ++used : ++stats_.rangesGated;
        noteGate(r->beaconId, accepted);
        lostBySingles = lostBySingleMeasurements(nis) || lostBySingles;
    }
    stats_.rangesUsed += used;
    // Lost track: every range rejected, or consistent fixes (ranges corrected by the bias
    // estimates) far outside the filter's covariance, resetAfter epochs in a row.
    if (used == 0 && ranges.size() >= 3) {
        ++epochsLost_;
    } else if (ranges.size() >= 3) {
        epochsLost_ = disagreesWithFix(ranges) ? epochsLost_ + 1 : 0;
    }
    if (epochsLost_ >= o_.resetAfter || lostBySingles) {
        // lost: start again, as at the beginning, from fixes that fit the odometry's path
        // or from the particles
        restart();
        return bootstrap(ranges);
    }
    return pdf_.mean;
}

}  // namespace mrloc::beacons
