#pragma once
// Section [polymap]: the map (a .poly file or a generator), the robot's true start and
// heading, its 360-degree scanner, and the hypothesis tolerances. The simulator gets the
// map, start and scanner through the app; the localizer reads the same section.
#include <mrloc/common/IniSection.h>
#include <mrloc/common/KeyTable.h>
#include <mrloc/common/Seeds.h>
#include <mrloc/polymap/Elimination.h>
#include <mrloc/polymap/GridTrace.h>
#include <mrloc/polymap/Hypotheses.h>
#include <mrloc/polymap/MapGenerators.h>
#include <mrloc/polymap/ScanLocalizer.h>
#include <mrloc/polymap/ScanPolygon.h>
#include <mrpt/config/CLoadableOptions.h>

#include <optional>
#include <string>
#include <vector>

namespace mrloc::polymap {

/** Upper bounds on the list keys that multiply the experiment's work (doc/errors.md). */
inline constexpr size_t kMaxListValues = 8;   ///< random_points
inline constexpr size_t kMaxSweepSteps = 20;  ///< sweep_steps
/** MRPT's section of a grid's insertion options (pf-localization's INIs): used to build the
 *  grid of a .simplemap when the INI holds it. */
inline constexpr const char* kGridInsertSection = "MetricMap_occupancyGrid_00_insertOpts";

struct PolymapOptions : public mrpt::config::CLoadableOptions {
    std::string mapFile;  ///< map = <file.poly> (a relative path: from the INI's folder)
    std::string generator = "steps";  ///< generator = steps | rooms (when no map file)
    StepsMapOptions steps;
    RoomsMapOptions rooms;
    /** map_seed: the rooms generator's seed; drawn from the run's seed unless given
     *  (common/Seeds.h) */
    common::SubSeed mapSeed;
    std::optional<TPoint2D> start;  ///< start = x y
    int startSite = 1;              ///< start_site = i: the generator's i-th site
    double heading = 0;             ///< heading (deg): known to the robot
    int scanRays = 1440;            ///< scan_rays
    double scanRangeSigma = 0.005;  ///< scan_range_sigma (m)
    double scanMaxRange = 100;      ///< scan_max_range (m)
    double scanRate = 0;            ///< scan_rate (Hz; 0: one scan at the start)
    double tolerance = 0;           ///< tolerance (m); 0: from the scan (see doc)
    double angleTolerance = 3;      ///< angle_tolerance (deg)
    double breakAngle = 10;         ///< break_angle (deg): scan segmentation
    /** elimination = none | all | a list of cells, randomized, triangulation, windows: the
     *  paper's experiment (seed 002 Tables 1-2) run after localization, every hypothesis in
     *  turn the truth, exact views. */
    std::vector<ProbeStrategy> elimination;
    std::vector<int> randomPoints{100, 500};  ///< random_points: X of each randomized run
    /** elimination_seed: the randomized probes' seed; from the run's seed unless given */
    common::SubSeed eliminationSeed;
    double clearance = 0.1;                   ///< clearance (m), see EliminationOptions
    /** sweep_steps: steps maps of these step counts for seed 002's Figs. 6-7 (mean path and
     *  time against n), with the run's other steps options; empty: no sweep. */
    std::vector<int> sweepSteps;
    int sweepStarts = 12;  ///< sweep_starts: at most this many starts per map, evenly spread
    /** drive = none | cells | randomized | triangulation | windows: the simulated robot
     *  eliminates with this algorithm, driving to each probe and scanning there, and the
     *  localizer replays it from the rawlog (randomized: the first random_points X). */
    std::optional<ProbeStrategy> drive;

    /** localizer = exact | scan (default: scan for a .gridmap, a .simplemap or a .poly with
     *  holes; exact otherwise). exact: seed 002's visibility polygons, 360-degree scans, a
     *  simple polygon; scan: real scans of any field of view, unknown heading, passive
     *  elimination as the robot drives (doc/polymap.md, "Real scans"). */
    bool scanMode = false;
    bool headingKnown = false;  ///< the heading key was given
    ScanLocalizerOptions scan;  ///< search_step, heading_step, beam_tolerance, ...
    double beamTolerance = 0;   ///< beam_tolerance (m); 0: from the scan and the map
    GridTraceOptions trace;     ///< grid_resolution, trace_occupied, trace_free, ...
    /** reference = <file>: another localizer's path to set the estimates beside (MRPT's
     *  pf-localization or icp-slam on a log without ground truth), TUM or "step x y phi";
     *  reference_name says whose it is. */
    std::string referenceFile, referenceName;
    /** The options of pf-localization's INI ([LocalizationExperiment], its map_file, its
     *  init_PDF box as the search region, its grid's resolution and insertion options):
     *  MRPT's demo INI runs unchanged. */
    void loadFromMrptLocalizationIni(const mrpt::config::CConfigFileBase& ini);

    /** The options of the driving robot's elimination, for a scan generated with tolerance. */
    EliminationOptions driveOptions(double tolerance) const;

    /** Every key of [polymap], declared once (loading, effective.ini, doc/ini.md). */
    static const common::KeyTable<PolymapOptions>& keys();

    void loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                            const std::string& section) override;
    void saveToConfigFile(mrpt::config::CConfigFileBase& target,
                          const std::string& section) const override;

    /** The polygon and its sites (none for a map file); throws mrloc::Error. */
    GeneratedMap buildMap() const;
    /** The true start: `start`, or the `start_site`-th site of a generated map. */
    TPoint2D startIn(const GeneratedMap& map) const;
    /** The tolerance used for a scan whose farthest return is rMax: the key's value, or
     *  6 sigma + a beam step times rMax (a window's end is within half a step). */
    double toleranceFor(double rMax) const;

 private:
    std::string origin_;  ///< file, for errors raised after loading
};

}  // namespace mrloc::polymap
