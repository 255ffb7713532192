#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/KeyTable.h>
#include <mrloc/common/MrptKeys.h>
#include <mrloc/polymap/PolymapOptions.h>
#include <mrpt/core/format.h>

#include <cmath>
#include <filesystem>
#include <iterator>
#include <sstream>

namespace mrloc::polymap {

namespace {

std::vector<std::pair<std::string, RoomsLayout>> layoutWords() {
    std::vector<std::pair<std::string, RoomsLayout>> words;
    for (const auto l : kRoomsLayouts) words.push_back({roomsLayoutName(l), l});
    return words;
}

bool scanModeOf(const PolymapOptions& o) { return o.scanMode; }

}  // namespace

const common::KeyTable<PolymapOptions>& PolymapOptions::keys() {
    using Opt = PolymapOptions;
    const auto generated = [](const Opt& o) { return o.mapFile.empty(); };
    const auto corridor = [](const Opt& o) { return o.rooms.layout != RoomsLayout::Row; };
    static const auto table =
        common::KeyTable<Opt>("polymap")
            .custom(
                "map", "", "",
                "a `.poly` file (one `x y` vertex per line, `#` comments; rings separated by "
                "blank lines: the outer boundary, then holes), or MRPT's `.gridmap(.gz)` / "
                "`.simplemap(.gz)` (traced into rings, doc/polymap.md); a relative path is "
                "taken from the INI's own folder (effective.ini keeps the resolved path); a "
                "missing file or a folder is refused naming the key; excludes `generator`",
                [](common::IniSection& s, Opt& o) {
                    o.mapFile = s.text("map", o.mapFile);
                    if (o.mapFile.empty()) return;
                    // a relative path is the INI's: the file works from any folder, and
                    // effective.ini keeps the resolved path
                    namespace fs = std::filesystem;
                    o.mapFile = common::pathFromIni(common::configOrigin(s.config()), o.mapFile);
                    if (fs::is_directory(o.mapFile))
                        s.fail("map", "'" + common::pathInWords(o.mapFile) +
                                          "' is a folder, not a .poly file");
                    if (!fs::exists(o.mapFile))
                        s.fail("map", "no such file '" + common::pathInWords(o.mapFile) +
                                          "' (a relative path is taken from the INI's folder)");
                },
                [](const Opt& o) -> std::optional<std::string> {
                    if (o.mapFile.empty()) return std::nullopt;
                    return o.mapFile;
                })
            .choice("generator", MRLOC_KEY_FIELD(generator), {"steps", "rooms"},
                    "`steps` (paper 002's staircase) or `rooms` (a random room repeated along a "
                    "corridor)")
            .savedOnlyIf(generated)
            .subSeed("map_seed", MRLOC_KEY_FIELD(mapSeed), "polymap rooms map",
                     "the rooms generator's seed: absent, drawn from `[scenario] seed` (purpose "
                     "`polymap rooms map`); given, it fixes the map whatever the seed, and the "
                     "report names it")
            .savedOnlyIf(generated)
            .integer("steps", MRLOC_KEY_FIELD(steps.steps), 1, 1000, "",
                     "steps: n = steps * (4 + 10 * branches_per_step) + 4")
            .integer("branches_per_step", MRLOC_KEY_FIELD(steps.branchesPerStep), 1, 100, "",
                     "branches on each step's ceiling; k = steps * branches_per_step")
            .real("step_width", MRLOC_KEY_FIELD(steps.stepWidth), {1e-3, 1e4}, "m", "a step's run")
            .real("step_rise", MRLOC_KEY_FIELD(steps.stepRise), {1e-3, 1e4}, "m",
                  "a step's rise: below `corridor_height`, the steps see into each other; from "
                  "it on, a shaft joins them")
            .real("shaft_width", MRLOC_KEY_FIELD(steps.shaftWidth), {1e-3, 1e4}, "m",
                  "the shaft from a step's right end up to the next step, when `step_rise` >= "
                  "`corridor_height`")
            .real("corridor_height", MRLOC_KEY_FIELD(steps.corridorHeight), {1e-3, 1e4}, "m",
                  "the staircase corridor's height")
            .real("branch_width", MRLOC_KEY_FIELD(steps.branchWidth), {1e-3, 1e4}, "m",
                  "a branch is a corridor with three bends")
            .real("branch_leg", MRLOC_KEY_FIELD(steps.branchLeg), {1e-3, 1e4}, "m",
                  "each of its legs")
            .choice("room_layout", MRLOC_KEY_FIELD(rooms.layout), layoutWords(),
                    "`side`: the rooms above one corridor, each through a neck; `mirrored`: "
                    "also their mirror images below the corridor, facing them (not congruent: "
                    "the sites are the upper rooms); `row`: rooms joined wall to wall by "
                    "Z-shaped passages (width min(`neck_width`, (`room_height_min` - 0.5) / 3), "
                    "length `neck_length` each leg) that no sight line passes, the two end "
                    "rooms with dead-end passages, so every room looks the same from inside")
            .integer("rooms", MRLOC_KEY_FIELD(rooms.rooms), 1, 1000, "",
                     "copies of the room: n = 4 + rooms * (6 + 2 * room_steps)")
            .integer("room_steps", MRLOC_KEY_FIELD(rooms.roomSteps), 1, 1000, "",
                     "random heights of its ceiling")
            .real("room_width", MRLOC_KEY_FIELD(rooms.roomWidth), {1e-3, 1e4}, "m",
                  "a room's width")
            .real("room_height_min", MRLOC_KEY_FIELD(rooms.roomHeightMin), {1e-3, 1e4}, "m",
                  "its ceiling's lowest")
            .real("room_height_max", MRLOC_KEY_FIELD(rooms.roomHeightMax), {1e-3, 1e4}, "m",
                  "and highest")
            .real("neck_width", MRLOC_KEY_FIELD(rooms.neckWidth), {1e-3, 1e4}, "m",
                  "the neck from the corridor into a room")
            .real("neck_length", MRLOC_KEY_FIELD(rooms.neckLength), {1e-3, 1e4}, "m", "its length")
            .real("room_gap", MRLOC_KEY_FIELD(rooms.roomGap), {1e-3, 1e4}, "m",
                  "between rooms along the corridor; refused with `room_layout = row` (no "
                  "corridor)")
            .savedOnlyIf(corridor)
            .real("right_margin", MRLOC_KEY_FIELD(rooms.rightMargin), {0, 1e4}, "m",
                  "lengthens the corridor's right end; refused with `room_layout = row`")
            .savedOnlyIf(corridor)
            .real("pillar", MRLOC_KEY_FIELD(rooms.pillar), {0, 1e3}, "m",
                  "> 0: a square pillar of that side in every room, the same spot in each copy "
                  "(a hole: half `room_height_min` above the floor, a quarter of `room_width` "
                  "from the wall farther from the site); at most `room_height_min` - 0.25 and "
                  "`room_width` / 4")
            .custom(
                "start", "m", "", "the true start `x y`; required with `map` (exact)",
                [](common::IniSection& s, Opt& o) {
                    o.start.reset();
                    if (!s.has("start")) return (void)s.text("start", "");
                    const auto xy = s.requireReals("start", 2);
                    o.start = TPoint2D{xy[0], xy[1]};
                },
                [](const Opt& o) -> std::optional<std::string> {
                    if (!o.start) return std::nullopt;
                    return common::keyListText({o.start->x, o.start->y});
                })
            .integer("start_site", MRLOC_KEY_FIELD(startSite), 1, 1000000, "",
                     "without `start`: the generator's i-th self-similar site (steps: left to "
                     "right, step by step)")
            .savedOnlyIf([](const Opt& o) { return !o.start; })
            .real("heading", MRLOC_KEY_FIELD(heading), {-360, 360}, "deg",
                  "the robot knows it (translation-only matching). With `localizer = scan` "
                  "absent means unknown (searched)")
            .savedOnlyIf([](const Opt& o) { return o.headingKnown || !o.scanMode; })
            .integer("scan_rays", MRLOC_KEY_FIELD(scanRays), 16, 100000, "",
                     "beams of the 360-degree scanner")
            .real("scan_range_sigma", MRLOC_KEY_FIELD(scanRangeSigma), {0, 10}, "m", "range noise")
            .real("scan_max_range", MRLOC_KEY_FIELD(scanMaxRange), {1e-3, 1e6}, "m",
                  "every beam must return (V must be closed)")
            .real("scan_rate", MRLOC_KEY_FIELD(scanRate), {0, 1000}, "Hz",
                  "0: one scan at the start")
            .real("tolerance", MRLOC_KEY_FIELD(tolerance), {0, 1e3}, "m",
                  "largest boundary distance between the sensed V and V(h); 0: 6 sigma + beam "
                  "step x farthest range + 1 cm")
            .real("angle_tolerance", MRLOC_KEY_FIELD(angleTolerance), {1e-6, 45}, "deg",
                  "for matching the edge directions at a corner")
            .real("break_angle", MRLOC_KEY_FIELD(breakAngle), {1, 45}, "deg",
                  "beams meeting a wall at a shallower angle count as a depth jump (a window)")
            .custom(
                "elimination", "", "none, all, or cells randomized triangulation windows",
                "after localization, paper 002's experiment (Tables 1-2): every hypothesis in "
                "turn the truth, each listed algorithm eliminates in closed loop with exact "
                "views (doc/polymap.md)",
                [](common::IniSection& s, Opt& o) {
                    o.elimination.clear();
                    std::istringstream names(s.text("elimination", "none"));
                    std::vector<std::string> list{std::istream_iterator<std::string>(names), {}};
                    if (list == std::vector<std::string>{"all"})
                        list = {"cells", "randomized", "triangulation", "windows"};
                    if (list != std::vector<std::string>{"none"})
                        for (const auto& name : list) try {
                                o.elimination.push_back(strategyFromName(name));
                            } catch (const Error& e) {
                                s.fail("elimination", std::string(e.what()) + " (or none, all)");
                            }
                },
                [](const Opt& o) {
                    std::string names;
                    for (const auto e : o.elimination)
                        names += (names.empty() ? "" : " ") + strategyName(e);
                    return names.empty() ? std::string("none") : names;
                })
            .numbers("random_points", MRLOC_KEY_FIELD(randomPoints), {1, 1e6, kMaxListValues, 1},
                     "", "X of the randomized algorithm: one column per value")
            .subSeed("elimination_seed", MRLOC_KEY_FIELD(eliminationSeed), "polymap elimination",
                     "seed of the randomized algorithm's points (the experiment's and the "
                     "drive's): absent, drawn from `[scenario] seed` (purpose `polymap "
                     "elimination`); given, an override the report names")
            .real("clearance", MRLOC_KEY_FIELD(clearance), {0, 10}, "m",
                  "probes keep this far from the overlay region's boundary and see no wall "
                  "edge-on")
            .numbers("sweep_steps", MRLOC_KEY_FIELD(sweepSteps), {1, 1000, kMaxSweepSteps}, "",
                     "step counts of steps maps (the run's other steps keys) for paper 002's "
                     "Figs. 6-7: mean path and time of each `elimination` algorithm against n; "
                     "needs `generator = steps`")
            .savedOnlyIf([](const Opt& o) { return !o.sweepSteps.empty(); })
            .integer("sweep_starts", MRLOC_KEY_FIELD(sweepStarts), 1, 100000, "",
                     "at most this many starts per swept map, evenly spread")
            .custom(
                "drive", "", "none, cells, randomized, triangulation, windows",
                "the simulated robot eliminates with this algorithm (`randomized` with the "
                "first `random_points`): it drives to each probe, turns to `heading`, scans, "
                "until one hypothesis is left; `mrloc localize` replays it from the rawlog. "
                "Needs `scan_rate = 0` and a `[scenario] duration` long enough to drive (0.3 "
                "m/s)",
                [](common::IniSection& s, Opt& o) {
                    o.drive.reset();
                    const std::string d = s.text("drive", "none");
                    if (d == "none") return;
                    try {
                        o.drive = strategyFromName(d);
                    } catch (const Error& e) {
                        s.fail("drive", std::string(e.what()) + " (or none)");
                    }
                    if (o.scanRate > 0)
                        s.fail("drive",
                               "a driving robot scans where it eliminates: set scan_rate = 0");
                },
                [](const Opt& o) { return o.drive ? strategyName(*o.drive) : std::string("none"); })
            .custom(
                "localizer", "", "auto, exact, scan",
                "`exact` (paper 002's visibility polygons: a polygon, holes allowed, 360-degree "
                "scans, heading known; an MRPT grid map is traced into one, the free space "
                "around `start`) or `scan` (real scans of any field of view, heading "
                "unknown unless `heading` is given, passive elimination as the robot drives); "
                "`auto`: `scan` for a grid map or a `.poly` with holes, else `exact`. An INI of "
                "MRPT's pf-localization (with `[MetricMap_occupancyGrid_00_creationOpts]`, no "
                "`[polymap]`) runs `scan` with its `[LocalizationExperiment] map_file` and "
                "`init_PDF_*` box",
                [](common::IniSection& s, Opt& o) {
                    const bool mrptMap = isMrptMapFile(o.mapFile);
                    const std::string mode =
                        s.choice("localizer", "auto", {"auto", "exact", "scan"});
                    // a .poly with holes (rings after blank lines) needs the scan localizer too
                    const bool holes =
                        !mrptMap && !o.mapFile.empty() && mode == "auto" &&
                        common::Polygon::readRings(o.mapFile, kMaxWallVertices, kMaxRings).size() >
                            1;
                    o.scanMode = mode == "scan" || (mode == "auto" && (mrptMap || holes));
                },
                [](const Opt& o) { return std::string(o.scanMode ? "scan" : "exact"); }, "auto")
            .savedFromHereOnlyIf(scanModeOf)  // the scan localizer's keys
            .real("search_step", MRLOC_KEY_FIELD(scan.positionStep), {0.02, 5}, "m",
                  "(scan) the first scan's grid of positions")
            .real("heading_step", MRLOC_KEY_FIELD(scan.headingStep), {0.25, 30}, "deg",
                  "(scan) the first scan's headings")
            .integer("search_positions", MRLOC_KEY_FIELD(scan.maxPositions), 100, 1000000, "",
                     "(scan) the grid's step grows until the free space (or `region`) holds at "
                     "most this many positions: the first scan's cost stays bounded")
            .real("beam_tolerance", MRLOC_KEY_FIELD(beamTolerance), {0, 5}, "m",
                  "(scan) a beam agrees within this; 0: 3 x the scan's stdError + 2 map cells + "
                  "5 cm")
            .real("keep_margin", MRLOC_KEY_FIELD(scan.keepMargin), {0, 1}, "",
                  "(scan) agreement below the best by more: not a hypothesis; during "
                  "elimination, dropped after two scans running")
            .real("min_agreement", MRLOC_KEY_FIELD(scan.minAgreement), {0.05, 1}, "",
                  "(scan) no hypothesis agrees with fewer of the beams")
            .real("max_through", MRLOC_KEY_FIELD(scan.maxThrough), {0, 1}, "",
                  "(scan) a pose with more of its beams passing through walls is refused; 1: "
                  "no such share (the beam model weighs those beams, doc/polymap.md)")
            .real("max_clutter", MRLOC_KEY_FIELD(scan.maxClutter), {0, 1}, "",
                  "(scan) a pose with more of its beams stopped short in front of a mapped wall "
                  "is refused (the truth of MRPT's two logs: 0.03 and 0.11; their scans in a "
                  "wrong map: 0.48-0.55)")
            .integer("max_hypotheses", MRLOC_KEY_FIELD(scan.maxHypotheses), 1, 2000, "",
                     "(scan) at most this many hypotheses (bounds each scan's cost)")
            .real("grid_resolution", MRLOC_KEY_FIELD(trace.resolution), {0.01, 1}, "m",
                  "the grid MRPT builds from a `.simplemap` (a `.gridmap` has its own); MRPT's "
                  "`[MetricMap_occupancyGrid_00_insertOpts]`, when the INI holds it, says how "
                  "scans go in")
            .real("trace_occupied", MRLOC_KEY_FIELD(trace.occupied), {0.01, 0.5}, "",
                  "a grid cell is a wall below this free probability")
            .real("trace_free", MRLOC_KEY_FIELD(trace.free), {0.5, 0.99}, "",
                  "and free above this one")
            .integer("speck_cells", MRLOC_KEY_FIELD(trace.speckCells), 1, 10000, "cells",
                     "wall blobs of fewer cells are dropped when tracing")
            .real("trace_simplify", MRLOC_KEY_FIELD(trace.simplify), {0, 1}, "m",
                  "the traced rings' simplification tolerance; 0: half a cell (with `localizer "
                  "= exact`: 0.2 m, doc/polymap.md)")
            .real("trace_open", MRLOC_KEY_FIELD(trace.open), {0, 5}, "m",
                  "(exact) free space narrower than this is closed before tracing (laser-fan "
                  "fringes, slits no robot passes); 0: 0.3 m")
            .real("free_clearance", MRLOC_KEY_FIELD(trace.clearance), {0, 2}, "m",
                  "(scan) the scanner stands at least this far from a wall")
            .custom(
                "reference", "", "",
                "(scan) another localizer's path to set the estimates beside (TUM, or `step x "
                "y phi` rows: step i is the i-th action with the sensory frame after it)",
                [](common::IniSection& s, Opt& o) {
                    o.referenceFile = s.text("reference", "");
                    if (o.referenceFile.empty()) return;
                    o.referenceFile =
                        common::pathFromIni(common::configOrigin(s.config()), o.referenceFile);
                    if (!std::filesystem::is_regular_file(o.referenceFile))
                        s.fail("reference",
                               "no such file '" + common::pathInWords(o.referenceFile) + "'");
                },
                [](const Opt& o) -> std::optional<std::string> {
                    if (o.referenceFile.empty()) return std::nullopt;
                    return o.referenceFile;
                })
            .custom(
                "reference_name", "", "", "(scan) whose the reference is, for the report",
                [](common::IniSection& s, Opt& o) {
                    o.referenceName =
                        s.text("reference_name", o.referenceFile.empty() ? "" : "the reference");
                },
                [](const Opt& o) -> std::optional<std::string> {
                    if (o.referenceFile.empty()) return std::nullopt;
                    return o.referenceName;
                },
                "`the reference`")
            .custom(
                "region", "m", "",
                "`xmin xmax ymin ymax` (scan): the robot's position is searched there only",
                [](common::IniSection& s, Opt& o) {
                    o.scan.region.reset();
                    if (!s.has("region")) return (void)s.text("region", "");
                    const auto r = s.requireReals("region", 4);
                    if (!(r[0] < r[1] && r[2] < r[3]))
                        s.fail("region",
                               "expected xmin xmax ymin ymax with xmin < xmax and ymin < ymax");
                    o.scan.region = std::make_pair(TPoint2D{r[0], r[2]}, TPoint2D{r[1], r[3]});
                },
                [](const Opt& o) -> std::optional<std::string> {
                    if (!o.scan.region) return std::nullopt;
                    const auto& r = *o.scan.region;
                    return common::keyListText({r.first.x, r.second.x, r.first.y, r.second.y});
                });
    return table;
}

void PolymapOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& src,
                                        const std::string& section) {
    *this = PolymapOptions{};  // every key absent takes the struct's default: written once
    common::IniSection s(src, section);
    origin_ = common::configOrigin(src) + ": [" + section + "]";
    keys().load(s, *this);
    if (!mapFile.empty() && s.has("generator"))
        s.fail("generator", "give either map = <file.poly> or a generator, not both");
    if (rooms.layout == RoomsLayout::Row)
        for (const char* key : {"room_gap", "right_margin"})  // a row has no corridor
            if (s.has(key))
                s.fail(key, "not used by room_layout = row (rooms joined wall to wall)");
    if (start && s.has("start_site")) s.fail("start_site", "give either start = x y or start_site");
    if (!start && !mapFile.empty() && !scanMode)
        s.fail("start", "required with a map file (start = x y)");
    headingKnown = s.has("heading");
    if (!sweepSteps.empty() && (!mapFile.empty() || generator != "steps"))
        s.fail("sweep_steps", "the sweep is over steps maps: needs generator = steps");
    if (!sweepSteps.empty() && elimination.empty())
        s.fail("sweep_steps", "give the algorithms to sweep in elimination = ...");
    if (scanMode && !elimination.empty())
        s.fail("elimination", "paper 002's experiment runs on exact views (localizer = exact)");
    // MRPT's own section for how a simplemap's scans go into the grid, when the INI holds it
    // (pf-localization's INIs; and effective.ini of a run from one)
    if (src.sectionExists(kGridInsertSection)) {
        trace.insertOptions = &src;
        trace.insertSection = kGridInsertSection;
    }
    s.finish();
}

