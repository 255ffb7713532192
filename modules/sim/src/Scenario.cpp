#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/IniSection.h>
#include <mrloc/common/Names.h>
#include <mrloc/common/Seeds.h>
#include <mrloc/sim/Scenario.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>
#include <mrpt/math/TSegment2D.h>
#include <mrpt/system/string_utils.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <sstream>

namespace mrloc::sim {

void ScenarioOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& src,
                                         const std::string& section) {
    *this = ScenarioOptions{};  // every key absent takes the struct's default: written once
    common::IniSection s(src, section);
    name = s.text("name", name);
    common::checkName(name, common::configOrigin(src) + ": [" + section + "] name");
    method = s.text("method", method);  // none given: the app finds it from the INI's sections
    seed = (unsigned long)s.integer("seed", long(seed), 0, long(common::kMaxSeed));
    duration = s.real("duration", duration, 1e-3, 1e6);
    dt = s.real("dt", dt, 1e-4, 1.0);
    if (duration / dt > kMaxSteps)
        s.fail("dt", mrpt::format("duration / dt = %.3g simulation steps, more than the %.3g "
                                  "allowed: a longer dt or a shorter duration",
                                  duration / dt, kMaxSteps));
    startTime = s.real("start_time", startTime, 1.0, 4e9);
    groundTruthRate = s.real("ground_truth_rate", groundTruthRate, 0.1, 1000);
    odometryErrorScale = s.real("odometry_error_scale", odometryErrorScale, 0, 100);
    robots.clear();
    std::istringstream in(s.text("robots", ""));
    std::set<std::string> seen;
    for (std::string r; in >> r;) {
        common::checkRobotName(r, common::configOrigin(src) + ": [" + section + "] robots");
        if (!seen.insert(r).second) s.fail("robots", "robot '" + r + "' is listed twice");
        robots.push_back(r);
    }
    if (robots.size() > kMaxRobots)
        s.fail("robots", "more than " + std::to_string(kMaxRobots) + " robots");
    groundTruth = {};
    groundTruth.path = s.text("ground_truth", groundTruth.path);
    groundTruth.format =
        s.choice("ground_truth_format", "tum", common::GroundTruthSource::formats());
    groundTruth.robot = s.text("ground_truth_robot", groundTruth.robot);
    common::checkRobotName(groundTruth.robot,
                           common::configOrigin(src) + ": [" + section + "] ground_truth_robot");
    const auto off = s.reals("ground_truth_offset", {0, 0, 0}, 3);
    groundTruth.offset = mrpt::poses::CPose3D(off[0], off[1], 0, mrpt::DEG2RAD(off[2]), 0, 0);
    if (!groundTruth.path.empty()) {
        namespace fs = std::filesystem;
        groundTruth.path = common::pathFromIni(common::configOrigin(src), groundTruth.path);
        if (!fs::is_regular_file(groundTruth.path))
            s.fail("ground_truth", "no such file '" + common::pathInWords(groundTruth.path) +
                                       "' (a relative path is taken from the INI's folder)");
    }
    s.finish();
}

void ScenarioOptions::saveLocalizeKeys(mrpt::config::CConfigFileBase& t,
                                       const std::string& section) const {
    t.write(section, "name", name);
    t.write(section, "method", method);
    t.write(section, "seed", std::to_string(seed));
    if (!groundTruth.path.empty()) {
        t.write(section, "ground_truth", groundTruth.path);
        t.write(section, "ground_truth_format", groundTruth.format);
        t.write(section, "ground_truth_robot", groundTruth.robot);
        t.write(section, "ground_truth_offset",
                mrpt::format("%g %g %g", groundTruth.offset.x(), groundTruth.offset.y(),
                             mrpt::RAD2DEG(groundTruth.offset.yaw())));
    }
}

bool ScenarioOptions::describesSimulation(const mrpt::config::CConfigFileBase& ini,
                                          const std::string& section) {
    if (!ini.sectionExists(section)) return false;
    std::vector<std::string> keys, localizeKeys;
    ini.getAllKeys(section, keys);
    if (keys.empty()) return true;
    // the localize keys are the ones saveLocalizeKeys writes, ground truth included
    ScenarioOptions all;
    all.groundTruth.path = "-";
    mrpt::config::CConfigFileMemory written;
    all.saveLocalizeKeys(written, section);
    written.getAllKeys(section, localizeKeys);
    const std::set<std::string> localize(localizeKeys.begin(), localizeKeys.end());
    for (const auto& k : keys)
        if (!localize.count(mrpt::system::lowerCase(k))) return true;
    return false;
}

void ScenarioOptions::saveToConfigFile(mrpt::config::CConfigFileBase& t,
                                       const std::string& section) const {
    saveLocalizeKeys(t, section);
    t.write(section, "duration", duration);
    t.write(section, "dt", dt);
    t.write(section, "start_time", mrpt::format("%.3f", startTime));
    t.write(section, "ground_truth_rate", groundTruthRate);
    // written only when set: the effective.ini of every run before the key is unchanged
    if (odometryErrorScale != 1) t.write(section, "odometry_error_scale", odometryErrorScale);
    std::string list;
    for (const auto& r : robots) list += (list.empty() ? "" : " ") + r;
    t.write(section, "robots", list);
}

