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

void PolymapOptions::loadScanKeys(common::IniSection& s, const std::string& iniPath) {
    scan.positionStep = s.real("search_step", scan.positionStep, 0.02, 5);
    scan.headingStep = s.real("heading_step", scan.headingStep, 0.25, 30);
    scan.maxPositions =
        size_t(s.integer("search_positions", long(scan.maxPositions), 100, 1000000));
    beamTolerance = s.real("beam_tolerance", beamTolerance, 0, 5);
    scan.keepMargin = s.real("keep_margin", scan.keepMargin, 0, 1);
    scan.minAgreement = s.real("min_agreement", scan.minAgreement, 0.05, 1);
    scan.maxThrough = s.real("max_through", scan.maxThrough, 0, 1);
    scan.maxClutter = s.real("max_clutter", scan.maxClutter, 0, 1);
    scan.maxHypotheses = size_t(s.integer("max_hypotheses", long(scan.maxHypotheses), 1, 2000));
    trace.resolution = s.real("grid_resolution", trace.resolution, 0.01, 1);
    trace.occupied = s.real("trace_occupied", trace.occupied, 0.01, 0.5);
    trace.free = s.real("trace_free", trace.free, 0.5, 0.99);
    trace.speckCells = int(s.integer("speck_cells", trace.speckCells, 1, 10000));
    trace.simplify = s.real("trace_simplify", trace.simplify, 0, 1);
    trace.clearance = s.real("free_clearance", trace.clearance, 0, 2);
    referenceFile = s.text("reference", "");
    if (!referenceFile.empty()) {
        referenceFile = common::pathFromIni(iniPath, referenceFile);
        if (!std::filesystem::is_regular_file(referenceFile))
            s.fail("reference", "no such file '" + common::pathInWords(referenceFile) + "'");
    }
    referenceName = s.text("reference_name", referenceFile.empty() ? "" : "the reference");
    scan.region.reset();
    if (s.has("region")) {
        const auto r = s.requireReals("region", 4);
        if (!(r[0] < r[1] && r[2] < r[3]))
            s.fail("region", "expected xmin xmax ymin ymax with xmin < xmax and ymin < ymax");
        scan.region = std::make_pair(TPoint2D{r[0], r[2]}, TPoint2D{r[1], r[3]});
    }
}

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
    std::vector<std::string> layouts;
    for (const auto l : kRoomsLayouts) layouts.push_back(roomsLayoutName(l));
    rooms.layout = roomsLayoutFromName(s.choice("room_layout", "side", layouts));
    rooms.rooms = (int)s.integer("rooms", long(rooms.rooms), 1, 1000);
    rooms.roomSteps = (int)s.integer("room_steps", long(rooms.roomSteps), 1, 1000);
    rooms.roomWidth = s.real("room_width", rooms.roomWidth, 1e-3, 1e4);
    rooms.roomHeightMin = s.real("room_height_min", rooms.roomHeightMin, 1e-3, 1e4);
    rooms.roomHeightMax = s.real("room_height_max", rooms.roomHeightMax, 1e-3, 1e4);
    rooms.neckWidth = s.real("neck_width", rooms.neckWidth, 1e-3, 1e4);
    rooms.neckLength = s.real("neck_length", rooms.neckLength, 1e-3, 1e4);
    rooms.roomGap = s.real("room_gap", rooms.roomGap, 1e-3, 1e4);
    rooms.rightMargin = s.real("right_margin", rooms.rightMargin, 0, 1e4);
    if (rooms.layout == RoomsLayout::Row)
        for (const char* key : {"room_gap", "right_margin"})  // a row has no corridor
            if (s.has(key))
                s.fail(key, "not used by room_layout = row (rooms joined wall to wall)");
    rooms.pillar = s.real("pillar", rooms.pillar, 0, 1e3);
    const unsigned long seed = common::runSeed(src);
    mapSeed = common::subSeed(s, "map_seed", seed, "polymap rooms map");
    start.reset();
    if (s.has("start")) {
        const auto xy = s.requireReals("start", 2);
        start = TPoint2D{xy[0], xy[1]};
        if (s.has("start_site")) s.fail("start_site", "give either start = x y or start_site");
    }
    startSite = (int)s.integer("start_site", long(startSite), 1, 1000000);
    const bool mrptMap = isMrptMapFile(mapFile);
    const std::string mode = s.choice("localizer", "auto", {"auto", "exact", "scan"});
    // a .poly with holes (rings after blank lines) needs the scan localizer too
    const bool holes = !mrptMap && !mapFile.empty() && mode == "auto" &&
                       common::Polygon::readRings(mapFile, kMaxWallVertices, kMaxRings).size() > 1;
    scanMode = mode == "scan" || (mode == "auto" && (mrptMap || holes));
    if (!scanMode && mrptMap)
        s.fail("localizer", "exact needs a .poly map; an MRPT grid map is localized with scan");
    if (!start && !mapFile.empty() && !scanMode)
        s.fail("start", "required with a map file (start = x y)");
    headingKnown = s.has("heading");
    heading = s.real("heading", heading, -360, 360);
    loadScanKeys(s, common::configOrigin(src));
    // MRPT's own section for how a simplemap's scans go into the grid, when the INI holds it
    // (pf-localization's INIs; and effective.ini of a run from one)
    if (src.sectionExists(kGridInsertSection)) {
        trace.insertOptions = &src;
        trace.insertSection = kGridInsertSection;
    }
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
    eliminationSeed = common::subSeed(s, "elimination_seed", seed, "polymap elimination");
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
    if (scanMode && !elimination.empty())
        s.fail("elimination", "paper 002's experiment runs on exact views (localizer = exact)");
    s.finish();
}

