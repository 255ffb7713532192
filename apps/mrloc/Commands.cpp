#include "Commands.h"

#include <mrloc/beacons/BeaconLocalizer.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/IniSection.h>
#include <mrloc/common/LocalizationRun.h>
#include <mrloc/omnivision/OmniLocalizer.h>
#include <mrloc/polymap/PolymapLocalizer.h>
#include <mrloc/report/Report.h>
#include <mrloc/report/ReportOptions.h>
#include <mrloc/sim/Simulator.h>
#include <mrpt/3rdparty/tclap/CmdLine.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/core/format.h>
#include <mrpt/random/RandomGenerators.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <set>

namespace mrloc::app {

namespace {

constexpr const char* kVersion = "0.1.0";

common::LocalizerRegistry makeRegistry() {
    common::LocalizerRegistry r;
    beacons::registerLocalizers(r);
    polymap::registerLocalizers(r);
    omnivision::registerLocalizers(r);
    return r;
}

/** Opens an INI and rejects lower-case sections that mrloc does not know (a misspelt
 *  section would otherwise be ignored). Sections of MRPT's apps start with upper case. */
std::unique_ptr<mrpt::config::CConfigFile> openIni(const std::string& path) {
    if (!std::filesystem::is_regular_file(path)) throw Error("config " + path + ": no such file");
    auto ini = std::make_unique<mrpt::config::CConfigFile>(path);
    std::vector<std::string> sections;
    ini->getAllSections(sections);
    static const std::set<std::string> known = {"scenario", "world",   "sensors",    "ultrasonic",
                                                "beacons",  "polymap", "omnivision", "report"};
    for (const auto& s : sections) {
        if (s.empty() || !std::islower(static_cast<unsigned char>(s[0]))) continue;
        if (known.count(s) || s.rfind("robot.", 0) == 0) continue;
        throw Error(path + ": [" + s +
                    "]: unknown section (mrloc's sections: scenario, world, "
                    "sensors, ultrasonic, robot.<name>, beacons, polymap, omnivision, report; see "
                    "doc/ini.md)");
    }
    return ini;
}

struct Common {
    TCLAP::ValueArg<std::string> out{
        "o", "out", "output directory (default: out/<scenario name>)", false, "", "DIR"};
    TCLAP::SwitchArg quiet{"q", "quiet", "no progress bar, only errors"};
};

std::string outDirOr(Common& c, const std::string& name) {
    return c.out.isSet() ? c.out.getValue() : "out/" + name;
}

/** A swarm of robots driving straight across the room at random headings, placed at
 *  random at least `separation` apart ([omnivision] swarm = N). */
std::vector<sim::RobotOptions> generateSwarm(const omnivision::OmniOptions& o,
                                             const sim::WorldOptions& world) {
    mrpt::random::CRandomGenerator rng(uint32_t(o.swarmSeed));
    const double side = std::min({o.swarmArea, world.sizeX, world.sizeY});
    const double x0 = 0.5 * (world.sizeX - side), y0 = 0.5 * (world.sizeY - side);
    std::vector<sim::RobotOptions> robots;
    for (int tries = 0; int(robots.size()) < o.swarm; ++tries) {
        if (tries > 100000)
            throw Error("[omnivision] swarm: cannot place " + std::to_string(o.swarm) + " robots " +
                        std::to_string(o.swarmSeparation) + " m apart in swarm_area");
        const double x = x0 + rng.drawUniform(0.05, 0.95) * side;
        const double y = y0 + rng.drawUniform(0.05, 0.95) * side;
        if (std::any_of(robots.begin(), robots.end(), [&](const auto& r) {
                return std::hypot(r.start.x() - x, r.start.y() - y) < o.swarmSeparation;
            }))
            continue;
        sim::RobotOptions r;
        r.name = mrpt::format("R%02d", int(robots.size()) + 1);
        const double heading = rng.drawUniform(-M_PI, M_PI);
        r.start = mrpt::poses::CPose2D(x, y, heading);
        r.speed = std::max(o.swarmSpeed, 1e-3);
        if (o.swarmSpeed > 0)  // a far waypoint straight ahead: the robot drives straight
            r.waypoints = {{x + 1e3 * std::cos(heading), y + 1e3 * std::sin(heading)}};
        r.loop = false;
        robots.push_back(r);
    }
    return robots;
}

/** The omni-directional camera setup [omnivision] implies: snapshots, stops, the LiDAR. */
sim::ScenarioConfig loadOmniScenario(const mrpt::config::CConfigFile& ini) {
    omnivision::OmniOptions o;
    o.loadFromConfigFile(ini, "omnivision");
    sim::WorldOptions world;
    world.loadFromConfigFile(ini, "world");
    auto cfg = o.swarm > 0 ? sim::ScenarioConfig::load(ini, generateSwarm(o, world))
                           : sim::ScenarioConfig::load(ini, /*withBeacons=*/false);
    const auto need = [&](const std::string& robot, const char* key) {
        if (std::find(cfg.scenario.robots.begin(), cfg.scenario.robots.end(), robot) ==
            cfg.scenario.robots.end())
            throw Error(common::configOrigin(ini) + ": [omnivision] " + key + ": robot '" + robot +
                        "' is not in the scenario");
    };
    sim::OmniSetup setup;
    setup.camera.render = o.render;
    setup.camera.panorama = o.panorama;
    setup.camera.bearingSigma = o.bearingSigma * M_PI / 180;
    setup.camera.maxRange = o.maxRange;
    setup.camera.markerRadius = o.markerRadius;
    setup.camera.markerHeight = o.markerHeight;
    setup.camera.cameraHeight = o.cameraHeight;
    setup.snapshotTimes = o.snapshotTimes();
    for (double t : setup.snapshotTimes)
        if (t > cfg.scenario.duration)
            throw Error(common::configOrigin(ini) + ": [omnivision]: a snapshot at " +
                        std::to_string(t) + " s is after [scenario] duration");
    if (o.method == "proposed") {
        for (size_t r = 0; r < o.pairs.size(); ++r) {
            const auto& [a, b] = o.pairs[r];
            need(a, "pairs");
            need(b, "pairs");
            const double shift = double(r) * o.roundPeriod;
            setup.stops.push_back({a, o.tb + shift, o.te + shift});
            setup.stops.push_back({b, o.tb + shift, o.te + shift});
        }
    } else {
        need(o.measuredPair.first, "measured_pair");
        need(o.measuredPair.second, "measured_pair");
        setup.lidar =
            sim::OmniSetup::Lidar{o.measuredPair.first, o.measuredPair.second, o.lidarSigma};
    }
    cfg.omni = setup;
    return cfg;
}

/** A floor-plan scenario takes its map, start and scanner from [polymap]; an omni-camera
 *  scenario its cameras, stops and swarm from [omnivision]. */
sim::ScenarioConfig loadScenarioOf(const mrpt::config::CConfigFile& ini) {
    sim::ScenarioOptions scenario;
    scenario.loadFromConfigFile(ini, "scenario");
    if (scenario.method == "omnivision") return loadOmniScenario(ini);
    if (scenario.method != "polymap") return sim::ScenarioConfig::load(ini);
    polymap::PolymapOptions o;
    o.loadFromConfigFile(ini, "polymap");
    auto map = o.buildMap();
    const auto start = o.startIn(map);
    sim::FloorPlan plan{std::move(map.polygon),
                        {o.scanRays, o.scanRangeSigma, o.scanMaxRange, o.scanRate}};
    return sim::ScenarioConfig::load(ini, std::move(plan),
                                     {start.x, start.y, mrpt::DEG2RAD(o.heading)});
}

sim::ScenarioConfig loadScenario(const mrpt::config::CConfigFile& ini,
                                 TCLAP::ValueArg<long>& seed) {
    auto cfg = loadScenarioOf(ini);
    report::ReportOptions().loadFromConfigFile(ini, "report");  // checked before any output
    if (seed.isSet()) {
        if (seed.getValue() < 0) throw Error("--seed must be non-negative");
        cfg.scenario.seed = (unsigned long)seed.getValue();
    }
    return cfg;
}

/** Validates the method's section before anything is written. */
std::unique_ptr<common::Localizer> makeLocalizer(const std::string& method,
                                                 const mrpt::config::CConfigFileBase& ini) {
    auto loc = makeRegistry().create(method);
    loc->configure(ini);
    return loc;
}

/** The method's on-board part in a closed-loop simulation (none for a method without). */
std::unique_ptr<beacons::OnboardBeacons> makeOnboard(const std::string& method,
                                                     const mrpt::config::CConfigFileBase& ini) {
    if (method != "beacons") return nullptr;
    return std::make_unique<beacons::OnboardBeacons>(ini);
}

sim::SimulationHooks hooksOf(const std::unique_ptr<beacons::OnboardBeacons>& o) {
    if (!o) return {};
    return {&o->localizer, &o->rfBeacon};
}

void doLocalize(const std::string& method, const mrpt::config::CConfigFileBase& ini,
                const mrpt::config::CConfigFileBase& effective, const std::string& rawlog,
                const std::string& outDir, bool quiet) {
    auto loc = makeLocalizer(method, ini);
    const auto m = common::runLocalization(*loc, {method, rawlog, outDir, quiet}, effective);
    if (!quiet) {
        std::cerr << "localized " << m["observations"] << " observations with '" << method << "'";
        if (m.value("ground_truth", false))
            std::cerr << ": RMSE " << m["rmse_m"].get<double>() << " m, max "
                      << m["max_m"].get<double>() << " m over " << m["n"] << " estimates";
        std::cerr << "\n";
    }
}

}  // namespace

std::optional<int> parseArgs(TCLAP::CmdLine& cmd, int argc, char** argv) {
    if (cmd.parse(argc, argv)) return std::nullopt;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--help" || a == "-h" || a == "--version") return 0;
    }
    return 2;
}

