#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/KeyTable.h>
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

namespace {

using SO = ScenarioOptions;

std::string where(const common::IniSection& s) {
    return common::configOrigin(s.config()) + ": [" + s.section() + "]";
}

void loadGroundTruthPath(common::IniSection& s, SO& o) {
    o.groundTruth.path = s.text("ground_truth", o.groundTruth.path);
    if (o.groundTruth.path.empty()) return;
    o.groundTruth.path = common::pathFromIni(common::configOrigin(s.config()), o.groundTruth.path);
}

void loadRobots(common::IniSection& s, SO& o) {
    o.robots.clear();
    std::istringstream in(s.text("robots", ""));
    std::set<std::string> seen;
    for (std::string r; in >> r;) {
        common::checkRobotName(r, where(s) + " robots");
        if (!seen.insert(r).second) s.fail("robots", "robot '" + r + "' is listed twice");
        o.robots.push_back(r);
    }
    if (o.robots.size() > SO::kMaxRobots)
        s.fail("robots", "more than " + std::to_string(SO::kMaxRobots) + " robots");
}

}  // namespace

const common::KeyTable<ScenarioOptions>& ScenarioOptions::localizeKeys() {
    static const auto table =
        common::KeyTable<SO>("scenario")
            .custom(
                "name", "", "", "names the output folder `out/<name>/` and files `<name>.rawlog`",
                [](common::IniSection& s, SO& o) {
                    o.name = s.text("name", o.name);
                    common::checkName(o.name, where(s) + " name");
                },
                [](const SO& o) { return o.name; })
            .text("method", MRLOC_KEY_FIELD(method),
                  "localization method; without it, the one method whose sections the INI holds "
                  "(MRPT's range-only INIs: beacons), else an error listing the methods")
            .custom(
                "seed", "", common::keyRangeText(0, double(common::kMaxSeed)),
                "random seed: every draw of the run derives from it; `--seed` overrides",
                [](common::IniSection& s, SO& o) {
                    o.seed =
                        (unsigned long)s.integer("seed", long(o.seed), 0, long(common::kMaxSeed));
                },
                [](const SO& o) { return std::to_string(o.seed); })
            // the ground truth's keys are written only with a ground-truth file
            .savedFromHereOnlyIf([](const SO& o) { return !o.groundTruth.path.empty(); })
            .custom("ground_truth", "", "",
                    "for `mrloc localize`: a ground-truth file (a relative path is taken from "
                    "the INI's folder); without it, where MRPT's apps look for it on a log "
                    "recorded elsewhere (MRPT's `[ro-localization] groundTruthFile`, only when "
                    "the log is that INI's own `rawlog_file`; else `<rawlog stem>_GT.txt` beside "
                    "the rawlog; either offset by the INI's `[OdometryEstimation] "
                    "odometry_X/Y/PHI`, its format told by its columns), then `<rawlog "
                    "stem>.<robot>.gt.txt` beside the rawlog (mrloc's simulator). metrics.json "
                    "`ground_truth_from` and the report say which was used. A `[scenario]` "
                    "holding only `name`, `method`, `seed` and `ground_truth*` keys describes no "
                    "simulation: it can be put on top of an MRPT INI, and such a run's "
                    "effective.ini keeps only those keys, so it runs again as is",
                    loadGroundTruthPath, [](const SO& o) { return o.groundTruth.path; })
            .choice("ground_truth_format", MRLOC_KEY_FIELD(groundTruth.format),
                    common::GroundTruthSource::formats(),
                    "`tum` (`t x y z qx qy qz qw`), `index_x_y_phi` (`i x y phi`: MRPT's "
                    "`*_GT.txt`), `x_y_z_yaw_pitch_roll` (one row per step: MRPT's "
                    "`*_ground_truth_robot_path.txt`); `%` and `#` lines are comments. The step "
                    "formats' time base: step i is the robot's i-th odometry reading (one per "
                    "action in an actions + sensory-frames rawlog)")
            .custom(
                "ground_truth_robot", "", "",
                "the robot it belongs to (a rawlog from MRPT's tools has one, `robot`)",
                [](common::IniSection& s, SO& o) {
                    o.groundTruth.robot = s.text("ground_truth_robot", o.groundTruth.robot);
                    common::checkRobotName(o.groundTruth.robot, where(s) + " ground_truth_robot");
                },
                [](const SO& o) { return o.groundTruth.robot; })
            .custom(
                "ground_truth_offset", "m m deg", "",
                "`x y phi_deg`: the file's frame in the estimates' frame, pose = offset (+) row "
                "(MRPT's UWB demo: its `[OdometryEstimation] odometry_X/Y/PHI`, `2 4 0`)",
                [](common::IniSection& s, SO& o) {
                    const auto off = s.reals("ground_truth_offset", {0, 0, 0}, 3);
                    o.groundTruth.offset =
                        mrpt::poses::CPose3D(off[0], off[1], 0, mrpt::DEG2RAD(off[2]), 0, 0);
                },
                [](const SO& o) {
                    const auto& off = o.groundTruth.offset;
                    return common::keyListText({off.x(), off.y()}) + " " +
                           common::keyDegreesText(off.yaw());
                });
    return table;
}

