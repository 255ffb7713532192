#include <mrloc/beacons/StartupTrack.h>
#include <mrloc/common/RigidFit.h>

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

namespace mrloc::beacons {

namespace {
Eigen::Vector2d odometryOf(const StartupTrack::Point& p) {
    return {p.odometry.x(), p.odometry.y()};
}
}  // namespace

void StartupTrack::add(const Point& p) {
    points_.push_back(p);
    if (points_.size() > kMaxPoints) points_.pop_front();
}

std::optional<Eigen::Matrix3d> StartupTrack::align(double baseline) {
    const size_t n = points_.size();
    if (n < kMinAgreeing) return std::nullopt;
    const auto fits = [&](const Eigen::Matrix3d& T, size_t i) {
        const Eigen::Vector2d aligned =
            T.topLeftCorner<2, 2>() * odometryOf(points_[i]) + T.topRightCorner<2, 1>();
        return (aligned - points_[i].fix).norm() <= points_[i].tolerance;
    };
    // consensus: a pair far enough apart gives the rotation (the direction of travel in the
    // world against the odometry's) and the translation (their midpoints)
    std::vector<size_t> best;
    for (size_t i = 0; i < n; ++i)
        for (size_t j = i + 1; j < n; ++j) {
            const Eigen::Vector2d odo = odometryOf(points_[j]) - odometryOf(points_[i]);
            const Eigen::Vector2d fix = points_[j].fix - points_[i].fix;
            if (odo.norm() < 0.5 * baseline) continue;
            const double angle = std::atan2(fix.y(), fix.x()) - std::atan2(odo.y(), odo.x());
            Eigen::Matrix3d T = Eigen::Matrix3d::Identity();
            T.topLeftCorner<2, 2>() = Eigen::Rotation2Dd(angle).toRotationMatrix();
            T.topRightCorner<2, 1>() =
                0.5 * (points_[i].fix + points_[j].fix) -
                T.topLeftCorner<2, 2>() * 0.5 * (odometryOf(points_[i]) + odometryOf(points_[j]));
            std::vector<size_t> agreeing;
            for (size_t k = 0; k < n; ++k)
                if (fits(T, k)) agreeing.push_back(k);
            if (agreeing.size() > best.size()) best = agreeing;
        }
    if (best.size() < kMinAgreeing || 2 * best.size() < n + 1) return std::nullopt;
    Eigen::Matrix2Xd from(2, best.size()), to(2, best.size());
    for (size_t k = 0; k < best.size(); ++k) {
        from.col(Eigen::Index(k)) = odometryOf(points_[best[k]]);
        to.col(Eigen::Index(k)) = points_[best[k]].fix;
    }
    if ((from.col(from.cols() - 1) - from.col(0)).norm() < baseline) return std::nullopt;
    const Eigen::Matrix3d T = common::rigidFit2D(from, to);
    for (size_t k : best)
        if (!fits(T, k)) return std::nullopt;
    std::deque<Point> kept;
    for (size_t k : best) kept.push_back(points_[k]);
    points_ = std::move(kept);
    return T;
}

bool StartupTrack::newestAgrees() const {
    if (points_.size() < 2) return false;
    const Point& now = points_.back();
    for (size_t i = 0; i + 1 < points_.size(); ++i) {
        const Point& then = points_[i];
        const double odometry = (odometryOf(now) - odometryOf(then)).norm();
        // both fixes' tolerances, and 5 % of the distance for the odometry's own error
        const double tolerance = now.tolerance + then.tolerance + 0.05 * odometry;
        if (std::abs((now.fix - then.fix).norm() - odometry) > tolerance) return false;
    }
    return true;
}

double StartupTrack::odometrySpread() const {
    if (points_.empty()) return 0;
    Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
    for (const auto& p : points_) centroid += odometryOf(p);
    centroid /= double(points_.size());
    double spread = 0;
    for (const auto& p : points_) spread += (odometryOf(p) - centroid).squaredNorm();
    return spread;
}

}  // namespace mrloc::beacons
