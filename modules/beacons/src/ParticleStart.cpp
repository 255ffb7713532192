#include <mrloc/beacons/ParticleStart.h>
#include <mrpt/math/wrap2pi.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace mrloc::beacons {

ParticleStart::ParticleStart(const BeaconMap& map, ParticleStartOptions options,
                             OdometryNoise noise)
    : map_(map), o_(options), noise_(std::move(noise)), rangeSpan_(rangeSpanOf(map_)) {
    rng_.randomize(uint32_t(o_.seed));
}

double ParticleStart::rangeSpanOf(const BeaconMap& map) {
    double extent = 0;
    for (const auto& [i, a] : map)
        for (const auto& [j, b] : map) extent = std::max(extent, std::hypot(a.x - b.x, a.y - b.y));
    return 2 * extent + 20;
}

void ParticleStart::clear() {
    particles_.clear();
    measurements_ = 0;
}

Eigen::Vector2d ParticleStart::sensorAt(const Particle& p, const Eigen::Vector3d& s) const {
    const double c = std::cos(p.phi), sn = std::sin(p.phi);
    return {p.x + c * s.x() - sn * s.y(), p.y + sn * s.x() + c * s.y()};
}

template <class Draw>
void ParticleStart::reseed(size_t count, Draw&& draw) {
    if (particles_.empty()) {
        particles_.resize(kParticles);
        count = kParticles;
    }
    // the redrawn ones take the mean weight: neither favoured nor lost at the next resampling
    double logMean = -INFINITY;
    for (const auto& p : particles_) {
        const double hi = std::max(logMean, p.logWeight);
        if (std::isfinite(hi))
            logMean = hi + std::log(std::exp(logMean - hi) + std::exp(p.logWeight - hi));
    }
    logMean = std::isfinite(logMean) ? logMean - std::log(double(particles_.size())) : 0.0;
    for (size_t k = 0; k < count; ++k) {
        // spread over the cloud, deterministically: every (N / count)-th particle
        Particle& p = particles_[(k * particles_.size()) / count];
        draw(p);
        p.logWeight = logMean;
    }
}

void ParticleStart::seedAround(const mrpt::poses::CPose2D& mean, double sigmaXY, double sigmaPhi) {
    particles_.assign(kParticles, {});
    measurements_ = 0;
    for (auto& p : particles_)
        p = {mean.x() + rng_.drawGaussian1D(0, sigmaXY), mean.y() + rng_.drawGaussian1D(0, sigmaXY),
             mrpt::math::wrapToPi(mean.phi() + rng_.drawGaussian1D(0, sigmaPhi)), 0.0};
}

void ParticleStart::onOdometry(const mrpt::poses::CPose2D& delta) {
    if (particles_.empty()) return;
    const double d = std::hypot(delta.x(), delta.y());
    if (d == 0 && delta.phi() == 0) return;
    // the tracker's odometry noise of the increment, plus a diffusion that keeps the
    // particles apart
    const Eigen::Matrix3d Q = noise_.of(delta);
    const double sxy = std::sqrt(Q(0, 0) + kRougheningXY * kRougheningXY * std::min(d, 1.0));
    const double sphi = std::sqrt(Q(2, 2) + kRougheningPhi * kRougheningPhi *
                                                std::min(d + std::abs(delta.phi()), 1.0));
    for (auto& p : particles_) {
        const double dx = delta.x() + rng_.drawGaussian1D(0, sxy);
        const double dy = delta.y() + rng_.drawGaussian1D(0, sxy);
        const double c = std::cos(p.phi), s = std::sin(p.phi);
        p.x += c * dx - s * dy;
        p.y += s * dx + c * dy;
        p.phi = mrpt::math::wrapToPi(p.phi + delta.phi() + rng_.drawGaussian1D(0, sphi));
    }
}

void ParticleStart::onTime(double dt) {
    if (particles_.empty() || dt <= 0) return;
    const double s = o_.randomWalkSigma * std::sqrt(dt);
    for (auto& p : particles_) {
        p.x += rng_.drawGaussian1D(0, s);
        p.y += rng_.drawGaussian1D(0, s);
    }
}