void PolymapOptions::saveToConfigFile(mrpt::config::CConfigFileBase& t,
                                      const std::string& section) const {
    if (!mapFile.empty()) {
        t.write(section, "map", mapFile);
    } else {
        t.write(section, "generator", generator);
        if (mapSeed.given) t.write(section, "map_seed", std::to_string(mapSeed.value));
    }
    t.write(section, "steps", steps.steps);
    t.write(section, "branches_per_step", steps.branchesPerStep);
    t.write(section, "step_width", steps.stepWidth);
    t.write(section, "step_rise", steps.stepRise);
    t.write(section, "corridor_height", steps.corridorHeight);
    t.write(section, "branch_width", steps.branchWidth);
    t.write(section, "branch_leg", steps.branchLeg);
    t.write(section, "room_layout", roomsLayoutName(rooms.layout));
    t.write(section, "rooms", rooms.rooms);
    t.write(section, "room_steps", rooms.roomSteps);
    t.write(section, "room_width", rooms.roomWidth);
    t.write(section, "room_height_min", rooms.roomHeightMin);
    t.write(section, "room_height_max", rooms.roomHeightMax);
    t.write(section, "neck_width", rooms.neckWidth);
    t.write(section, "neck_length", rooms.neckLength);
    if (rooms.layout != RoomsLayout::Row) t.write(section, "room_gap", rooms.roomGap);
    if (rooms.layout != RoomsLayout::Row) t.write(section, "right_margin", rooms.rightMargin);
    t.write(section, "pillar", rooms.pillar);
    if (start)
        t.write(section, "start", mrpt::format("%.17g %.17g", start->x, start->y));
    else
        t.write(section, "start_site", startSite);
    if (headingKnown || !scanMode) t.write(section, "heading", heading);  // absent: unknown
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
    if (eliminationSeed.given)
        t.write(section, "elimination_seed", std::to_string(eliminationSeed.value));
    t.write(section, "clearance", clearance);
    std::string sweep;
    for (const int x : sweepSteps) sweep += (sweep.empty() ? "" : " ") + std::to_string(x);
    if (!sweep.empty()) t.write(section, "sweep_steps", sweep);
    t.write(section, "sweep_starts", sweepStarts);
    t.write(section, "drive", drive ? strategyName(*drive) : std::string("none"));
    t.write(section, "localizer", std::string(scanMode ? "scan" : "exact"));
    if (!scanMode) return;
    t.write(section, "search_step", scan.positionStep);
    t.write(section, "heading_step", scan.headingStep);
    t.write(section, "search_positions", int(scan.maxPositions));
    t.write(section, "beam_tolerance", beamTolerance);
    t.write(section, "keep_margin", scan.keepMargin);
    t.write(section, "min_agreement", scan.minAgreement);
    t.write(section, "max_through", scan.maxThrough);
    t.write(section, "max_clutter", scan.maxClutter);
    t.write(section, "max_hypotheses", int(scan.maxHypotheses));
    t.write(section, "grid_resolution", trace.resolution);
    t.write(section, "trace_occupied", trace.occupied);
    t.write(section, "trace_free", trace.free);
    t.write(section, "speck_cells", trace.speckCells);
    t.write(section, "trace_simplify", trace.simplify);
    t.write(section, "free_clearance", trace.clearance);
    if (!referenceFile.empty()) {
        t.write(section, "reference", referenceFile);
        t.write(section, "reference_name", referenceName);
    }
    if (scan.region)
        t.write(section, "region",
                mrpt::format("%.17g %.17g %.17g %.17g", scan.region->first.x, scan.region->second.x,
                             scan.region->first.y, scan.region->second.y));
}

