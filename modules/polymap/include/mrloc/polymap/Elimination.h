#pragma once
// Hypothesis elimination with little travel (seed 002 steps 4-10): with k hypotheses left,
// the robot travels inside the overlay intersection region OI (a displacement valid under
// every live hypothesis) to a probe point whose view differs between at least two of them,
// senses, keeps the hypotheses whose predicted view matches, and repeats until one is left.
//
// One machinery, four probe strategies (seed 002 sec. 2):
//   - VisibilityCells (algorithm 1, Dudek-Romanik-Whitesides 1998): views change only across
//     the critical chords of OI (a reflex vertex's extension of its sight line to another
//     vertex); the nearest point of each cell lies on a chord, so the candidates are points
//     along every chord, on both of its sides;
//   - Randomized (algorithm 2, Rao-Dudek-Whitesides 2007): X uniform random points of OI;
//   - Triangulation, LUT (algorithm 3): midpoints of the map triangulation's edges and
//     centroids of its triangles, placed at the origin hypothesis, inside OI;
//   - Windows, LUW (algorithm 4): midpoints of OI's windows, the edges of OI that are a wall
//     of some live copies but not of all.
// Every strategy keeps the candidates that separate and goes to the nearest by shortest path
// inside OI. Frame: displacements from the robot's start, axes along the map's.
#include <mrloc/common/Polygon.h>
#include <mrloc/polymap/Overlay.h>
#include <mrloc/polymap/ScanPolygon.h>
#include <mrloc/polymap/ShortestPath.h>
#include <mrloc/polymap/Triangulation.h>
#include <mrloc/polymap/ViewComparison.h>
#include <mrloc/polymap/Visibility.h>
#include <mrpt/obs/CObservation2DRangeScan.h>

#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace mrloc::polymap {

enum class ProbeStrategy { VisibilityCells, Randomized, Triangulation, Windows };

/** "cells", "randomized", "triangulation", "windows" (the INI's names). */
std::string strategyName(ProbeStrategy s);
/** Parses a name of strategyName(); throws mrloc::Error naming the valid ones. */
ProbeStrategy strategyFromName(const std::string& name);

/** Beams a stopping point is refined on (consistentWithScan): a 1440-beam scan is refined on
 *  every fourth beam, which keeps a 20-hypothesis scan under a second. */
constexpr size_t kRefineBeams = 360;

/** Draws of X random points algorithm 2 makes for one probe before it says none separates. */
constexpr size_t kRandomBatches = 20;

/** Views algorithm 4 expands, breadth first from the robot, to find windows' middles. */
constexpr size_t kWindowViews = 256;

struct EliminationOptions {
    ProbeStrategy strategy = ProbeStrategy::Windows;
    int randomPoints = 100;  ///< algorithm 2's X (the paper: 100 and 500)
    uint32_t seed = 1;       ///< algorithm 2's random points
    /** A sensed view matches a predicted one within this boundary distance (m): the
     *  sensing error's bound (the hypothesis generation's tolerance); tiny for exact views.
     *  A candidate separates only if two predicted views differ by more than twice it, so
     *  that every probe eliminates a hypothesis and never the truth. */
    double tolerance = 1e-6;
    /** The scanner the probes are for: 0 for exact views (polygons compared), else its beams
     *  per turn; then a candidate separates two hypotheses only if their predicted ranges
     *  differ by more than 2 x rangeTolerance on over 2 % of the beams, so that a scan, each
     *  beam within rangeTolerance of the truth, is sure to tell them apart. */
    int sensorBeams = 0;
    double rangeTolerance = 0.04;  ///< m: a beam's range error bound (6 sigma + 1 cm)
    /** m: the scanner's reach; predicted ranges beyond it are one (no return), so a probe
     *  whose views differ only farther away does not separate. */
    double sensorMaxRange = std::numeric_limits<double>::infinity();
    /** Probes keep this far from OI's boundary and from the line of every wall they see (m):
     *  the robot stands off the walls, and sees none edge-on (grazing beams make a scan's
     *  polygon worthless). */
    double clearance = 0.1;
};

/** Where a probe came from. Each algorithm tries its own (the paper's) candidates first;
 *  only if none separates does it try, in turn, its candidates completed beyond OI (cells:
 *  the map's critical chords placed at every live hypothesis, not only OI's; windows: the
 *  windows of the hypotheses' views in the map, not only in OI), the triangulation
 *  algorithm's probe, and the union of every algorithm's candidates with the map's chords:
 *  so no algorithm stops while another finds a separating probe (issue 55). */
enum class ProbeSource { Own, Completed, Triangulation, Every };
/** "own", "completed", "triangulation", "every algorithm's" (for reports). */
std::string probeSourceName(ProbeSource s);

/** One probe: where, how the robot gets there, and what the choice cost. */
struct Probe {
    TPoint2D at;            ///< displacement from the start
    GeodesicPath path;      ///< from the previous position, inside OI (displacements)
    size_t candidates = 0;  ///< the strategy's candidates (cells': chord points, cleared lazily)
    size_t tested = 0;      ///< candidates whose views were computed (nearest first)
    double oiArea = 0;      ///< m^2
    ProbeSource source = ProbeSource::Own;  ///< not Own: the algorithm fell back
};

