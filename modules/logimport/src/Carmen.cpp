// CARMEN logs (one message per line, "name [contents] ipc_timestamp ipc_hostname
// logger_timestamp"), as CARMEN's writelog.c writes them. MRPT's own CARMEN reader skips SONAR
// lines; this one keeps them. doc/import.md#carmen says what maps to what.
#include <mrloc/common/Error.h>
#include <mrloc/common/Names.h>
#include <mrloc/logimport/Format.h>
#include <mrloc/logimport/TextLog.h>
#include <mrpt/core/format.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CObservationRange.h>

#include <cmath>
#include <map>

namespace mrloc::logimport {

namespace {

using mrpt::poses::CPose2D;

/** The message's time: its ipc_timestamp, third field from the end (the sensor's clock; the
 *  logger's, last, is when it was written). */
double stampOf(const TextLog& log, size_t firstTrailer) {
    log.expectExactly(firstTrailer + 3,
                      "the message, then ipc_timestamp ipc_hostname logger_timestamp");
    return log.number(firstTrailer, "ipc_timestamp");
}

size_t countAt(const TextLog& log, size_t i, const char* name, size_t max) {
    return size_t(log.integer(i, name, 0, long(max)));
}

/** A laser's scan: `n` ranges from field `first`, the beams from `start` over `fov`. */
mrpt::obs::CObservation2DRangeScan::Ptr scanOf(const TextLog& log, size_t first, size_t n,
                                               double fov, double maxRange) {
    auto scan = mrpt::obs::CObservation2DRangeScan::Create();
    scan->aperture = float(fov);
    scan->rightToLeft = true;
    scan->maxRange = float(maxRange);
    scan->resizeScan(n);
    for (size_t i = 0; i < n; ++i) {
        const double r = log.number(first + i, "range");
        if (r < 0 || r > 1e4) log.fail(mrpt::format("range %g m cannot be", r));
        scan->setScanRange(i, float(r));
        // CARMEN writes the maximum range (or more) for no return
        scan->setScanRangeValidity(i, r > 0 && r < maxRange);
    }
    return scan;
}

void convertCarmen(const ImportRequest& req, ImportOutput& out) {
    const std::string robot = req.options.text("robot");
    common::checkRobotName(robot, "--opt robot");
    const double flaserMax = req.options.number("flaser_max_range");
    if (!(flaserMax > 0 && flaserMax <= 1e4)) throw Error("--opt flaser_max_range: 0 to 10000 m");
    TextLog log(req.inputs[0], "CARMEN log");
    TimeOrder order;
    std::map<std::string, size_t> dropped;
    const auto stamped = [&](const mrpt::obs::CObservation::Ptr& obs, const std::string& sensor,
                             double t) {
        order.check(log, sensor, t);
        obs->sensorLabel = robot + "." + sensor;
        obs->timestamp = mrpt::Clock::fromDouble(t);
        out.add(obs, log.where());
    };
    while (log.next()) {
        const std::string type(log.field(0));
        if (type == "ODOM") {
            const double t = stampOf(log, 7);
            auto obs = mrpt::obs::CObservationOdometry::Create();
            obs->odometry = CPose2D(log.number(1, "x"), log.number(2, "y"), log.number(3, "theta"));
            obs->hasVelocities = true;
            obs->velocityLocal = mrpt::math::TTwist2D(log.number(4, "tv"), 0, log.number(5, "rv"));
            stamped(obs, "odometry", t);
        } else if (type == "TRUEPOS") {
            const double t = stampOf(log, 7);
            order.check(log, "truepos", t);
            out.addGroundTruth(
                robot, t,
                mrpt::poses::CPose3D(log.number(1, "true_x"), log.number(2, "true_y"), 0,
                                     log.number(3, "true_theta"), 0, 0),
                log.where());
        } else if (type == "FLASER" || type == "RLASER") {
            // num_readings [ranges] x y theta odom_x odom_y odom_theta: a 180-degree laser
            const size_t n = countAt(log, 1, "num_readings", 100000);
            const double t = stampOf(log, 2 + n + 6);
            auto scan = scanOf(log, 2, n, M_PI, flaserMax);
            const CPose2D laser(log.number(2 + n, "x"), log.number(3 + n, "y"),
                                log.number(4 + n, "theta"));
            const CPose2D odom(log.number(5 + n, "odom_x"), log.number(6 + n, "odom_y"),
                               log.number(7 + n, "odom_theta"));
            scan->sensorPose = mrpt::poses::CPose3D(laser - odom);  // the laser on the robot
            stamped(scan, type == "FLASER" ? "laser" : "rear_laser", t);
        } else if (type == "ROBOTLASER1" || type == "ROBOTLASER2") {
            // laser_type start_angle fov resolution max_range accuracy remission_mode n [ranges]
            // m [remissions] laser_pose(3) robot_pose(3) tv rv forward side turn_axis
            const double start = log.number(2, "start_angle"), fov = log.number(3, "field_of_view");
            const double maxRange = log.number(5, "maximum_range");
            if (!(fov > 0 && fov <= 2 * M_PI)) log.fail(mrpt::format("field of view %g rad", fov));
            if (!(maxRange > 0 && maxRange <= 1e4))
                log.fail(mrpt::format("maximum range %g m", maxRange));
            const size_t n = countAt(log, 8, "num_readings", 100000);
            const size_t m = countAt(log, 9 + n, "num_remissions", 100000);
            const size_t pose = 10 + n + m;
            const double t = stampOf(log, pose + 11);
            auto scan = scanOf(log, 9, n, fov, maxRange);
            const CPose2D laser(log.number(pose, "laser_pose_x"),
                                log.number(pose + 1, "laser_pose_y"),
                                log.number(pose + 2, "laser_pose_theta"));
            const CPose2D body(log.number(pose + 3, "robot_pose_x"),
                               log.number(pose + 4, "robot_pose_y"),
                               log.number(pose + 5, "robot_pose_theta"));
            // the scan's beams are centred on the sensor's front: a start angle other than
            // -fov/2 turns the sensor pose by the difference
            const CPose2D onRobot = laser - body;
            scan->sensorPose = mrpt::poses::CPose3D(onRobot + CPose2D(0, 0, start + fov / 2));
            stamped(scan, type == "ROBOTLASER1" ? "laser" : "laser2", t);
        } else if (type == "SONAR") {
            // cone_angle num_sonars [ranges] [x y theta per sonar]
            const double cone = log.number(1, "cone_angle");
            if (!(cone > 0 && cone < M_PI)) log.fail(mrpt::format("cone angle %g rad", cone));
            const size_t n = countAt(log, 2, "num_sonars", 256);
            const double t = stampOf(log, 3 + 4 * n);
            auto obs = mrpt::obs::CObservationRange::Create();
            obs->sensorConeApperture = float(cone);
            obs->maxSensorDistance = float(req.options.number("sonar_max_range"));
            for (size_t i = 0; i < n; ++i) {
                mrpt::obs::CObservationRange::TMeasurement s;
                s.sensorID = uint16_t(i);
                const size_t o = 3 + n + 3 * i;
                s.sensorPose =
                    mrpt::math::TPose3D(log.number(o, "sonar x"), log.number(o + 1, "sonar y"), 0,
                                        log.number(o + 2, "sonar theta"), 0, 0);
                const double r = log.number(3 + i, "sonar range");
                if (r < 0 || r > 1e4) log.fail(mrpt::format("sonar range %g m cannot be", r));
                // no echo: at or beyond the maximum range -> MRPT's 0
                s.sensedDistance = r < obs->maxSensorDistance ? float(r) : 0.0f;
                obs->sensedData.push_back(s);
            }
            stamped(obs, "sonar", t);
        } else {
            ++dropped[common::printable(type.substr(0, 32))];
        }
    }
    for (const auto& [type, n] : dropped)
        out.note(
            mrpt::format("%zu %s lines left out (no matching MRPT class here)", n, type.c_str()));
}

}  // namespace

void registerCarmen(FormatRegistry& r) {
    r.add({"carmen",
           "CARMEN logs: ODOM -> CObservationOdometry (<robot>.odometry), FLASER/RLASER/"
           "ROBOTLASER1/2 -> CObservation2DRangeScan (<robot>.laser ...), SONAR -> "
           "CObservationRange (<robot>.sonar), TRUEPOS -> ground truth",
           "<log.clf>",
           1,
           1,
           {{"robot", "robot", "the robot's name, the labels' first part"},
            {"flaser_max_range", "81.9", "m; FLASER lines carry no maximum range (SICK LMS: 81.9)"},
            {"sonar_max_range", "5.0", "m; SONAR readings at or beyond it are no echo"}},
           convertCarmen});
}

}  // namespace mrloc::logimport
