// Plain-text sonar logs as the Udacity RoboND occupancy-grid exercise ships them: a measurement
// file (time, one range per sonar) and a pose file (time, x, y, heading). The units are
// options; the time's is inferred from the poses' speed when not given (doc/import.md).
#include <mrloc/common/Error.h>
#include <mrloc/common/Names.h>
#include <mrloc/logimport/Format.h>
#include <mrloc/logimport/TextLog.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CObservationRange.h>

#include <algorithm>
#include <cmath>

namespace mrloc::logimport {

namespace {

struct PoseLine {
    double t, x, y, heading;  // in the file's units
    std::string where;
};

/** A unit's name and its size in SI units (m, rad, s). */
using Unit = std::pair<const char*, double>;
const std::vector<Unit> kTimeUnits{{"s", 1}, {"ms", 1e-3}, {"us", 1e-6}};

Unit unitOf(const std::string& key, const std::string& value, const std::vector<Unit>& units) {
    std::string names;
    for (const auto& unit : units) {
        if (value == unit.first) return unit;
        names += (names.empty() ? "" : ", ") + std::string(unit.first);
    }
    throw Error("--opt " + key + "=" + common::printable(value) + ": expected one of " + names);
}

/** The time unit: given, or the one of s, ms, us under which the robot's median speed over
 *  its moving steps is a ground robot's (0.02 to 3 m/s) and the other two's is not. */
Unit timeUnit(const std::string& option, const std::vector<PoseLine>& poses, double metres,
              const std::string& path) {
    if (option != "auto") return unitOf("time_unit", option, kTimeUnits);
    std::vector<double> rates;  // distance per time unit, while moving
    for (size_t i = 1; i < poses.size(); ++i) {
        const double d = std::hypot(poses[i].x - poses[i - 1].x, poses[i].y - poses[i - 1].y);
        const double dt = poses[i].t - poses[i - 1].t;
        if (d > 0 && dt > 0) rates.push_back(d * metres / dt);
    }
    if (rates.size() < 5)
        throw Error(path +
                    ": the robot hardly moves, so the time unit cannot be inferred: give "
                    "--opt time_unit=s|ms|us");
    std::nth_element(rates.begin(), rates.begin() + rates.size() / 2, rates.end());
    const double perUnit = rates[rates.size() / 2];
    std::vector<Unit> fits;
    for (const auto& unit : kTimeUnits)
        if (const double speed = perUnit / unit.second; speed >= 0.02 && speed <= 3)
            fits.push_back(unit);
    if (fits.size() != 1)
        throw Error(path + mrpt::format(": the time unit cannot be inferred (median speed %g m "
                                        "per time unit): give --opt time_unit=s|ms|us",
                                        perUnit));
    return fits[0];
}

void convertSonarText(const ImportRequest& req, ImportOutput& out) {
    const auto& o = req.options;
    const std::string robot = o.text("robot");
    common::checkRobotName(robot, "--opt robot");
    const std::vector<double> bearings = o.numbers("bearings");
    if (bearings.empty())
        throw Error(
            "format 'sonar-text' needs the sonars' bearings: --opt bearings=b1,b2,... "
            "(degrees, counter-clockwise from the robot's front)");
    if (bearings.size() > 256) throw Error("--opt bearings: more than 256 sonars");
    const double metres =
        unitOf("length_unit", o.text("length_unit"), {{"m", 1}, {"cm", 0.01}, {"mm", 0.001}})
            .second;
    const double radians = unitOf("heading_unit", o.text("heading_unit"),
                                  {{"rad", 1}, {"deg", M_PI / 180}, {"decideg", M_PI / 1800}})
                               .second;
    const double minRange = o.number("min_range"), maxRange = o.number("max_range");
    const double cone = mrpt::DEG2RAD(o.number("cone_deg")), ring = o.number("ring_radius");
    const double height = o.number("height");
    if (!(minRange >= 0 && minRange < maxRange && maxRange <= 1e4))
        throw Error("--opt min_range / max_range: need 0 <= min_range < max_range <= 10000 m");
    if (!(cone > 0 && cone < M_PI)) throw Error("--opt cone_deg: need 0 < cone_deg < 180");
    if (!(ring >= 0 && ring <= 10) || std::abs(height) > 10)
        throw Error("--opt ring_radius / height: need 0 to 10 m");
    const std::string posesAre = o.text("poses_are");
    if (posesAre != "both" && posesAre != "odometry" && posesAre != "truth")
        throw Error("--opt poses_are=" + common::printable(posesAre) +
                    ": expected both, odometry or truth");

    std::vector<PoseLine> poses;
    {
        TextLog log(req.inputs[1], "sonar-text pose file");
        TimeOrder order;
        while (log.next()) {
            log.expectExactly(4, "time x y heading");
            PoseLine p{log.number(0, "time"), log.number(1, "x"), log.number(2, "y"),
                       log.number(3, "heading"), log.where()};
            order.check(log, "poses", p.t);
            if (std::abs(p.x * metres) > 1e6 || std::abs(p.y * metres) > 1e6)
                log.fail("a pose beyond 1000 km");
            poses.push_back(p);
        }
        if (poses.empty()) throw Error(req.inputs[1] + ": no pose");
    }
    const Unit time = timeUnit(o.text("time_unit"), poses, metres, req.inputs[1]);
    const double seconds = time.second;
    if (!o.given("time_unit"))
        out.note(std::string("time unit inferred from the poses' speed: ") + time.first);

    size_t nextPose = 0;
    const auto emitPosesUpTo = [&](double t) {
        for (; nextPose < poses.size() && poses[nextPose].t <= t; ++nextPose) {
            const PoseLine& p = poses[nextPose];
            const mrpt::poses::CPose2D pose(p.x * metres, p.y * metres, p.heading * radians);
            if (posesAre != "truth") {
                auto obs = mrpt::obs::CObservationOdometry::Create();
                obs->sensorLabel = robot + ".odometry";
                obs->timestamp = mrpt::Clock::fromDouble(p.t * seconds);
                obs->odometry = pose;
                out.add(obs, p.where);
            }
            if (posesAre != "odometry")
                out.addGroundTruth(robot, p.t * seconds, mrpt::poses::CPose3D(pose), p.where);
        }
    };
    TextLog log(req.inputs[0], "sonar-text measurement file");
    TimeOrder order;
    std::vector<size_t> noEcho(bearings.size());
    while (log.next()) {
        log.expectExactly(1 + bearings.size(), "time and one range per bearing of --opt bearings");
        const double t = log.number(0, "time");
        order.check(log, "measurements", t);
        emitPosesUpTo(t);
        auto obs = mrpt::obs::CObservationRange::Create();
        obs->sensorLabel = robot + ".sonar";
        obs->timestamp = mrpt::Clock::fromDouble(t * seconds);
        obs->minSensorDistance = float(minRange);
        obs->maxSensorDistance = float(maxRange);
        obs->sensorConeApperture = float(cone);
        for (size_t i = 0; i < bearings.size(); ++i) {
            const double r = log.number(1 + i, "range") * metres;
            if (r < 0) log.fail(mrpt::format("a negative range (sonar %zu)", i + 1));
            mrpt::obs::CObservationRange::TMeasurement m;
            m.sensorID = uint16_t(i);
            const double b = mrpt::DEG2RAD(bearings[i]);
            m.sensorPose =
                mrpt::math::TPose3D(ring * std::cos(b), ring * std::sin(b), height, b, 0, 0);
            // outside the valid band (a max-range 5110 mm, a ringing 0) is MRPT's "no echo"
            const bool valid = r >= minRange && r <= maxRange;
            if (!valid) ++noEcho[i];
            m.sensedDistance = valid ? float(r) : 0.0f;
            obs->sensedData.push_back(m);
        }
        out.add(obs, log.where());
    }
    emitPosesUpTo(INFINITY);
    std::string counts;
    for (size_t i = 0; i < noEcho.size(); ++i)
        counts += mrpt::format("%s%zu", i ? " " : "", noEcho[i]);
    out.note("readings outside [min_range, max_range] written as no echo (0), per sonar: " +
             counts);
}

}  // namespace

void registerSonarText(FormatRegistry& r) {
    r.add({"sonar-text",
           "a sonar ring's text log (Udacity RoboND layout): measurement lines (time, one range "
           "per sonar) -> CObservationRange (<robot>.sonar, no echo = 0); pose lines (time, x, "
           "y, heading) -> CObservationOdometry (<robot>.odometry) and ground truth",
           "<measurements.txt> <poses.txt>",
           2,
           2,
           {{"bearings", "",
             "the sonars' bearings, degrees counter-clockwise from the front, "
             "in the file's column order (required)"},
            {"robot", "robot", "the robot's name, the labels' first part"},
            {"time_unit", "auto", "s, ms or us; auto: inferred from the poses' speed"},
            {"length_unit", "mm", "m, cm or mm: ranges and positions"},
            {"heading_unit", "decideg", "rad, deg or decideg (tenths of a degree)"},
            {"min_range", "0.17", "m; shorter readings are no echo"},
            {"max_range", "5.0", "m; longer readings are no echo"},
            {"cone_deg", "30", "each sonar's full beam width, degrees"},
            {"ring_radius", "0", "m from the robot's centre to each sonar, along its bearing"},
            {"height", "0", "the sonars' height, m"},
            {"poses_are", "both", "both, odometry or truth: what the pose file is written as"}},
           convertSonarText});
}

}  // namespace mrloc::logimport
