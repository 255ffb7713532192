#pragma once
// Hypothesis generation (seed 002 sec. 2; Guibas-Motwani-Raghavan 1997): given the map P
// and the sensed visibility polygon V, every point p of P with V(p) congruent to V under
// translation.
//
// Not a search over positions: a corner of V (a vertex between two wall pieces) must be a
// vertex of P with the same two edge directions, so each such vertex proposes one
// translation. The most selective corner proposes; every other corner of V must land on a
// matching vertex of P too (a hash lookup); the survivors are refined by least squares over
// their matched corners and verified by computing V(p) exactly and comparing boundaries.
// Without corners (V bounded by windows), a window's near end, a vertex of P with
// one visible edge, proposes instead.
#include <mrloc/common/Polygon.h>
#include <mrloc/polymap/Triangulation.h>
#include <mrloc/polymap/Visibility.h>

#include <functional>
#include <optional>
#include <unordered_map>
#include <vector>

namespace mrloc::polymap {

struct HypothesisOptions {
    /** Largest boundary distance between V and V(p) - p that still counts as the same
     *  view (m); also how far a corner may sit from its map vertex. Must exceed the
     *  sensing error: about 3 range sigmas plus half a beam step times the range. */
    double tolerance = 0.05;
    /** Largest difference in the direction of an edge at a corner (rad). */
    double angleTolerance = 3 * M_PI / 180;
};

struct Hypothesis {
    TPoint2D point;         ///< where the robot would stand in P
    TVector2D translation;  ///< point minus the origin hypothesis' point (seed 002 step 4)
    /** Boundary distance between V and V(point), bounded above (m): the largest vertex
     *  displacement when the two pair vertex by vertex, else sampled. */
    double mismatch = 0;
};

struct HypothesisStats {
    size_t features = 0;  ///< features of V used (corners, else window ends)
    size_t proposed = 0;  ///< translations proposed by the anchor feature (and places proposed by
                          ///< the consensus pass)
    size_t verified = 0;  ///< exact visibility polygons computed
};

class HypothesisGenerator {
 public:
    /** Triangulates P and indexes its vertices by edge directions and by position; P must
     *  outlive this. */
    HypothesisGenerator(const common::Polygon& map, HypothesisOptions options = {});
    /** A verdict on a proposed place p, from its exact view Vp: the mismatch to keep it
     *  with, or nothing to refuse it. */
    using Verify =
        std::function<std::optional<double>(const TPoint2D& p, const VisibilityPolygon& Vp)>;
    /** At most this many consensus places are verified (each costs an exact V(p)). */
    static constexpr size_t kConsensusPlaces = 64;
    /** At most this many places are tried in the consensus pass (each costs a lookup per
     *  feature): a bound on a stranger's map of 20,000 vertices. */
    static constexpr size_t kConsensusGuesses = 50000;
    /** H, sorted by x then y; hypotheses[0] is the origin of the translations. Throws
     *  mrloc::Error if V has no feature to anchor on. A place whose V(p) is beyond the
     *  tolerance of V's boundary gets `secondChance`, if given (a scan's beams against
     *  V(p): a real building's view has slits narrower than a beam step, which a boundary
     *  distance counts in full and the beams pass between). */
    std::vector<Hypothesis> generate(const VisibilityPolygon& V, HypothesisStats* stats = nullptr,
                                     const Verify& secondChance = {}) const;
    const HypothesisOptions& options() const { return options_; }

 private:
    struct Feature {
        TPoint2D at;          ///< position in V's frame
        double inAngle = 0;   ///< direction of the wall arriving (NaN: not seen)
        double outAngle = 0;  ///< direction of the wall leaving (NaN: not seen)
    };
    std::vector<Feature> featuresOf(const VisibilityPolygon& V) const;
    bool matches(const Feature& f, size_t vertex) const;
    /** A vertex of P within tolerance of p matching f, if any. */
    std::optional<size_t> vertexNear(const TPoint2D& p, const Feature& f) const;
    /** The consensus pass: each feature of the map (inMap) anchoring in turn at each vertex
     *  it matches (the rarest features first, at most kConsensusGuesses places tried), the
     *  places where at least 3 of them (all, if fewer) land on matching vertices, refined by
     *  their mean offset, best supported first, one per tolerance, at most kConsensusPlaces. */
    std::vector<TPoint2D> consensusPlaces(const std::vector<Feature>& features,
                                          const std::vector<bool>& inMap) const;

    const common::Polygon& map_;
    Triangulation triangulation_;  ///< for V(p) by triangular expansion and point location
    HypothesisOptions options_;
    std::vector<double> inAngle_, outAngle_;
    double cell_;
    std::unordered_map<long long, std::vector<size_t>> grid_;
};

}  // namespace mrloc::polymap
