#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/DataFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/Trajectory.h>
#include <mrpt/core/format.h>
#include <mrpt/math/CQuaternion.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/system/datetime.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace mrloc::common {

void saveTum(const std::string& path, const Trajectory& traj) {
    std::string out = "# t x y z qx qy qz qw\n";
    char line[256];
    for (const auto& p : traj) {
        if (!std::isfinite(p.t) || !std::isfinite(p.pose.x()) || !std::isfinite(p.pose.y()) ||
            !std::isfinite(p.pose.z()) || !std::isfinite(p.pose.yaw()))
            throw Error(
                mrpt::format("%s: the pose at t = %.6f s is not finite: no NaN is "
                             "written",
                             path.c_str(), p.t));
        mrpt::math::CQuaternionDouble q;
        p.pose.getAsQuaternion(q);
        std::snprintf(line, sizeof(line), "%.9f %.6f %.6f %.6f %.9f %.9f %.9f %.9f\n", p.t,
                      p.pose.x(), p.pose.y(), p.pose.z(), q.x(), q.y(), q.z(), q.r());
        out += line;
    }
    writeFileAtomically(path, out);
}

double stampSeconds(mrpt::Clock::time_point stamp) {
    // MRPT's ticks are 100 ns from 1601 (Windows' FILETIME); 1970 is this many after
    constexpr int64_t kTicksAt1970 = 116444736000000000LL;
    return double(stamp.time_since_epoch().count() - kTicksAt1970) / 1e7;
}

std::string timeInWords(double seconds) {
    // MRPT's date text wraps before 1970 (the year 60425), as its toDouble does
    if (!std::isfinite(seconds) || seconds < 0) return "before 1970";
    if (isRelativeTime(seconds)) return mrpt::format("t = %.3f s (relative clock)", seconds);
    return mrpt::system::dateTimeToString(mrpt::Clock::fromDouble(seconds)) + " UTC";
}

void checkTrajectoryPose(double t, double x, double y, double z, const std::string& where) {
    if (!std::isfinite(t) || std::abs(t) > TrajectoryLimits::kMaxTime)
        throw Error(where + ": time " + mrpt::format("%g", t) + " s is not within +/-1e11 s");
    for (const double v : {x, y, z})
        if (!std::isfinite(v) || std::abs(v) > TrajectoryLimits::kMaxCoordinate)
            throw Error(where + ": position (" + mrpt::format("%g, %g, %g", x, y, z) +
                        ") m is not within 1,000 km of the origin");
}

std::optional<mrpt::math::CQuaternionDouble> unitQuaternion(double w, double x, double y,
                                                            double z, double minNorm) {
    const double big = std::max({std::abs(w), std::abs(x), std::abs(y), std::abs(z)});
    if (!(big > 0)) return std::nullopt;
    w /= big, x /= big, y /= big, z /= big;
    const double unit = std::sqrt(w * w + x * x + y * y + z * z);  // in [1, 2]
    if (big * unit < minNorm) return std::nullopt;
    return mrpt::math::CQuaternionDouble(w / unit, x / unit, y / unit, z / unit);
}

Trajectory loadTum(const std::string& path) {
    checkReadableFile(path, "trajectory", TrajectoryLimits::kMaxBytes);
    std::ifstream in(path);
    if (!in) throw Error("trajectory " + path + ": cannot open");
    Trajectory traj;
    std::string line;
    for (int lineNo = 1; std::getline(in, line); ++lineNo) {
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '#') continue;
        std::istringstream s(line);
        double v[8];
        for (double& x : v) {
            if (!(s >> x) || !std::isfinite(x))
                throw Error("trajectory " + path + ":" + std::to_string(lineNo) +
                            ": expected 't x y z qx qy qz qw'");
        }
        const std::string where = "trajectory " + path + ":" + std::to_string(lineNo);
        checkTrajectoryPose(v[0], v[1], v[2], v[3], where);
        if (traj.size() >= TrajectoryLimits::kMaxPoses)
            throw Error(where + ": more than 2,000,000 poses in one trajectory");
        // normalized before MRPT sees it (found by fuzz_json_readers: a quaternion off unit
        // norm ended in MRPT's words); under 1e-6 it is a zero quaternion, refused
        const auto q = unitQuaternion(v[7], v[4], v[5], v[6], 1e-6);
        if (!q) throw Error(where + ": zero quaternion");
        if (!traj.empty() && v[0] < traj.back().t)
            throw Error("trajectory " + path + ":" + std::to_string(lineNo) +
                        ": time goes backwards");
        traj.push_back({v[0], mrpt::poses::CPose3D(*q, v[1], v[2], v[3])});
    }
    return traj;
}

