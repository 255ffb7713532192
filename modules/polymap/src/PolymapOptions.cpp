#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/IniSection.h>
#include <mrloc/polymap/PolymapOptions.h>
#include <mrpt/core/format.h>

#include <cmath>
#include <filesystem>
#include <iterator>
#include <sstream>

namespace mrloc::polymap {

void PolymapOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& src,
                                        const std::string& section) {
    *this = PolymapOptions{};  // every key absent takes the struct's default: written once
    common::IniSection s(src, section);
    origin_ = common::configOrigin(src) + ": [" + section + "]";
    mapFile = s.text("map", mapFile);
    if (!mapFile.empty()) {
        // a relative path is the INI's: the file works from any folder, and effective.ini
        // keeps the resolved path
        namespace fs = std::filesystem;
        mapFile = common::pathFromIni(common::configOrigin(src), mapFile);
        if (fs::is_directory(mapFile))
            s.fail("map", "'" + common::pathInWords(mapFile) + "' is a folder, not a .poly file");
        if (!fs::exists(mapFile))
            s.fail("map", "no such file '" + common::pathInWords(mapFile) +
                              "' (a relative path is taken from the INI's folder)");
    }
    generator = s.choice("generator", "steps", {"steps", "rooms"});
    if (!mapFile.empty() && s.has("generator"))
        s.fail("generator", "give either map = <file.poly> or a generator, not both");
    steps.steps = (int)s.integer("steps", long(steps.steps), 1, 1000);
    steps.branchesPerStep =
        (int)s.integer("branches_per_step", long(steps.branchesPerStep), 1, 100);
    steps.stepWidth = s.real("step_width", steps.stepWidth, 1e-3, 1e4);
    steps.stepRise = s.real("step_rise", steps.stepRise, 1e-3, 1e4);
    steps.corridorHeight = s.real("corridor_height", steps.corridorHeight, 1e-3, 1e4);
    steps.branchWidth = s.real("branch_width", steps.branchWidth, 1e-3, 1e4);
    steps.branchLeg = s.real("branch_leg", steps.branchLeg, 1e-3, 1e4);
    rooms.rooms = (int)s.integer("rooms", long(rooms.rooms), 1, 1000);
    rooms.roomSteps = (int)s.integer("room_steps", long(rooms.roomSteps), 1, 1000);
    rooms.roomWidth = s.real("room_width", rooms.roomWidth, 1e-3, 1e4);
    rooms.roomHeightMin = s.real("room_height_min", rooms.roomHeightMin, 1e-3, 1e4);
    rooms.roomHeightMax = s.real("room_height_max", rooms.roomHeightMax, 1e-3, 1e4);
    rooms.neckWidth = s.real("neck_width", rooms.neckWidth, 1e-3, 1e4);
    rooms.neckLength = s.real("neck_length", rooms.neckLength, 1e-3, 1e4);
    rooms.roomGap = s.real("room_gap", rooms.roomGap, 1e-3, 1e4);
    rooms.rightMargin = s.real("right_margin", rooms.rightMargin, 0, 1e4);
    mapSeed = (unsigned long)s.integer("map_seed", long(mapSeed), 0, 4294967295L);
    start.reset();
    if (s.has("start")) {
        const auto xy = s.requireReals("start", 2);
        start = TPoint2D{xy[0], xy[1]};
        if (s.has("start_site")) s.fail("start_site", "give either start = x y or start_site");
    }
    startSite = (int)s.integer("start_site", long(startSite), 1, 1000000);
    if (!start && !mapFile.empty()) s.fail("start", "required with a map file (start = x y)");
    heading = s.real("heading", heading, -360, 360);
    scanRays = (int)s.integer("scan_rays", long(scanRays), 16, 100000);
    scanRangeSigma = s.real("scan_range_sigma", scanRangeSigma, 0, 10);
    scanMaxRange = s.real("scan_max_range", scanMaxRange, 1e-3, 1e6);
    scanRate = s.real("scan_rate", scanRate, 0, 1000);
    tolerance = s.real("tolerance", tolerance, 0, 1e3);
    angleTolerance = s.real("angle_tolerance", angleTolerance, 1e-6, 45);
    breakAngle = s.real("break_angle", breakAngle, 1, 45);
    elimination.clear();
    std::istringstream names(s.text("elimination", "none"));
    std::vector<std::string> list{std::istream_iterator<std::string>(names), {}};
    if (list == std::vector<std::string>{"all"})
        list = {"cells", "randomized", "triangulation", "windows"};
    if (list != std::vector<std::string>{"none"})
        for (const auto& name : list) try {
                elimination.push_back(strategyFromName(name));
            } catch (const Error& e) {
                s.fail("elimination", std::string(e.what()) + " (or none, all)");
            }
    randomPoints.clear();
    for (const double x : s.reals("random_points", {100, 500})) {
        if (x < 1 || x > 1e6 || x != std::floor(x))
            s.fail("random_points", "each X must be a whole number from 1 to 1000000");
        randomPoints.push_back((int)x);
    }
    if (randomPoints.empty()) s.fail("random_points", "give at least one X");
    if (randomPoints.size() > kMaxListValues)  // each X is a column of the whole experiment
        s.fail("random_points", "at most " + std::to_string(kMaxListValues) + " values");
    eliminationSeed =
        (unsigned long)s.integer("elimination_seed", long(eliminationSeed), 0, 4294967295L);
    clearance = s.real("clearance", clearance, 0, 10);
    sweepSteps.clear();
    for (const double x : s.reals("sweep_steps", {})) {
        if (x < 1 || x > 1000 || x != std::floor(x))
            s.fail("sweep_steps", "each step count must be a whole number from 1 to 1000");
        sweepSteps.push_back((int)x);
    }
    if (sweepSteps.size() > kMaxSweepSteps)  // each is a map, every start, every algorithm
        s.fail("sweep_steps", "at most " + std::to_string(kMaxSweepSteps) + " values");
    if (!sweepSteps.empty() && (!mapFile.empty() || generator != "steps"))
        s.fail("sweep_steps", "the sweep is over steps maps: needs generator = steps");
    if (!sweepSteps.empty() && elimination.empty())
        s.fail("sweep_steps", "give the algorithms to sweep in elimination = ...");
    sweepStarts = (int)s.integer("sweep_starts", long(sweepStarts), 1, 100000);
    drive.reset();
    if (const std::string d = s.text("drive", "none"); d != "none") {
        try {
            drive = strategyFromName(d);
        } catch (const Error& e) {
            s.fail("drive", std::string(e.what()) + " (or none)");
        }
        if (scanRate > 0)
            s.fail("drive", "a driving robot scans where it eliminates: set scan_rate = 0");
    }
    s.finish();
}

