#pragma once
// Seed 000 eq. (11)-(12): the proposed method's search at t_b, localized.
//
// At t_e the conventional search has identified every image. At t_b only one triangle is
// needed: the stopped pair A, B and a robot K that both see, and that sees them, at both
// instants. K is therefore sought only among the witnesses of t_e (NM_A^e ∩ NM_B^e,
// eq. (11)), and for one K the search examines |NM_A^b| |NM_B^b| |NM_K^b| image triples
// (eq. (12)): A and B stand still, so A's image of B (and B's of A) is the one at its t_e
// bearing; what remains is A's image of K, B's image of K and K's image of A, and the 180
// degree sum then fixes K's image of B. The search stops at the first witness with a
// triangle, as the paper's does.
//
// Gap filled: with many robots several triples sum to 180 degrees within tolerance by
// chance (eq. (9)'s chance sums: hundreds per witness at N = 30). What the paper's setting
// gives tells the true one, without any robot's heading ("no mobile nodes achieve their
// mobility directions"): a candidate places K at t_b and turns K's view into the frame A and
// B hold (from its image of A); eq. (8) gives |AB| from K's odometer. Every robot K saw at
// t_e stood at t_b within its own odometer distance of its t_e place, so K's view at t_b
// must hold an image inside the angle that disc spans. The true triangle finds nearly all;
// a chance one only what its images hit at random. A candidate is kept when its robots
// found are three binomial deviations above chance with at most a tenth missed; the one
// most above chance is taken, then the one that puts K nearest its t_e place. A witness is
// skipped when a second labelling comes within three robots of it, or when another robot
// seen at t_e, within its odometer's reach, could have made one of the six images (rays of
// other robots crossing near K give nearly the same pose). At most ten witnesses are tried;
// the caller then searches t_b in full (the fall-back the paper names).
// Beyond the paper (useOdometerTurn): K's turn instead. The triangle gives K's heading at
// t_b, the t_e triangle its heading at t_e; the difference must be what K's odometer
// turned, within kTurnTolerance; then the candidate nearest K's t_e place.
// The witnesses are tried farthest travelled first, the proposed method's choice of C.
#include <mrloc/omnivision/TriangleSearch.h>

#include <string>
#include <vector>

namespace mrloc::omnivision {

/** rad: K's turn from the triangles against its odometer's. Wheel odometry over the short
 *  [t_b, t_e] errs well under a degree; the triangles' headings err by the bearing noise
 *  times the lever (tenths of a degree at 0.05 deg). */
constexpr double kTurnTolerance = 3 * M_PI / 180;

struct RestartSearch {
    /** At t_b: the labels of the triangle's six images and that triangle (the other
     *  robots unresolved: they are not searched). */
    Identification before;
    int witness = -1;           ///< K; -1: no witness formed a triangle (see `unconfirmed`)
    std::string unconfirmed;    ///< with witness -1: why, in one line
    size_t witnessesTried = 0;  ///< eq. (11): witnesses searched before one had a triangle
    size_t triples = 0;         ///< eq. (12): image triples examined, over those witnesses
    size_t triangles = 0;       ///< triples of the witness taken that summed to 180 degrees
};

/** The localized search at t_b. `travelled[r]` and `turned[r]` are robot r's odometer
 *  distance (m) and heading change (rad) over [t_b, t_e]; witnesses that did not move are
 *  skipped (eq. (8) needs l_C > 0). `turned` is read only with `useOdometerTurn` (beyond the
 *  paper). When no moving witness of t_e forms a (confirmed) triangle with A and B at t_b,
 *  the result has witness -1, the work done and the reason (the caller then searches t_b in
 *  full). Throws mrloc::Error if A and B do not see each other at t_e, or if the views
 *  exceed the work bound. */
RestartSearch localizedRestartSearch(const Snapshot& before, const Snapshot& after,
                                     const Identification& idAfter, int a, int b,
                                     const std::vector<double>& travelled,
                                     const std::vector<double>& turned, const SearchOptions& o,
                                     bool useOdometerTurn);

}  // namespace mrloc::omnivision