class Eliminator {
 public:
    /** P and the hypotheses' positions (map frame; hypotheses[i] is H's i-th). P must
     *  outlive this. */
    Eliminator(const common::Polygon& P, std::vector<TPoint2D> hypotheses,
               EliminationOptions options);

    /** The next probe for the live hypotheses (indices into the hypotheses), the robot at
     *  displacement `at`; nothing if no candidate of the strategy separates them. Candidates
     *  within `avoidRadius` of a point of `avoid` are skipped (probes whose real scan
     *  separated nothing: the views differ there, but by less than a stopped robot's scan
     *  can tell). */
    std::optional<Probe> chooseProbe(const std::vector<size_t>& live, const TPoint2D& at,
                                     const std::vector<TPoint2D>& avoid = {},
                                     double avoidRadius = 0) const;
    /** The strategy's candidates for the live hypotheses (displacements), and OI: what the
     *  report draws. */
    std::pair<std::vector<TPoint2D>, OverlayRegion> candidatesAndRegion(
        const std::vector<size_t>& live) const;
    /** The first-separation distance: the shortest travel inside OI from `at` to a point
     *  where the live hypotheses' views differ, searched among every strategy's candidates
     *  with OI's critical chords sampled every `spacing` (m) on both sides. Views change only
     *  across those chords, so the nearest separating point lies on one: this is the travel
     *  any strategy needs at least, found from above to within `spacing` plus the clearance.
     *  Nothing if no point separates them. */
    std::optional<double> firstSeparation(const std::vector<size_t>& live, const TPoint2D& at,
                                          double spacing = 0.05) const;
    /** The live hypotheses whose view at displacement `at` matches the sensed one within
     *  `tolerance` (negative: the options'; at most the options', see there). */
    std::vector<size_t> consistent(const std::vector<size_t>& live, const TPoint2D& at,
                                   const VisibilityPolygon& sensed, double tolerance = -1) const;
    /** The live hypotheses that a 360-degree scan taken at displacement `at` (heading known)
     *  agrees with, beam by beam: a beam agrees if its range is within `rangeTolerance` of
     *  the predicted view's, looked up at its direction and half a beam step either side (a
     *  window's end); a hypothesis is kept if at most 1 % of the beams disagree. Comparing
     *  beams, not polygons: a wall seen at grazing incidence breaks a scan's polygon into
     *  pieces but leaves its beams right. With searchRadius > 0 the scan may have been taken
     *  up to that far from `at` (a robot stops near its goal, not on it): the position that
     *  explains the beams best is searched on three nested 7 x 7 grids (to 0.3 mm), with at
     *  most kRefineBeams of the beams (evenly spread: a bounded cost per scan), and counts;
     *  `refined` then receives it for each hypothesis kept. A beam without a return agrees
     * where the predicted view reaches the scanner's max range. Throws mrloc::Error for a
     * scan that is not a full turn (ScanPolygon's beamsOf). */
    std::vector<size_t> consistentWithScan(const std::vector<size_t>& live, const TPoint2D& at,
                                           const mrpt::obs::CObservation2DRangeScan& scan,
                                           double heading, double rangeTolerance,
                                           double searchRadius = 0,
                                           std::vector<TPoint2D>* refined = nullptr) const;
    /** What a view taken at displacement `at` rules out when `truth` is the truth: the
     *  hypotheses whose predicted view there differs from the truth's beyond the tolerance
     *  (consistent()'s rule), or under which `at` is outside P. Nothing if `at` is no probe
     *  under the truth: outside P, or a wall seen edge-on (see clearance). */
    std::optional<std::vector<size_t>> ruledOut(size_t truth, const TPoint2D& at) const {
        return ruledOutByEach(viewsAt(at)).at(truth);
    }
    /** The same for every truth in turn ([truth]), from every hypothesis' view there
     *  (viewsAt), each pair of views compared once. */
    std::vector<std::optional<std::vector<size_t>>> ruledOutByEach(
        const std::vector<std::optional<VisibilityPolygon>>& views) const;
    /** Every hypothesis' view at displacement `at`; nothing where `at` is outside P under it. */
    std::vector<std::optional<VisibilityPolygon>> viewsAt(const TPoint2D& at) const;
    /** The view hypothesis i predicts at displacement `at`: V(p_i + at). */
    VisibilityPolygon viewOf(size_t i, const TPoint2D& at) const;
    /** Same view within `tolerance` (vertex by vertex, else the sampled boundary distance). */
    static bool sameView(const VisibilityPolygon& a, const VisibilityPolygon& b, double tolerance);

    const std::vector<TPoint2D>& hypotheses() const { return hypotheses_; }
    const EliminationOptions& options() const { return options_; }
    const common::Polygon& map() const { return P_; }
    const Triangulation& triangulation() const { return T_; }