const common::KeyTable<ScenarioOptions>& ScenarioOptions::simulationKeys() {
    static const auto table =
        common::KeyTable<SO>("scenario")
            .real("duration", MRLOC_KEY_FIELD(duration), {1e-3, 1e6}, "s", "simulated time")
            .real("dt", MRLOC_KEY_FIELD(dt), {1e-4, 1.0}, "s",
                  "simulation step; `duration / dt` at most 1e7 steps")
            .custom(
                "start_time", "s", "1 .. 4e9", "time stamp of t = 0, seconds since 1970",
                [](common::IniSection& s, SO& o) {
                    o.startTime = s.real("start_time", o.startTime, 1.0, 4e9);
                },
                [](const SO& o) { return mrpt::format("%.3f", o.startTime); },
                common::keyNumberText(SO{}.startTime))
            .real("ground_truth_rate", MRLOC_KEY_FIELD(groundTruthRate), {0.1, 1000}, "Hz",
                  "ground-truth rows per second")
            .real("odometry_error_scale", MRLOC_KEY_FIELD(odometryErrorScale), {0, 100}, "",
                  "multiplies every robot's systematic odometry errors (`odometry_scale_error`, "
                  "`odometry_heading_drift` and their sigmas): one key for a sweep of odometry "
                  "quality (`mrloc batch --grid scenario.odometry_error_scale=1,2,3`; "
                  "framesync's `experiment_drift` is this sweep)")
            // written only when set: the effective.ini of every run before the key is unchanged
            .savedOnlyIf([](const SO& o) { return o.odometryErrorScale != 1; })
            .custom(
                "robots", "", "at most 1000",
                "robot names separated by spaces; each has `[robot.<name>]`", loadRobots,
                [](const SO& o) {
                    std::string list;
                    for (const auto& r : o.robots) list += (list.empty() ? "" : " ") + r;
                    return list;
                },
                "(required to simulate)");
    return table;
}

common::SectionKeys ScenarioOptions::keysDocs() {
    auto docs = localizeKeys().docs();
    const auto simulation = simulationKeys().docs();
    docs.keys.insert(docs.keys.end(), simulation.keys.begin(), simulation.keys.end());
    return docs;
}

void ScenarioOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& src,
                                         const std::string& section) {
    *this = ScenarioOptions{};  // every key absent takes the struct's default: written once
    common::IniSection s(src, section);
    localizeKeys().load(s, *this);
    simulationKeys().load(s, *this);
    // after its format and robot, which a wrong file must not hide
    if (!groundTruth.path.empty() && !std::filesystem::is_regular_file(groundTruth.path))
        s.fail("ground_truth", "no such file '" + common::pathInWords(groundTruth.path) +
                                   "' (a relative path is taken from the INI's folder)");
    if (duration / dt > kMaxSteps)
        s.fail("dt", mrpt::format("duration / dt = %.3g simulation steps, more than the %.3g "
                                  "allowed: a longer dt or a shorter duration",
                                  duration / dt, kMaxSteps));
    s.finish();
}

void ScenarioOptions::saveLocalizeKeys(mrpt::config::CConfigFileBase& t,
                                       const std::string& section) const {
    localizeKeys().save(*this, t, section);
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
    localizeKeys().save(*this, t, section);
    simulationKeys().save(*this, t, section);
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
