#pragma once
// The files the polygon-map localizer writes into the run directory for its report
// section, each defined once, write and read side by side:
//   map.poly                  the map P (common::Polygon's own format)
//   hypotheses.<robot>.txt    the sensed V (robot frame) and the hypotheses H
//   elimination.txt           the elimination experiment: travel per algorithm and start
//   elimination.times.txt     its run times (the one output that differs run to run)
//   elimination.sweep.txt     mean path and time against n (seed 002 Figs. 6-7)
#include <mrloc/polymap/Hypotheses.h>

#include <limits>
#include <string>
#include <vector>

namespace mrloc::polymap {

inline std::string mapFilePath(const std::string& dir) { return dir + "/map.poly"; }

/** One robot's result: V as sensed (robot frame) and H. */
struct HypothesesFile {
    double time = 0;               ///< of the scan (s)
    std::vector<TPoint2D> sensed;  ///< V's vertices, robot frame
    std::vector<Hypothesis> hypotheses;

    static std::string path(const std::string& dir, const std::string& robot);
    void write(const std::string& dir, const std::string& robot) const;
    /** Throws mrloc::Error naming the file and line on a malformed line. */
    static HypothesesFile read(const std::string& dir, const std::string& robot);
};

/** The elimination experiment (seed 002 Tables 1-2): each column an algorithm, each row a
 *  start (H's order, every hypothesis in turn the truth). */
struct EliminationFile {
    struct Column {
        std::string name;                  ///< cells, randomized:X, triangulation, windows
        std::vector<double> travel;        ///< m, per start
        std::vector<int> probes;           ///< per start
        std::vector<int> survivors;        ///< per start: hypotheses left (1: localized)
        /** per start: probes beyond the algorithm's own candidates (Probe::source) */
        std::vector<int> fallbacks;
        std::vector<TPoint2D> route;       ///< the run's true start: its path (map frame)
        std::vector<TPoint2D> stops;       ///< and its probes (map frame)
        std::vector<int> stopsLeft;        ///< hypotheses live after each of them
        std::vector<TPoint2D> candidates;  ///< its first step's candidates (map frame)
    };
    size_t trueStart = 0;  ///< index in H of the run's true start
    /** The first-separation distance (m), a bound on any strategy's travel
     *  (Eliminator::firstSeparation); NaN if none was found. */
    double bound = std::numeric_limits<double>::quiet_NaN();
    std::vector<TPoint2D> overlay;  ///< OI of all hypotheses, placed at the true start
    std::vector<Column> columns;
    /** Per start, the verification tour (m; NaN: not computed, k too large) and its probes'
     *  count: the least travel from that start over the experiment's sites
     *  (polymap/VerificationTour.h). */
    std::vector<double> tour;
    std::vector<int> tourProbes;
    std::vector<TPoint2D> trueTour;       ///< the true start's tour: its probes (map frame)
    std::vector<TPoint2D> trueTourRoute;  ///< and its path (map frame)

    static std::string path(const std::string& dir) { return dir + "/elimination.txt"; }
    void write(const std::string& dir) const;
    static EliminationFile read(const std::string& dir);
};

/** Seconds per localization, [column][start]: kept apart, as the only output that is not
 *  the same from run to run. */
struct EliminationTimes {
    std::vector<std::vector<double>> seconds;

    static std::string path(const std::string& dir) { return dir + "/elimination.times.txt"; }
    void write(const std::string& dir) const;
    static EliminationTimes read(const std::string& dir);
};

/** Seed 002 Figs. 6-7: per steps map and algorithm, the mean path and time over its starts.
 *  The times are in the file too: a sweep's plot is of them. */
struct EliminationSweepFile {
    struct Row {
        int n = 0, k = 0, starts = 0;
        std::string column;      ///< algorithm, as in EliminationFile
        double meanTravel = 0;   ///< m
        double meanSeconds = 0;  ///< per localization
        int notLocalized = 0;    ///< starts that did not end with one hypothesis
    };
    std::vector<Row> rows;

    static std::string path(const std::string& dir) { return dir + "/elimination.sweep.txt"; }
    void write(const std::string& dir) const;
    static EliminationSweepFile read(const std::string& dir);
};

}  // namespace mrloc::polymap
