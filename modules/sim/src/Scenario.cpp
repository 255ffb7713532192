#include <mrloc/common/Error.h>
#include <mrloc/common/IniSection.h>
#include <mrloc/common/Names.h>
#include <mrloc/sim/Scenario.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <sstream>

namespace mrloc::sim {

void ScenarioOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& src,
                                         const std::string& section) {
    common::IniSection s(src, section);
    name = s.text("name", "run");
    common::checkName(name, common::configOrigin(src) + ": [" + section + "] name");
    method = s.text("method", "");  // none given: the app finds it from the INI's sections
    seed = (unsigned long)s.integer("seed", 1, 0, 4294967295L);
    duration = s.real("duration", 60, 1e-3, 1e6);
    dt = s.real("dt", 0.01, 1e-4, 1.0);
    if (duration / dt > kMaxSteps)
        s.fail("dt", mrpt::format("duration / dt = %.3g simulation steps, more than the %.3g "
                                  "allowed: a longer dt or a shorter duration",
                                  duration / dt, kMaxSteps));
    startTime = s.real("start_time", 1.7e9, 1.0, 4e9);
    groundTruthRate = s.real("ground_truth_rate", 20, 0.1, 1000);
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
    groundTruth.path = s.text("ground_truth", "");
    groundTruth.format =
        s.choice("ground_truth_format", "tum", common::GroundTruthSource::formats());
    groundTruth.robot = s.text("ground_truth_robot", "robot");
    common::checkRobotName(groundTruth.robot,
                           common::configOrigin(src) + ": [" + section + "] ground_truth_robot");
    const auto off = s.reals("ground_truth_offset", {0, 0, 0}, 3);
    groundTruth.offset = mrpt::poses::CPose3D(off[0], off[1], 0, mrpt::DEG2RAD(off[2]), 0, 0);
    if (!groundTruth.path.empty()) {
        namespace fs = std::filesystem;
        const std::string ini = common::configOrigin(src);
        if (fs::path(groundTruth.path).is_relative() && fs::is_regular_file(ini))
            groundTruth.path =
                (fs::path(ini).parent_path() / groundTruth.path).lexically_normal().string();
        if (!fs::is_regular_file(groundTruth.path))
            s.fail("ground_truth", "no such file '" + groundTruth.path +
                                       "' (a relative path is taken from the INI's folder)");
    }
    s.finish();
}

void ScenarioOptions::saveToConfigFile(mrpt::config::CConfigFileBase& t,
                                       const std::string& section) const {
    t.write(section, "name", name);
    t.write(section, "method", method);
    t.write(section, "seed", std::to_string(seed));
    t.write(section, "duration", duration);
    t.write(section, "dt", dt);
    t.write(section, "start_time", mrpt::format("%.3f", startTime));
    t.write(section, "ground_truth_rate", groundTruthRate);
    std::string list;
    for (const auto& r : robots) list += (list.empty() ? "" : " ") + r;
    t.write(section, "robots", list);
    if (!groundTruth.path.empty()) {
        t.write(section, "ground_truth", groundTruth.path);
        t.write(section, "ground_truth_format", groundTruth.format);
        t.write(section, "ground_truth_robot", groundTruth.robot);
        t.write(section, "ground_truth_offset",
                mrpt::format("%g %g %g", groundTruth.offset.x(), groundTruth.offset.y(),
                             mrpt::RAD2DEG(groundTruth.offset.yaw())));
    }
}

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