void ParticleStart::onSighting(const Sighting& m) {
    if (!m.range && !m.bearing) return;
    const double dz = m.sensorOnRobot.z() - m.beacon.z();
    // seeding, or sensor resetting: particles drawn where this sighting puts the robot
    const auto draw = [&](Particle& p) {
        p.phi = rng_.drawUniform(-M_PI, M_PI);
        double horizontal;
        if (m.range) {
            const double r = std::max(0.0, *m.range + rng_.drawGaussian1D(0, m.rangeSigma));
            horizontal = std::sqrt(std::max(0.0, r * r - dz * dz));
        } else {
            horizontal = rng_.drawUniform(0.2, 0.5 * rangeSpan_);
        }
        // a bearing sets the direction from the sensor to the beacon, given the heading
        const double direction =
            m.bearing ? p.phi + m.sensorYaw + *m.bearing + rng_.drawGaussian1D(0, m.bearingSigma)
                      : rng_.drawUniform(-M_PI, M_PI);
        const Eigen::Vector2d sensor(m.beacon.x() - horizontal * std::cos(direction),
                                     m.beacon.y() - horizontal * std::sin(direction));
        const double c = std::cos(p.phi), s = std::sin(p.phi);
        p.x = sensor.x() - (c * m.sensorOnRobot.x() - s * m.sensorOnRobot.y());
        p.y = sensor.y() - (s * m.sensorOnRobot.x() + c * m.sensorOnRobot.y());
    };
    if (particles_.empty())
        reseed(kParticles, draw);
    else
        reseed(size_t(kResetShare * double(particles_.size())), draw);

    // the mixture: the sensor's Gaussian, widened by the particles' spacing, and a uniform
    // part for gross errors (doc/beacons.md)
    const double sr = std::hypot(m.rangeSigma, kRougheningXY);
    const double sb = std::hypot(m.bearingSigma, kRougheningPhi);
    const double rangeFloor = kOutlierShare / rangeSpan_;
    const double bearingFloor = kOutlierShare / (2 * M_PI);
    std::vector<double> logLikelihood(particles_.size(), 0.0);
    for (size_t k = 0; k < particles_.size(); ++k) {
        const auto& p = particles_[k];
        const Eigen::Vector2d sensor = sensorAt(p, m.sensorOnRobot);
        const Eigen::Vector2d to = m.beacon.head<2>() - sensor;
        double l = 0;
        if (m.range) {
            const double z = (*m.range - std::sqrt(to.squaredNorm() + dz * dz)) / sr;
            l +=
                std::log((1 - kOutlierShare) * std::exp(-0.5 * z * z) / (std::sqrt(2 * M_PI) * sr) +
                         rangeFloor);
        }
        if (m.bearing) {
            const double predicted = std::atan2(to.y(), to.x()) - p.phi - m.sensorYaw;
            const double z = mrpt::math::wrapToPi(*m.bearing - predicted) / sb;
            l +=
                std::log((1 - kOutlierShare) * std::exp(-0.5 * z * z) / (std::sqrt(2 * M_PI) * sb) +
                         bearingFloor);
        }
        logLikelihood[k] = l;
    }
    weigh(logLikelihood);
    ++measurements_;
    resampleIfDegenerate();
}

void ParticleStart::weigh(const std::vector<double>& logLikelihood) {
    double top = -INFINITY;
    for (size_t k = 0; k < particles_.size(); ++k) {
        particles_[k].logWeight += logLikelihood[k];
        top = std::max(top, particles_[k].logWeight);
    }
    for (auto& p : particles_) p.logWeight -= top;  // the best at 0: no underflow of all
}