void PolymapOptions::saveToConfigFile(mrpt::config::CConfigFileBase& t,
                                      const std::string& section) const {
    keys().save(*this, t, section);
}

void PolymapOptions::loadFromMrptLocalizationIni(const mrpt::config::CConfigFileBase& ini) {
    namespace k = common::mrpt_ini;
    *this = PolymapOptions{};
    const std::string section = k::kMapFile.section;
    origin_ = common::configOrigin(ini) + ": [" + section + "]";
    const std::string named = ini.read_string(section, k::kMapFile.name, "");
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
    const auto read = [&](const k::Key& key, double def) {
        const double v = ini.read_double(key.section, key.name, def);
        if (!std::isfinite(v) || std::abs(v) > common::Polygon::kMaxCoordinate)
            throw Error(origin_ + " " + key.name + ": " + std::to_string(v) +
                        " is not a coordinate");
        return v;
    };
    const double x0 = read(k::kInitMinX, -10), x1 = read(k::kInitMaxX, 10);
    const double y0 = read(k::kInitMinY, -10), y1 = read(k::kInitMaxY, 10);
    if (!(x0 < x1 && y0 < y1))
        throw Error(origin_ + " init_PDF_min_x .. init_PDF_max_y: an empty box");
    scan.region = std::make_pair(TPoint2D{x0, y0}, TPoint2D{x1, y1});
    // the grid MRPT builds from a simplemap, with the INI's resolution and insertion options
    const auto& resolution = k::kGridResolution;  // kGridInsertSection's map
    const double res = ini.read_double(resolution.section, resolution.name, trace.resolution);
    if (!(res >= 0.01 && res <= 1))
        throw Error(common::configOrigin(ini) + ": [" + resolution.section + "] " +
                    resolution.name + ": expected 0.01 to 1 m");
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