 private:
    struct Region;
    std::vector<TPoint2D> positionsOf(const std::vector<size_t>& live) const;
    /** The strategy's candidates in OI (displacements), the robot at `from`. */
    std::vector<TPoint2D> candidates(const std::vector<size_t>& live, const Region& region,
                                     const TPoint2D& from, size_t step, ProbeStrategy strategy,
                                     double chordSpacing, int perChord) const;
    /** Algorithm 1's candidates: points along OI's critical chords, both sides, not yet
     *  checked for clearance (Region::nearest does that for the few it reaches). */
    std::vector<TPoint2D> chordCandidates(const Region& region, double chordSpacing,
                                          int perChord) const;
    /** Algorithm 4's candidates: the middles of the windows of the robot's view in OI from
     *  `from`, and of the views from those middles, breadth first. */
    std::vector<TPoint2D> windowCandidates(const Region& region, const TPoint2D& from) const;
    /** Cells' completion: points along the map's own critical chords placed at every live
     *  hypothesis (displacements; those off OI's box dropped). Each hypothesis' view changes
     *  only across its copy of them, so every cell of views inside OI is bounded by one. */
    std::vector<TPoint2D> mapChordCandidates(const std::vector<size_t>& live, const Region& region,
                                             double chordSpacing, int perChord) const;
    /** Windows' completion: points along the windows of each live hypothesis' view in the
     *  map (not in OI) from `from` and from algorithm 4's middles, both sides. */
    std::vector<TPoint2D> mapWindowCandidates(const std::vector<size_t>& live, const Region& region,
                                              const TPoint2D& from) const;
    /** A critical chord: from a reflex vertex, `length` along the unit direction d. */
    struct Chord {
        TPoint2D from;
        TVector2D d;
        double length = 0;
    };
    /** Every algorithm's candidates, OI's chords every `spacing` (at most perChord per
     *  chord), and both completions: the last resort, and the first-separation search. */
    std::vector<TPoint2D> everyCandidate(const std::vector<size_t>& live, const Region& region,
                                         const TPoint2D& at, double spacing, int perChord) const;
    /** The map's critical chords (its frame), computed once, on first use. */
    const std::vector<Chord>& mapChords() const;
    /** The live hypotheses' views at displacement `at` differ (and none sees a wall
     *  edge-on). */
    bool separates(const std::vector<size_t>& live, const TPoint2D& at) const;

    const common::Polygon& P_;
    Triangulation T_;
    std::vector<TPoint2D> hypotheses_;
    EliminationOptions options_;
    struct ChordCache;
    std::shared_ptr<ChordCache> chords_;  ///< shared by copies: the map's, whatever is live
};

/** One robot's elimination as it happens, scan by scan: what the simulated robot's on-board
 *  part runs, and what `mrloc localize` runs again on the rawlog, so that both take the same
 *  decisions. The robot stands at the start; plan() says where to scan next (a
 *  displacement); the scan taken there goes to observe(), which eliminates and plans again.
 *  The scanner's heading is the known heading at every scan (the robot turns back to it). */
class EliminationSession {
 public:
    /** hypotheses: H's positions (map frame); P must outlive this. */
    EliminationSession(const common::Polygon& P, std::vector<TPoint2D> hypotheses,
                       EliminationOptions options, double heading, double arrivalRadius);
    /** The next probe, or nothing: one hypothesis left, or none separates what is left. */
    const std::optional<Probe>& plan() const { return plan_; }
    /** A scan taken at plan()'s probe. A scan that rules nothing out marks its probe
     *  fruitless: the next plan avoids it (and every fruitless probe since the live set last
     *  shrank), so a session always ends, with one hypothesis or with no plan left. Throws
     *  mrloc::Error if there is no plan. */
    void observe(const mrpt::obs::CObservation2DRangeScan& scan);
    const std::vector<size_t>& live() const { return live_; }
    /** The probes reached so far, in order (displacements). */
    const std::vector<Probe>& visited() const { return visited_; }
    /** Where, at visited probe k, the robot stood under hypothesis i (the displacement that
     *  explains the scan best); for the hypotheses kept there. */
    TPoint2D stoppedAt(size_t k, size_t i) const { return stops_.at(k).at(i); }
    const Eliminator& eliminator() const { return eliminator_; }
    /** Probes since the live set last shrank whose scans kept every live hypothesis. */
    size_t fruitlessProbes() const { return fruitless_.size(); }

 private:
    Eliminator eliminator_;
    double heading_, arrivalRadius_;
    std::vector<size_t> live_;
    std::vector<Probe> visited_;
    std::vector<std::map<size_t, TPoint2D>> stops_;
    std::vector<TPoint2D> fruitless_;  ///< probes whose scan kept every live hypothesis
    std::optional<Probe> plan_;
};

/** A whole elimination in closed loop, the sensor being the exact view from the true
 *  hypothesis (tests, benchmarks, the paper's experiment). */
struct EliminationRun {
    std::vector<Probe> probes;
    std::vector<size_t> survivors;  ///< one, the truth, when it worked
    std::vector<size_t> leftAfter;  ///< hypotheses live after each probe
    double travel = 0;              ///< m, the sum of the probes' paths
};
EliminationRun eliminateExactly(const Eliminator& eliminator, size_t truth);

}  // namespace mrloc::polymap