namespace {

/** Obstacles a floor robot cannot pass: boxes reaching below this height (m), and pillars
 *  (which stand on the floor). A box higher up (a shelf, a beam) is passed under. */
constexpr double kRobotHeight = 0.3;

/** Does the segment a-b cross the rectangle [lo, hi]? (Liang-Barsky clipping.) */
bool crossesRectangle(const mrpt::math::TPoint2D& a, const mrpt::math::TPoint2D& b,
                      const mrpt::math::TPoint2D& lo, const mrpt::math::TPoint2D& hi) {
    double t0 = 0, t1 = 1;
    const double d[2] = {b.x - a.x, b.y - a.y}, p0[2] = {a.x, a.y};
    const double mins[2] = {lo.x, lo.y}, maxs[2] = {hi.x, hi.y};
    for (int k = 0; k < 2; ++k) {
        if (std::abs(d[k]) < 1e-12) {
            if (p0[k] < mins[k] || p0[k] > maxs[k]) return false;
            continue;
        }
        double ta = (mins[k] - p0[k]) / d[k], tb = (maxs[k] - p0[k]) / d[k];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta), t1 = std::min(t1, tb);
        if (t0 > t1) return false;
    }
    return true;
}

/** A route the robot cannot drive: a waypoint outside the room, or a leg (start to the
 *  first waypoint, waypoint to waypoint, the last back to the first when it loops) through
 *  an obstacle on the floor. The robot steers straight at each waypoint. */
void checkRoute(const WorldOptions& world, const RobotOptions& r, const std::string& where) {
    using mrpt::math::TPoint2D;
    for (size_t i = 0; i < r.waypoints.size(); ++i)
        if (!world.contains({r.waypoints[i].x, r.waypoints[i].y, 0}))
            throw Error(where + " waypoints: waypoint " + std::to_string(i + 1) + " (" +
                        mrpt::format("%g %g", r.waypoints[i].x, r.waypoints[i].y) +
                        ") is outside the room (" +
                        mrpt::format("%g x %g m", world.sizeX, world.sizeY) + ")");
    std::vector<std::pair<TPoint2D, TPoint2D>> legs;
    TPoint2D from(r.start.x(), r.start.y());
    for (const auto& w : r.waypoints) legs.push_back({from, w}), from = w;
    if (r.loop && r.waypoints.size() > 1) legs.push_back({r.waypoints.back(), r.waypoints.front()});
    for (size_t i = 0; i < legs.size(); ++i) {
        const auto& [a, b] = legs[i];
        const std::string leg = mrpt::format("the leg from (%g %g) to (%g %g)", a.x, a.y, b.x, b.y);
        for (const auto& box : world.obstacles)
            if (box.min.z < kRobotHeight &&
                crossesRectangle(a, b, {box.min.x, box.min.y}, {box.max.x, box.max.y}))
                throw Error(where + " waypoints: " + leg + " goes through obstacle_" + box.name);
        for (const auto& p : world.pillars)
            if (mrpt::math::TSegment2D(a, b).distance({p.x, p.y}) < p.radius)
                throw Error(where + " waypoints: " + leg + " goes through pillar_" + p.name);
    }
}

}  // namespace

ScenarioConfig ScenarioConfig::loadWithoutRobots(const mrpt::config::CConfigFileBase& ini) {
    ScenarioConfig c;
    c.scenario.loadFromConfigFile(ini, "scenario");
    c.world.loadFromConfigFile(ini, "world");
    return c;
}

ScenarioConfig ScenarioConfig::load(const mrpt::config::CConfigFileBase& ini,
                                    const std::vector<std::string>& methodKeys) {
    ScenarioConfig c = loadWithoutRobots(ini);
    if (c.scenario.robots.empty())
        throw Error(common::configOrigin(ini) +
                    ": [scenario] robots: required key is missing "
                    "(robots = <name> ..., each with a [robot.<name>] section)");
    for (const auto& name : c.scenario.robots) {
        const std::string section = "robot." + name;
        if (!ini.sectionExists(section))
            throw Error(common::configOrigin(ini) + ": [scenario] robots: robot '" + name +
                        "' has no section [" + section + "]");
        RobotOptions r;
        r.name = name;
        r.methodKeys = methodKeys;
        r.loadFromConfigFile(ini, section);
        if (!c.world.contains({r.start.x(), r.start.y(), 0}))
            throw Error(common::configOrigin(ini) + ": [" + section + "] start: outside the room");
        checkRoute(c.world, r, common::configOrigin(ini) + ": [" + section + "]");
        c.robots.push_back(r);
    }
    return c;
}

void ScenarioConfig::addGeneratedRobots(const mrpt::config::CConfigFileBase& ini,
                                        std::vector<RobotOptions> generated) {
    if (!scenario.robots.empty())
        throw Error(common::configOrigin(ini) +
                    ": [scenario] robots: the robots are generated here; leave the key out");
    for (const auto& r : generated) {
        common::checkRobotName(r.name, common::configOrigin(ini) + ": a generated robot");
        if (!world.contains({r.start.x(), r.start.y(), 0}))
            throw Error(common::configOrigin(ini) + ": generated robot " + r.name +
                        " starts outside the room");
        scenario.robots.push_back(r.name);
    }
    robots = std::move(generated);
    robotsGenerated = true;
}

void ScenarioConfig::save(mrpt::config::CConfigFileBase& t) const {
    ScenarioOptions listed = scenario;
    if (robotsGenerated) listed.robots.clear();  // the method's section regenerates them
    listed.saveToConfigFile(t, "scenario");
    world.saveToConfigFile(t, "world");
    if (robotsGenerated) return;
    for (const auto& r : robots) r.saveToConfigFile(t, "robot." + r.name);
}

}  // namespace mrloc::sim