void PolymapOptions::loadFromMrptLocalizationIni(const mrpt::config::CConfigFileBase& ini) {
    *this = PolymapOptions{};
    const std::string section = "LocalizationExperiment";
    origin_ = common::configOrigin(ini) + ": [" + section + "]";
    const std::string named = ini.read_string(section, "map_file", "");
    if (named.empty())
        throw Error(origin_ + " map_file: required (the map pf-localization localizes in)");
    namespace fs = std::filesystem;
    mapFile = common::pathFromIni(common::configOrigin(ini), named);
    if (!fs::is_regular_file(mapFile))
        throw Error(origin_ + " map_file: no such file '" + common::pathInWords(mapFile) +
                    "' (a relative path is taken from the INI's folder)");
    if (!isMrptMapFile(mapFile))
        throw Error(origin_ + " map_file: '" + common::pathInWords(mapFile) +
                    "' is not a .gridmap or .simplemap");
    scanMode = true;
    // pf-localization's init_PDF box (MRPT's defaults when absent), where it spreads its
    // particles: the same prior for the search
    const auto read = [&](const char* key, double def) {
        const double v = ini.read_double(section, key, def);
        if (!std::isfinite(v) || std::abs(v) > common::Polygon::kMaxCoordinate)
            throw Error(origin_ + " " + key + ": " + std::to_string(v) + " is not a coordinate");
        return v;
    };
    const double x0 = read("init_PDF_min_x", -10), x1 = read("init_PDF_max_x", 10);
    const double y0 = read("init_PDF_min_y", -10), y1 = read("init_PDF_max_y", 10);
    if (!(x0 < x1 && y0 < y1))
        throw Error(origin_ + " init_PDF_min_x .. init_PDF_max_y: an empty box");
    scan.region = std::make_pair(TPoint2D{x0, y0}, TPoint2D{x1, y1});
    // the grid MRPT builds from a simplemap, with the INI's resolution and insertion options
    const std::string grid = "MetricMap_occupancyGrid_00_";  // kGridInsertSection's map
    const double res = ini.read_double(grid + "creationOpts", "resolution", trace.resolution);
    if (!(res >= 0.01 && res <= 1))
        throw Error(common::configOrigin(ini) + ": [" + grid +
                    "creationOpts] resolution: expected 0.01 to 1 m");
    trace.resolution = res;
    if (ini.sectionExists(kGridInsertSection)) {
        trace.insertOptions = &ini;
        trace.insertSection = kGridInsertSection;
    }
}

EliminationOptions PolymapOptions::driveOptions(double tolerance) const {
    EliminationOptions o;
    o.strategy = drive.value_or(ProbeStrategy::Windows);
    o.randomPoints = randomPoints.front();
    o.seed = (uint32_t)eliminationSeed.value;
    o.tolerance = tolerance;
    o.clearance = clearance;
    o.sensorBeams = scanRays;                      // the scanner the probes are for
    o.rangeTolerance = 6 * scanRangeSigma + 0.01;  // a beam's error bound
    o.sensorMaxRange = scanMaxRange;
    return o;
}

GeneratedMap PolymapOptions::buildMap() const {
    if (!mapFile.empty()) {
        auto P = common::Polygon::load(mapFile);
        return {std::move(P), {}, "map " + mapFile};
    }
    if (generator == "steps") return stepsMap(steps);
    mrpt::random::CRandomGenerator rng{static_cast<uint32_t>(mapSeed.value)};
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
