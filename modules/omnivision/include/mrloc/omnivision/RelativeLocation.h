#pragma once
// From identified triangles to distances and a layout (seed 000 sections 2 and 3).
//  - Conventional method (Kato-Ishiguro-Barth, section 2): one measured distance |AB|.
//  - Proposed method (section 3): A and B stop during [t_b, t_e], a third robot C seen by
//    both at both instants moves l_C; eq. (8) gives L = |AB|.
// Either way every other distance follows from the sine rule over the triangles, and the
// layout puts A at the origin and B on the x axis (each robot placed by eq. (3) on a
// triangle with two robots already placed).
#include <mrloc/omnivision/Geometry.h>
#include <mrloc/omnivision/TriangleSearch.h>

#include <map>
#include <optional>
#include <vector>

namespace mrloc::omnivision {

struct Solution {
    int a = -1, b = -1;
    double baseline = 0;                             ///< |AB| (m)
    std::vector<std::optional<Vec2>> position;       ///< per robot; A = (0,0), B = (L,0)
    std::vector<std::optional<double>> heading;      ///< per robot (rad): headingsFromLayout
    std::map<std::pair<int, int>, double> distance;  ///< sine rule, key (i, j) with i < j
};

/** Each placed robot's heading in the layout's frame (beyond the paper, which leaves it
 *  out): the circular mean, over its labelled images of placed robots, of the direction to
 *  that robot less the image's bearing. None for a robot with no such image. */
std::vector<std::optional<double>> headingsFromLayout(
    const Snapshot& s, const Labels& labels, const std::vector<std::optional<Vec2>>& position);

/** Distances by the sine rule and the layout, from |AB| = baseline. Throws mrloc::Error if
 *  A and B are in no common triangle. */
Solution solveFromBaseline(const Snapshot& s, const Identification& id, int a, int b,
                           double baseline);

/** The conventional method: |AB| measured (by a LiDAR, say). */
inline Solution conventionalMethod(const Snapshot& s, const Identification& id, int a, int b,
                                   double measuredAB) {
    return solveFromBaseline(s, id, a, b, measuredAB);
}

struct ProposedSolution {
    Solution before, after;  ///< at t_b and t_e
    int moving = -1;         ///< C
    double travelled = 0;    ///< l_C
};

/** Robots in a triangle with A and B at both instants: the candidates for C. */
std::vector<int> commonWitnesses(const Identification& before, const Identification& after, int a,
                                 int b);

/** The proposed method. `travelled[r]` is robot r's odometer distance over [t_b, t_e]; C is
 *  the witness that travelled farthest (its angles change most). Throws mrloc::Error if A
 *  and B share no witness at both instants (the paper restarts with another pair), and,
 *  through eq. (8), if C did not move. */
ProposedSolution proposedMethod(const Snapshot& before, const Identification& idBefore,
                                const Snapshot& after, const Identification& idAfter, int a, int b,
                                const std::vector<double>& travelled);

/** The triangle of robots {i, j, k} in an identification, if found. */
const Triangle* findTriangle(const Identification& id, int i, int j, int k);
/** Interior angle of a triangle at robot r, and the side of the line r->toward the third
 *  robot is on, seen from r (+1: counter-clockwise). */
double angleAt(const Triangle& t, int r);
int sideAt(const Snapshot& s, const Triangle& t, int r, int toward);

}  // namespace mrloc::omnivision
