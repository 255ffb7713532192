#pragma once
// The verification tour (Dudek, Romanik and Whitesides, SIAM J. Comput. 27, 1998): with the
// truth known, the shortest travel from the start through points whose views, together,
// tell the truth from every other hypothesis. No strategy, which does not know the truth,
// travels less from that start: its route must visit such points too. Finding it is
// NP-hard; for small k it is found exactly over a finite set of sites by A* search over
// (position, hypotheses ruled out so far), the mask of at most kMaxTourHypotheses bits.
//
// Exact over the sites, so it bounds the continuous tour from above; the first-separation
// distance (Eliminator::firstSeparation) bounds it from below. With every strategy's own
// probes among the sites, the tour is at most each strategy's path from that start.
#include <mrloc/polymap/Elimination.h>

#include <optional>
#include <vector>

namespace mrloc::polymap {

struct VerificationTour {
    std::vector<TPoint2D> probes;  ///< displacements from the start, in visiting order
    double length = 0;             ///< m, shortest paths inside P under the truth
    size_t sites = 0;              ///< the sites that rule out at least one hypothesis
    size_t expanded = 0;           ///< search states expanded
};

/** The search's state holds one bit per hypothesis. */
constexpr size_t kMaxTourHypotheses = 16;

/** The shortest travel from the start of hypothesis `truth` through points of `sites`
 *  (displacements from the start) that, seen from, rule out every other hypothesis by the
 *  elimination's own rule (Eliminator::ruledOut). Nothing if the sites cannot rule them all
 *  out. Throws mrloc::Error for more than kMaxTourHypotheses hypotheses. */
std::optional<VerificationTour> verificationTour(const Eliminator& eliminator, size_t truth,
                                                 const std::vector<TPoint2D>& sites);
/** The tour from every start: over the `shared` sites (their views computed once for all)
 *  and, for start i, the sites ownSites[i] too (its strategies' probes). */
std::vector<std::optional<VerificationTour>> verificationTours(
    const Eliminator& eliminator, const std::vector<TPoint2D>& shared,
    const std::vector<std::vector<TPoint2D>>& ownSites);

}  // namespace mrloc::polymap
