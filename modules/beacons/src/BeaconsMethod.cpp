#include <mrloc/beacons/BeaconPayload.h>
#include <mrloc/beacons/BeaconsMethod.h>
#include <mrloc/common/Error.h>
#include <mrloc/report/ReportOptions.h>
#include <mrpt/core/format.h>

#include <algorithm>
#include <filesystem>
#include <map>

namespace mrloc::beacons {

method::Scenario loadScenario(const mrpt::config::CConfigFileBase& ini) {
    method::Scenario s;
    s.config = sim::ScenarioConfig::load(ini, BeaconRobotOptions::keys());
    std::vector<BeaconRobotOptions> robots(s.config.robots.size());
    for (size_t i = 0; i < robots.size(); ++i) robots[i].load(ini, s.config.robots[i].name);
    SensorOptions sensors;
    sensors.loadFromConfigFile(ini, "sensors");
    UltrasonicOptions ultrasonic;
    ultrasonic.loadFromConfigFile(ini, "ultrasonic");
    common::IniSection section(ini, "beacons");  // keys are checked by the localizer's options
    const BeaconMap map = loadBeaconMap(ini, section);
    for (const auto& [id, p] : map)
        if (!s.config.world.contains(p, 1e-9))
            throw Error(common::configOrigin(ini) + ": [beacons] beacon_" + std::to_string(id) +
                        ": position " + p.asString() + " is outside the room [world] size");
    s.payload = std::make_unique<BeaconPayload>(ini, map, sensors, ultrasonic, robots);
    s.saveOptions = [sensors, ultrasonic, robots,
                     names = s.config.scenario.robots](mrpt::config::CConfigFileBase& t) {
        sensors.saveToConfigFile(t, "sensors");
        ultrasonic.saveToConfigFile(t, "ultrasonic");
        for (size_t i = 0; i < robots.size(); ++i) robots[i].save(t, names[i]);
    };
    return s;
}

namespace {

/** Seed 001 Tables 3/4 and Figs. 10/11 for this run: per robot (test point) the reception
 *  rate of each beacon from the simulator's shot log, and the mean and max error, beside
 *  the paper's figures ([beacons] paper_reception_<id>). */
std::string receptionSection(const report::RunView& run) {
    const auto& metrics = run.metrics;
    // the shot log of a rawlog simulated into this run folder: the report reads nothing
    // outside the folder, whatever metrics.json names
    const std::string rawlogName =
        std::filesystem::path(metrics.value("rawlog", "")).filename().string();
    const std::string shotsPath = shotLogPath(run.dir + "/" + rawlogName);
    if (!std::filesystem::exists(shotsPath))
        return "<p>No shot log beside the rawlog (not simulated here): no reception table.</p>\n";
    const auto shots = loadShotLog(shotsPath);
    if (shots.empty()) return "<p>The shot log is empty: no beacon fired.</p>\n";
    BeaconOptions options;
    options.loadFromConfigFile(*run.effective, "beacons");
    report::ReportOptions paper;
    paper.loadFromConfigFile(*run.effective, "report");
    std::vector<std::string> robots;
    std::map<int, std::map<std::string, std::pair<int, int>>> heard;  // beacon, robot: n, ok
    for (const auto& s : shots) {
        if (std::find(robots.begin(), robots.end(), s.robot) == robots.end())
            robots.push_back(s.robot);
        auto& c = heard[s.beacon][s.robot];
        ++c.first;
        c.second += s.detected;
    }
    std::string t = "<h2>Beacon system: reception and errors per robot</h2>\n";
    if (!options.paperReception.empty())
        t +=
            "<p>Ours, with the paper's in brackets" +
            (paper.paperCaption.empty() ? std::string() : ": " + report::html(paper.paperCaption)) +
            ".</p>\n";
    t += "<table><tr><th>successful receiving rate (%)</th>";
    for (const auto& r : robots) t += "<th>" + report::html(r) + "</th>";
    t += "</tr>\n";
    for (const auto& [beacon, perRobot] : heard) {
        t += "<tr><th>beacon " + std::to_string(beacon) + "</th>";
        const auto p = options.paperReception.find(beacon);
        for (size_t i = 0; i < robots.size(); ++i) {
            const auto c = perRobot.find(robots[i]);
            t += "<td>";
            if (c != perRobot.end())
                t += mrpt::format("%.0f", 100.0 * c->second.second / c->second.first);
            if (p != options.paperReception.end() && i < p->second.size())
                t += mrpt::format(" (%g)", p->second[i]);
            t += "</td>";
        }
        t += "</tr>\n";
    }
    const auto methodRobots = metrics.value("beacons", nlohmann::json::object())
                                  .value("robots", nlohmann::json::object());
    const auto rowOf = [&](const nlohmann::json& m, const char* name, const char* key, double scale,
                           const char* fmt) {
        std::string r = std::string("<tr><th>") + name + "</th>";
        for (const auto& robot : robots) {
            r += "<td>";
            if (m.contains(robot) && m[robot].contains(key) && m[robot][key].is_number())
                r += mrpt::format(fmt, scale * m[robot][key].get<double>());
            else
                r += "none";
            r += "</td>";
        }
        return r + "</tr>\n";
    };
    const auto row = [&](const char* name, const char* key, double scale, const char* fmt) {
        return rowOf(metrics["robots"], name, key, scale, fmt);
    };
    t += row("mean error (mm)", "mean_m", 1000, "%.1f");
    t += row("max error (mm)", "max_m", 1000, "%.1f");
    t += row("estimates", "estimates", 1, "%.0f");
    // seed 001 sec. 4's figure for the scheduler: how far a robot moves between two fixes
    t += rowOf(methodRobots, "mean distance between fixes (m)", "mean_distance_between_fixes_m", 1,
               "%.3f");
    t += rowOf(methodRobots, "max distance between fixes (m)", "max_distance_between_fixes_m", 1,
               "%.3f");
    // the link's biases as each robot's tracker estimated them (estimate_bias)
    bool anyBias = false;
    std::string offsets = "<tr><th>range offset per beacon at the end (mm)</th>",
                scales = "<tr><th>common range scale at the end (per mille)</th>";
    for (const auto& robot : robots) {
        const auto m = methodRobots.value(robot, nlohmann::json::object());
        offsets += "<td>";
        scales += "<td>";
        if (m.contains("range_offsets_m")) {
            anyBias = true;
            std::string cell;
            for (const auto& [id, v] : m["range_offsets_m"].items())
                cell += (cell.empty() ? "" : ", ") + id + ": " +
                        mrpt::format("%+.1f", 1000 * v.get<double>());
            offsets += cell;
            scales += mrpt::format("%+.2f", 1000 * m.value("range_scale", 0.0));
        } else {
            offsets += "none";
            scales += "none";
        }
        offsets += "</td>";
        scales += "</td>";
    }
    if (anyBias) t += offsets + "</tr>\n" + scales + "</tr>\n";
    t += "</table>\n";
    t += "<p>Scheduling: <b>" +
         std::string(options.system.scheduling == Scheduling::Priority
                         ? "priority (slots in proportion to speed, seed 001 sec. 4)"
                         : "round robin") +
         "</b>. Seed 001's point: with priority scheduling the distance a robot moves between "
         "two fixes stays about the same whatever its speed; round robin lets a fast robot "
         "go further.</p>\n";
    size_t detected = 0;
    for (const auto& s : shots) detected += s.detected;
    t += mrpt::format(
             "<p>Shots fired: %zu, heard: %zu, a reception rate of %.1f %% (of the shots fired: "
             "a section fires only its own beacons). Multilateration fixes: %d (in the tracker "
             "mode, those made while the filter starts or restarts; then every epoch gives an "
             "estimate, the ranges corrected by the offsets and scale above). Log: "
             "<code>",
             shots.size(), detected, 100.0 * double(detected) / double(shots.size()),
             metrics.value("beacons", nlohmann::json::object()).value("multilateration_fixes", 0)) +
         report::html(std::filesystem::path(shotsPath).filename().string()) +
         "</code> (in this folder).</p>\n";
    return t;
}

void beaconsInTopView(const report::RunView& run, report::TopViewContent& view) {
    common::IniSection section(*run.effective, "beacons");
    for (const auto& [id, p] : readBeaconKeys(section)) view.landmarks.push_back(p);
    view.landmarksName = "beacons";
}

}  // namespace

void registerMethod(method::Registry& registry) {
    method::MethodUnit<BeaconLocalizer> m;
    m.name = "beacons";
    m.sections = {"beacons", "sensors", "ultrasonic"};
    // MRPT's range-only localization INIs (ro-localization, pf-localization's RO demo) name
    // no mrloc section: their beacon likelihood section says they are this method's
    m.foreignSections = {"MetricMap_landmarksMap_00_likelihoodOpts"};
    m.scenario = [](const mrpt::config::CConfigFileBase& ini, const BeaconLocalizer&) {
        return loadScenario(ini);
    };
    m.report.html = receptionSection;
    m.report.topView = beaconsInTopView;
    registry.add(std::move(m));
}

}  // namespace mrloc::beacons
