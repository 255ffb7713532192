#include <mrloc/common/Error.h>
#include <mrloc/common/IniSection.h>
#include <mrloc/sim/Scenario.h>
#include <mrpt/core/format.h>

#include <set>
#include <sstream>

namespace mrloc::sim {

void ScenarioOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& src,
                                         const std::string& section) {
    common::IniSection s(src, section);
    name = s.text("name", "run");
    if (name.empty() || name.find_first_of("/\\ ") != std::string::npos)
        s.fail("name", "must be a non-empty file name without '/' or spaces");
    method = s.text("method", "beacons");
    seed = (unsigned long)s.integer("seed", 1, 0, 4294967295L);
    duration = s.real("duration", 60, 1e-3, 1e6);
    dt = s.real("dt", 0.01, 1e-4, 1.0);
    startTime = s.real("start_time", 1.7e9, 1.0, 4e9);
    groundTruthRate = s.real("ground_truth_rate", 20, 0.1, 1000);
    robots.clear();
    std::istringstream in(s.text("robots", ""));
    std::set<std::string> seen;
    for (std::string r; in >> r;) {
        if (r.find('.') != std::string::npos) s.fail("robots", "robot name '" + r + "' has a '.'");
        if (!seen.insert(r).second) s.fail("robots", "robot '" + r + "' is listed twice");
        robots.push_back(r);
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
}

namespace {

ScenarioConfig loadCommon(const mrpt::config::CConfigFileBase& ini) {
    ScenarioConfig c;
    c.scenario.loadFromConfigFile(ini, "scenario");
    c.world.loadFromConfigFile(ini, "world");
    c.sensors.loadFromConfigFile(ini, "sensors");
    c.ultrasonic.loadFromConfigFile(ini, "ultrasonic");
    return c;
}

}  // namespace

ScenarioConfig ScenarioConfig::load(const mrpt::config::CConfigFileBase& ini, FloorPlan plan,
                                    const mrpt::poses::CPose2D& start) {
    ScenarioConfig c = loadCommon(ini);
    if (c.scenario.robots.empty()) c.scenario.robots = {"r1"};
    if (c.scenario.robots.size() != 1)
        throw Error(common::configOrigin(ini) +
                    ": [scenario] robots: a floor-plan scenario has one robot");
    RobotOptions r;
    r.name = c.scenario.robots[0];
    r.startInSection = false;  // the method's section has it
    if (ini.sectionExists("robot." + r.name)) r.loadFromConfigFile(ini, "robot." + r.name);
    r.start = start;
    if (!plan.polygon.contains({start.x(), start.y()}))
        throw Error(common::configOrigin(ini) + mrpt::format(": the start (%g %g) is outside the "
                                                             "floor plan",
                                                             start.x(), start.y()));
    c.robots.push_back(r);
    c.floorPlan = std::move(plan);
    return c;
}

ScenarioConfig ScenarioConfig::load(const mrpt::config::CConfigFileBase& ini, bool withBeacons) {
    ScenarioConfig c = loadCommon(ini);
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
        r.loadFromConfigFile(ini, section);
        if (!c.world.contains({r.start.x(), r.start.y(), 0}))
            throw Error(common::configOrigin(ini) + ": [" + section + "] start: outside the room");
        c.robots.push_back(r);
    }
    if (!withBeacons) return c;
    common::IniSection beacons(ini, "beacons");  // keys are checked by the method's options
    c.beacons = common::loadBeaconMap(ini, beacons);
    for (const auto& [id, p] : c.beacons)
        if (!c.world.contains(p, 1e-9))
            throw Error(common::configOrigin(ini) + ": [beacons] beacon_" + std::to_string(id) +
                        ": position " + p.asString() + " is outside the room [world] size");
    return c;
}

ScenarioConfig ScenarioConfig::load(const mrpt::config::CConfigFileBase& ini,
                                    std::vector<RobotOptions> robots) {
    ScenarioConfig c = loadCommon(ini);
    if (!c.scenario.robots.empty())
        throw Error(common::configOrigin(ini) +
                    ": [scenario] robots: the robots are generated here; leave the key out");
    for (const auto& r : robots) {
        if (!c.world.contains({r.start.x(), r.start.y(), 0}))
            throw Error(common::configOrigin(ini) + ": generated robot " + r.name +
                        " starts outside the room");
        c.scenario.robots.push_back(r.name);
    }
    c.robots = std::move(robots);
    return c;
}

void ScenarioConfig::save(mrpt::config::CConfigFileBase& t) const {
    scenario.saveToConfigFile(t, "scenario");
    world.saveToConfigFile(t, "world");
    sensors.saveToConfigFile(t, "sensors");
    ultrasonic.saveToConfigFile(t, "ultrasonic");
    for (const auto& r : robots) r.saveToConfigFile(t, "robot." + r.name);
}

}  // namespace mrloc::sim
