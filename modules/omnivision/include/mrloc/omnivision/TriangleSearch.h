#pragma once
// Triangle search and image identification (seed 000 section 2, Fig. 4-6).
//
// Three angles measured by three different robots that sum to 180 degrees are the interior
// angles of the triangle those robots form; two such triangles sharing two robots identify
// the image both angles use at each of them (Fig. 6: at A, the image in both 72.3 and 45.7
// degrees is B). Two searches give the same answer:
//  - identifyBruteForce(): the paper's search over every triple of angles (eq. (9)), then
//    the identification by votes of triangle pairs. O(N^9) for N mutually visible robots;
//    kept as the test oracle.
//  - identify(): seed and grow. One triangle whose identities are fixed places three
//    robots (up to scale) and their headings; every further robot must then appear where
//    the rays of placed robots meet, and see them at the bearings that point predicts.
//    Each acceptance is checked against every placed robot, so chance sums near 180
//    degrees do not survive. Seeds come first from robots on the swarm's hull (their
//    images span less than 180 degrees; the extreme images are hull neighbours).
// Both report labels (which robot each image is), the triangles consistent with them
// (every triple of mutually identified robots whose angles sum to 180 within tolerance)
// and the robots left unresolved.
#include <mrloc/omnivision/Snapshot.h>

#include <array>
#include <vector>

namespace mrloc::omnivision {

/** Three robots and, at each, the two images forming its interior angle. */
struct Triangle {
    std::array<int, 3> robot{};
    std::array<std::array<int, 2>, 3> images{};  ///< at robot[v]: images of the other two
    std::array<double, 3> angle{};               ///< interior angles (rad)
    double sum() const { return angle[0] + angle[1] + angle[2]; }
};

/** labels[r][image] = the robot that image of robot r's camera shows, or -1. */
using Labels = std::vector<std::vector<int>>;

struct SearchOptions {
    double sumTolerance = 0.5 * M_PI / 180;      ///< |sum - 180 deg| accepted (rad)
    double bearingTolerance = 0.3 * M_PI / 180;  ///< a predicted bearing matches (rad)
    size_t maxSeeds = 200;  ///< seed triangles identify() grows before it gives up
    /** Angle pairs, image lookups and the images they look at that identify() may examine
     *  while growing its seeds, in all, per N^3 robots: tolerances too loose for the noise
     *  make every pair a candidate, and the search then ran for hours (doc/errors.md,
     *  "Work"). Beyond it identify() throws mrloc::Error naming the keys. 15000 N^3 is
     *  4.05e8 for 30 robots, which need 0.03 to 0.08 million at 0.02 deg (all in sight);
     *  75 robots at 0.05 deg need 7 to 204 million of 6.3e9 (measured December 2026). */
    double maxPairVisitsPerRobotCubed = 15000;
    size_t maxPairVisits(size_t robots) const {
        const double n = double(robots);
        return size_t(maxPairVisitsPerRobotCubed * n * n * n);
    }
};

struct Identification {
    Labels labels;
    std::vector<Triangle> triangles;  ///< consistent with labels, sorted by robots
    std::vector<int> unresolved;      ///< robots in no consistent triangle
    size_t candidates = 0;            ///< angle triples (brute force) or seeds (fast) tried
    size_t pairVisits = 0;            ///< angle pairs examined while growing (fast)
};

/** Every triple of angles from three different robots summing to 180 degrees within
 *  tolerance (seed 000 eq. (9)): the paper's search, chance sums included. */
std::vector<Triangle> bruteForceTriangles(const Snapshot& s, double sumTolerance);

/** Fig. 4-6: each pair of candidate triangles sharing two robots votes, at each shared
 *  robot, for the image both angles use (and the other two images); each camera's images
 *  take the labels with most votes, one image per robot. */
Labels labelsByVotes(const Snapshot& s, const std::vector<Triangle>& candidates);

/** The triangles of mutually identified robots whose angles sum to 180 within tolerance. */
Identification consistentTriangles(const Snapshot& s, Labels labels, double sumTolerance);

/** Why a robot is in no consistent triangle (Identification::unresolved). */
enum class UnresolvedReason {
    SeesTooFew,  ///< its camera shows fewer than 2 robots
    NotPlaced,   ///< fewer than 2 robots identified both ways with it (the search left it)
    NoTriangle,  ///< identified with 2 or more, but no two of them form a triangle with
                 ///< it: they do not identify each other, or the angles miss 180 degrees
};
UnresolvedReason whyUnresolved(const Snapshot& s, const Identification& id, int robot);
/** Each reason's name in metrics.json (snapshots.<t>.unresolved_why) and its words, as a
 *  headline says them after a count of robots. */
struct UnresolvedReasonText {
    UnresolvedReason reason;
    const char* key;
    const char* words;
};
constexpr UnresolvedReasonText kUnresolvedReasons[] = {
    {UnresolvedReason::SeesTooFew, "camera_shows_fewer_than_2",
     "whose camera shows fewer than 2 robots"},
    {UnresolvedReason::NotPlaced, "not_placed",
     "not placed: identified both ways with fewer than 2 robots"},
    {UnresolvedReason::NoTriangle, "in_no_triangle",
     "identified, but in no triangle summing to 180 degrees within the tolerance"}};
const UnresolvedReasonText& textOf(UnresolvedReason reason);

/** The paper's search and identification: the test oracle. */
Identification identifyBruteForce(const Snapshot& s, const SearchOptions& o);

/** Seed and grow (see above): the same answer, far faster. Uses the sign of the bearings
 *  (all cameras share one handedness), which the paper's unsigned angles do not. */
Identification identify(const Snapshot& s, const SearchOptions& o);

}  // namespace mrloc::omnivision
