#include <mrloc/beacons/RangeWindow.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <cmath>
#include <vector>

namespace mrloc::beacons {

void RangeWindow::add(double t, const mrpt::obs::CObservationBeaconRanges& obs,
                      const mrpt::poses::CPose2D& odo, const BeaconMap& map) {
    for (const auto& m : obs.sensedData) {
        if (!map.count(m.beaconID) || !std::isfinite(m.sensedDistance)) continue;
        newest_[m.beaconID] = {t, m.sensedDistance, m.sensorLocationOnRobot, odo};
        ++added_;
    }
}

std::optional<mrpt::obs::CObservationBeaconRanges> RangeWindow::epoch(
    double t, const mrpt::poses::CPose2D& now, const BeaconMap& map, size_t needed,
    double span) const {
    struct Row {
        int32_t id;
        double range;
        Eigen::Vector2d q;  ///< the receiver at its reading, in the robot's frame at `now`
        double dz;          ///< receiver height - beacon height
        Eigen::Vector2d b;
        mrpt::poses::CPoint3D sensor;
    };
    std::vector<Row> rows;
    for (const auto& [id, r] : newest_) {
        if (t - r.t > span) continue;
        const auto& b = map.at(id);
        // where the receiver was, seen from the robot now: (now^-1 + odo) + sensor
        const mrpt::poses::CPose2D rel = r.odo - now;
        const auto q = rel.composePoint(mrpt::math::TPoint2D(r.sensor.x(), r.sensor.y()));
        rows.push_back({id, r.range, {q.x, q.y}, r.sensor.z() - b.z, {b.x, b.y}, r.sensor});
    }
    if (rows.empty() || rows.size() < needed) return std::nullopt;

    // Gauss-Newton with Levenberg's damping on s = (x, y, phi): d_i = |p + R(phi) q_i - b_i|
    // (with the height difference); from the beacons' centroid at four headings, the best kept
    const auto distance = [](const Eigen::Vector3d& s, const Row& r, const Eigen::Vector2d& q) {
        const Eigen::Vector2d w = s.head<2>() + Eigen::Rotation2Dd(s[2]) * q;
        return std::sqrt((w - r.b).squaredNorm() + r.dz * r.dz);
    };
    const auto cost = [&](const Eigen::Vector3d& s) {
        double c = 0;
        for (const auto& r : rows) c += std::pow(r.range - distance(s, r, r.q), 2);
        return c;
    };
    Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
    for (const auto& r : rows) centroid += r.b;
    centroid /= double(rows.size());
    Eigen::Vector3d best(centroid.x(), centroid.y(), 0);
    double bestCost = INFINITY;
    for (int k = 0; k < 4; ++k) {
        Eigen::Vector3d s(centroid.x() + 0.1, centroid.y() + 0.1, k * M_PI / 2);
        double lambda = 1e-3, c = cost(s);
        for (int it = 0; it < 50; ++it) {
            Eigen::MatrixXd J(rows.size(), 3);
            Eigen::VectorXd e(rows.size());
            const Eigen::Rotation2Dd R(s[2]), dR(s[2] + M_PI / 2);  // dR: d R(phi) / d phi
            for (size_t i = 0; i < rows.size(); ++i) {
                const auto& r = rows[i];
                const Eigen::Vector2d dw = s.head<2>() + R * r.q - r.b;
                const double d = std::max(1e-9, std::sqrt(dw.squaredNorm() + r.dz * r.dz));
                J.row(i) << dw.x() / d, dw.y() / d, dw.dot(dR * r.q) / d;
                e[i] = r.range - d;
            }
            Eigen::Matrix3d A = J.transpose() * J;
            A.diagonal() += lambda * (A.diagonal().array() + 1e-9).matrix();
            const Eigen::Vector3d step = A.ldlt().solve(J.transpose() * e);
            const double c2 = cost(s + step);
            if (c2 < c) {
                s += step, c = c2, lambda = std::max(1e-9, lambda / 10);
                if (step.head<2>().norm() < 1e-6) break;
            } else {
                lambda *= 10;
                if (lambda > 1e6) break;
            }
        }
        if (c < bestCost) bestCost = c, best = s;
    }

    // each range as read from the receiver's position now (the sensor's own offset)
    mrpt::obs::CObservationBeaconRanges out;
    out.timestamp = mrpt::Clock::fromDouble(t);
    for (const auto& r : rows) {
        const Eigen::Vector2d here(r.sensor.x(), r.sensor.y());
        mrpt::obs::CObservationBeaconRanges::TMeasurement m;
        m.beaconID = r.id;
        m.sensorLocationOnRobot = r.sensor;
        m.sensedDistance = float(r.range + distance(best, r, here) - distance(best, r, r.q));
        out.sensedData.push_back(m);
    }
    return out;
}

}  // namespace mrloc::beacons