int simulate(int argc, char** argv) {
    TCLAP::CmdLine cmd(
        "mrloc simulate: simulate the INI's scenario into a rawlog "
        "(<out>/<name>.rawlog) and ground truth (<out>/<name>.<robot>.gt.txt)",
        ' ', kVersion);
    TCLAP::UnlabeledValueArg<std::string> iniArg("ini", "scenario INI file", true, "", "INI", cmd);
    TCLAP::ValueArg<long> seed("s", "seed", "random seed (overrides [scenario] seed)", false, 0,
                               "N", cmd);
    Common c;
    cmd.add(c.out);
    cmd.add(c.quiet);
    if (const auto code = parseArgs(cmd, argc, argv)) return *code;
    const auto ini = openIni(iniArg.getValue());
    const auto cfg = loadScenario(*ini, seed);
    makeLocalizer(cfg.scenario.method, *ini);  // a bad method section fails before simulating
    const auto onboard = makeOnboard(cfg.scenario.method, *ini);
    const std::string path = sim::simulateToFiles(cfg, outDirOr(c, cfg.scenario.name),
                                                  c.quiet.getValue(), hooksOf(onboard));
    std::cout << path << "\n";
    return 0;
}

int localize(int argc, char** argv) {
    TCLAP::CmdLine cmd(
        "mrloc localize: run the INI's method ([scenario] method, default "
        "'beacons') on any MRPT rawlog, in either rawlog format. Ground truth "
        "is taken from <rawlog stem>.<robot>.gt.txt when present.",
        ' ', kVersion);
    TCLAP::UnlabeledValueArg<std::string> iniArg("ini", "INI file", true, "", "INI", cmd);
    TCLAP::UnlabeledValueArg<std::string> rawlog("rawlog", "rawlog file", true, "", "RAWLOG", cmd);
    Common c;
    cmd.add(c.out);
    cmd.add(c.quiet);
    if (const auto code = parseArgs(cmd, argc, argv)) return *code;
    const auto ini = openIni(iniArg.getValue());
    sim::ScenarioOptions scenario;
    scenario.loadFromConfigFile(*ini, "scenario");
    const std::string dir = outDirOr(c, scenario.name);
    doLocalize(scenario.method, *ini, *ini, rawlog.getValue(), dir, c.quiet.getValue());
    std::cout << dir << "\n";
    return 0;
}