void ParticleStart::resampleIfDegenerate() {
    std::vector<double> w(particles_.size());
    double sum = 0, sumSquares = 0;
    for (size_t k = 0; k < particles_.size(); ++k) sum += w[k] = std::exp(particles_[k].logWeight);
    for (auto& v : w) {
        v /= sum;
        sumSquares += v * v;
    }
    if (1.0 / sumSquares >= 0.5 * double(particles_.size())) return;
    // systematic resampling: one uniform draw, N evenly spaced pointers into the weights
    std::vector<Particle> out;
    out.reserve(particles_.size());
    const double step = 1.0 / double(particles_.size());
    double pointer = rng_.drawUniform(0.0, step), cumulative = w[0];
    size_t k = 0;
    for (size_t n = 0; n < particles_.size(); ++n, pointer += step) {
        while (pointer > cumulative && k + 1 < particles_.size()) cumulative += w[++k];
        out.push_back(particles_[k]);
        out.back().logWeight = 0;
    }
    particles_ = std::move(out);
}

std::optional<ParticleStart::Start> ParticleStart::converged(bool headingKnown) const {
    if (particles_.empty() || measurements_ < kMinMeasurements) return std::nullopt;
    std::vector<double> w(particles_.size());
    double sum = 0;
    for (size_t k = 0; k < particles_.size(); ++k) sum += w[k] = std::exp(particles_[k].logWeight);
    for (auto& v : w) v /= sum;
    // the mode: from the heaviest particle, the mean of those within kModeRadius, thrice (the
    // few particles each sighting redraws on its annulus are far off and must not count)
    const double radius = std::max(kModeRadius, 10 * o_.rangeSigma);
    const auto heaviest = size_t(std::max_element(w.begin(), w.end()) - w.begin());
    Eigen::Vector2d centre(particles_[heaviest].x, particles_[heaviest].y);
    double share = 0;
    for (int pass = 0; pass < 3; ++pass) {
        Eigen::Vector2d m = Eigen::Vector2d::Zero();
        share = 0;
        for (size_t k = 0; k < particles_.size(); ++k)
            if (std::hypot(particles_[k].x - centre.x(), particles_[k].y - centre.y()) <= radius)
                m += w[k] * Eigen::Vector2d(particles_[k].x, particles_[k].y), share += w[k];
        centre = m / share;
    }
    if (share < kModeShare) return std::nullopt;  // another mode still holds weight
    double sc = 0, ss = 0;
    for (size_t k = 0; k < particles_.size(); ++k)
        if (std::hypot(particles_[k].x - centre.x(), particles_[k].y - centre.y()) <= radius)
            sc += w[k] * std::cos(particles_[k].phi), ss += w[k] * std::sin(particles_[k].phi);
    const double mphi = std::atan2(ss, sc);
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (size_t k = 0; k < particles_.size(); ++k) {
        const auto& p = particles_[k];
        if (std::hypot(p.x - centre.x(), p.y - centre.y()) > radius) continue;
        const Eigen::Vector3d e(p.x - centre.x(), p.y - centre.y(),
                                mrpt::math::wrapToPi(p.phi - mphi));
        cov += w[k] / share * e * e.transpose();
    }
    const double positionSd =
        std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(cov.topLeftCorner<2, 2>())
                      .eigenvalues()
                      .maxCoeff());
    if (positionSd > std::max(kConvergedSd, 3 * o_.rangeSigma)) return std::nullopt;
    // the resultant length R of the mode's headings: circular sd sqrt(-2 ln R)
    const double resultant = std::hypot(sc, ss) / share;
    const double phiSd = std::sqrt(-2 * std::log(std::max(resultant, 1e-12)));
    if (headingKnown && phiSd > kConvergedPhiSd) return std::nullopt;
    // the mode's sample covariance understates its spread (resampled copies, the mode's
    // tails cut at its radius): the EKF starts with twice its sd, so that its first
    // sightings can still move it
    cov *= kStartInflation * kStartInflation;
    if (!headingKnown) cov(2, 2) = M_PI * M_PI, cov(0, 2) = cov(2, 0) = cov(1, 2) = cov(2, 1) = 0;
    return Start{mrpt::poses::CPose2D(centre.x(), centre.y(), headingKnown ? mphi : 0.0), cov};
}

}  // namespace mrloc::beacons