void PolymapOptions::saveToConfigFile(mrpt::config::CConfigFileBase& t,
                                      const std::string& section) const {
    if (!mapFile.empty()) {
        t.write(section, "map", mapFile);
    } else {
        t.write(section, "generator", generator);
        t.write(section, "map_seed", std::to_string(mapSeed));
    }
    t.write(section, "steps", steps.steps);
    t.write(section, "branches_per_step", steps.branchesPerStep);
    t.write(section, "step_width", steps.stepWidth);
    t.write(section, "step_rise", steps.stepRise);
    t.write(section, "corridor_height", steps.corridorHeight);
    t.write(section, "branch_width", steps.branchWidth);
    t.write(section, "branch_leg", steps.branchLeg);
    t.write(section, "rooms", rooms.rooms);
    t.write(section, "room_steps", rooms.roomSteps);
    t.write(section, "room_width", rooms.roomWidth);
    t.write(section, "room_height_min", rooms.roomHeightMin);
    t.write(section, "room_height_max", rooms.roomHeightMax);
    t.write(section, "neck_width", rooms.neckWidth);
    t.write(section, "neck_length", rooms.neckLength);
    t.write(section, "room_gap", rooms.roomGap);
    t.write(section, "right_margin", rooms.rightMargin);
    if (start)
        t.write(section, "start", mrpt::format("%.17g %.17g", start->x, start->y));
    else
        t.write(section, "start_site", startSite);
    t.write(section, "heading", heading);
    t.write(section, "scan_rays", scanRays);
    t.write(section, "scan_range_sigma", scanRangeSigma);
    t.write(section, "scan_max_range", scanMaxRange);
    t.write(section, "scan_rate", scanRate);
    t.write(section, "tolerance", tolerance);
    t.write(section, "angle_tolerance", angleTolerance);
    t.write(section, "break_angle", breakAngle);
    std::string names;
    for (const auto e : elimination) names += (names.empty() ? "" : " ") + strategyName(e);
    t.write(section, "elimination", names.empty() ? std::string("none") : names);
    std::string xs;
    for (const int x : randomPoints) xs += (xs.empty() ? "" : " ") + std::to_string(x);
    t.write(section, "random_points", xs);
    t.write(section, "elimination_seed", std::to_string(eliminationSeed));
    t.write(section, "clearance", clearance);
    std::string sweep;
    for (const int x : sweepSteps) sweep += (sweep.empty() ? "" : " ") + std::to_string(x);
    if (!sweep.empty()) t.write(section, "sweep_steps", sweep);
    t.write(section, "sweep_starts", sweepStarts);
    t.write(section, "drive", drive ? strategyName(*drive) : std::string("none"));
}

EliminationOptions PolymapOptions::driveOptions(double tolerance) const {
    EliminationOptions o;
    o.strategy = drive.value_or(ProbeStrategy::Windows);
    o.randomPoints = randomPoints.front();
    o.seed = (uint32_t)eliminationSeed;
    o.tolerance = tolerance;
    o.clearance = clearance;
    o.sensorBeams = scanRays;                      // the scanner the probes are for
    o.rangeTolerance = 6 * scanRangeSigma + 0.01;  // a beam's error bound
    return o;
}

GeneratedMap PolymapOptions::buildMap() const {
    if (!mapFile.empty()) {
        auto P = common::Polygon::load(mapFile);
        return {std::move(P), {}, "map " + mapFile};
    }
    if (generator == "steps") return stepsMap(steps);
    mrpt::random::CRandomGenerator rng{static_cast<uint32_t>(mapSeed)};
    return roomsMap(rooms, rng);
}

TPoint2D PolymapOptions::startIn(const GeneratedMap& map) const {
    if (start) return *start;
    if (size_t(startSite) > map.sites.size())
        throw Error(origin_ + mrpt::format(" start_site: %d, but the %s has %zu sites", startSite,
                                           map.description.c_str(), map.sites.size()));
    return map.sites[size_t(startSite) - 1];
}

double PolymapOptions::toleranceFor(double rMax) const {
    if (tolerance > 0) return tolerance;
    return 6 * scanRangeSigma + 2 * M_PI / scanRays * rMax + 0.01;
}

}  // namespace mrloc::polymap