int report(int argc, char** argv) {
    TCLAP::CmdLine cmd(
        "mrloc report: render report.html, topview.png, error_time.png and "
        "error_cdf.png in a directory written by `mrloc localize`",
        ' ', kVersion);
    TCLAP::UnlabeledValueArg<std::string> dir("run-dir", "run directory", true, "", "DIR", cmd);
    if (const auto code = parseArgs(cmd, argc, argv)) return *code;
    std::cout << report::makeReport(dir.getValue()) << "\n";
    return 0;
}

int run(int argc, char** argv) {
    TCLAP::CmdLine cmd(
        "mrloc run: simulate, localize and report in a row; everything goes to "
        "<out> (default out/<scenario name>)",
        ' ', kVersion);
    TCLAP::UnlabeledValueArg<std::string> iniArg("ini", "scenario INI file", true, "", "INI", cmd);
    TCLAP::ValueArg<long> seed("s", "seed", "random seed (overrides [scenario] seed)", false, 0,
                               "N", cmd);
    Common c;
    cmd.add(c.out);
    cmd.add(c.quiet);
    if (const auto code = parseArgs(cmd, argc, argv)) return *code;
    const auto ini = openIni(iniArg.getValue());
    const auto cfg = loadScenario(*ini, seed);
    makeLocalizer(cfg.scenario.method, *ini);
    const std::string dir = outDirOr(c, cfg.scenario.name);
    const auto onboard = makeOnboard(cfg.scenario.method, *ini);
    const std::string rawlog = sim::simulateToFiles(cfg, dir, c.quiet.getValue(), hooksOf(onboard));
    mrpt::config::CConfigFileMemory effective;
    cfg.save(effective);
    report::ReportOptions paper;
    paper.loadFromConfigFile(*ini, "report");
    paper.saveToConfigFile(effective, "report");
    doLocalize(cfg.scenario.method, *ini, effective, rawlog, dir, c.quiet.getValue());
    const std::string page = report::makeReport(dir);
    std::cout << "report: " << page << "\n";
    return 0;
}

}  // namespace mrloc::app