std::optional<mrpt::poses::CPose3D> interpolate(const Trajectory& traj, double t) {
    if (traj.empty() || t < traj.front().t || t > traj.back().t) return std::nullopt;
    auto hi = std::lower_bound(traj.begin(), traj.end(), t,
                               [](const StampedPose& p, double time) { return p.t < time; });
    if (hi->t == t || hi == traj.begin()) return hi->pose;
    return interpolateBetween(*(hi - 1), *hi, t);
}

mrpt::poses::CPose3D interpolateBetween(const StampedPose& lo, const StampedPose& hi, double t) {
    const double a = (t - lo.t) / (hi.t - lo.t);
    const auto& p0 = lo.pose;
    const auto& p1 = hi.pose;
    const double yaw = p0.yaw() + a * mrpt::math::wrapToPi(p1.yaw() - p0.yaw());
    return mrpt::poses::CPose3D(p0.x() + a * (p1.x() - p0.x()), p0.y() + a * (p1.y() - p0.y()),
                                p0.z() + a * (p1.z() - p0.z()), yaw, p0.pitch(), p0.roll());
}

Trajectory carriedByOdometry(const mrpt::poses::CPose3D& pose, double t0,
                             const Trajectory& odometry) {
    Trajectory out{{t0, pose}};
    const auto atT0 = interpolate(odometry, t0);
    if (!atT0) return out;
    const mrpt::poses::CPose3D fromT0 = -*atT0;
    for (const auto& reading : odometry)
        if (reading.t > t0 + 1e-6) out.push_back({reading.t, pose + (fromT0 + reading.pose)});
    return out;
}

std::string groundTruthPath(const std::string& rawlogPath, const std::string& robot) {
    std::string stem = rawlogPath;
    const std::string ext = ".rawlog";
    if (stem.size() > ext.size() && stem.compare(stem.size() - ext.size(), ext.size(), ext) == 0)
        stem.resize(stem.size() - ext.size());
    return stem + "." + robot + ".gt.txt";
}

}  // namespace mrloc::common

namespace mrloc::common {

void saveCovariances(const std::string& path, const CovarianceTrack& track) {
    std::ostringstream out;
    out << "# t xx xy xphi yy yphi phiphi (the covariance of x, y, phi: m^2, m rad, rad^2)\n";
    for (const auto& c : track) {
        out << formatNumber(c.t);
        for (const auto& [i, j] : {std::pair{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}})
            out << " " << formatNumber(c.cov(i, j));
        out << "\n";
    }
    writeFileAtomically(path, out.str());
}

CovarianceTrack loadCovariances(const std::string& path) {
    CovarianceTrack track;
    for (const auto& line : readDataLines(path)) {
        line.expectFields(7);
        StampedCovariance c;
        c.t = line.number(0);
        size_t k = 1;
        for (const auto& [i, j] : {std::pair{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}}) {
            c.cov(i, j) = c.cov(j, i) = line.number(k++);
        }
        track.push_back(c);
    }
    return track;
}

std::optional<mrpt::poses::CPose3D> startPoseOf(const Trajectory& truth, double t) {
    auto start = interpolate(truth, t);
    if (!start) return start;
    const bool positionsOnly = std::all_of(truth.begin(), truth.end(), [](const StampedPose& p) {
        return p.pose.yaw() == 0 && p.pose.pitch() == 0 && p.pose.roll() == 0;
    });
    if (!positionsOnly) return start;
    for (const auto& p : truth)
        if (p.t >= t && std::hypot(p.pose.x() - start->x(), p.pose.y() - start->y()) > 0.3) {
            start->setYawPitchRoll(std::atan2(p.pose.y() - start->y(), p.pose.x() - start->x()), 0,
                                   0);
            return start;
        }
    return start;  // it never moves 0.3 m: any heading will do
}

}  // namespace mrloc::common
