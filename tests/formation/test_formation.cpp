// The formation planner (seed 003 sec. 3): the starting strip, the moving robot and its target
// vertex, Algorithm 2's path, safety zones, and a formation that cannot move.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/formation/Formation.h>

#include <cmath>

using namespace mrloc;
using formation::TPoint2D;

namespace {

const double kH = 1.5 * std::sqrt(3.0) / 2;  // 1.299 m: the triangles' height

void expectPoint(const TPoint2D& got, const TPoint2D& want, const char* what) {
    EXPECT_NEAR(got.x, want.x, 1e-12) << what;
    EXPECT_NEAR(got.y, want.y, 1e-12) << what;
}

}  // namespace

TEST(Formation, InitialStripIsThePapersFourRobots) {
    // seed 003 sec. 5: (0.75, 0), (0, 1.30), (2.25, 0), (1.5, 1.30) m; fig. 7 for more.
    const auto p = formation::initialStrip(6, 1.5);
    ASSERT_EQ(p.size(), 6u);
    expectPoint(p[0], {0.75, 0}, "robot 0");
    expectPoint(p[1], {0, kH}, "robot 1");
    expectPoint(p[2], {2.25, 0}, "robot 2");
    expectPoint(p[3], {1.5, kH}, "robot 3");
    expectPoint(p[4], {3.75, 0}, "robot 4");
    expectPoint(p[5], {3, kH}, "robot 5");
}

TEST(Formation, FarthestRobotGoesToTheNearestVertexThroughTheMidpoints) {
    // Destination east: robot 1 at (0, 1.30) is farthest. Its beacons 0, 2, 3 form a
    // triangle whose reflections are (1.5, -1.30) (anchor 3), its own spot (anchor 2) and
    // (3, 1.30) (anchor 0), the nearest. Algorithm 2: the midpoint of beacons 3-0 (nearest
    // the robot), of 2-3 (nearest the target), the target.
    const auto p = formation::initialStrip(4, 1.5);
    const auto move = formation::nextMove(p, {10, 0.65}, {}, {});
    ASSERT_TRUE(move);
    EXPECT_EQ(move->robot, 1u);
    EXPECT_EQ(move->anchor, 0u);
    EXPECT_EQ(move->base, (std::array<size_t, 2>{2, 3}));
    expectPoint(move->target, {3, kH}, "target");
    ASSERT_EQ(move->path.size(), 3u);
    expectPoint(move->path[0], {1.125, kH / 2}, "midpoint 3-0");
    expectPoint(move->path[1], {1.875, kH / 2}, "midpoint 2-3");
    expectPoint(move->path[2], {3, kH}, "target");
}

TEST(Formation, AnObstacleOnThePathSendsTheRobotToTheNextVertex) {
    // seed 003 fig. 5-6: an obstacle 5 cm in radius at (2.5, 1.1) is 7.8 cm from the last leg
    // to (3, 1.30), inside its 0.3 m safety zone; the next nearest vertex, (1.5, -1.30), is
    // clear. Without the safety zone the leg clears the obstacle itself and is taken.
    const auto p = formation::initialStrip(4, 1.5);
    const std::vector<formation::Obstacle> obstacles{{{2.5, 1.1}, 0.05}};
    const auto move = formation::nextMove(p, {10, 0.65}, obstacles, {});
    ASSERT_TRUE(move);
    EXPECT_EQ(move->robot, 1u);
    expectPoint(move->target, {1.5, -kH}, "target");
    EXPECT_TRUE(formation::clearOf(p[1], move->path, obstacles, 0.3));
    formation::FormationOptions noZone;
    noZone.safetyMargin = 0;
    const auto again = formation::nextMove(p, {10, 0.65}, obstacles, noZone);
    ASSERT_TRUE(again);
    expectPoint(again->target, {3, kH}, "target without the zone");
}

TEST(Formation, WhenNoPathIsClearNoRobotMoves) {
    // An obstacle on the midpoint of beacons 3-0: every path of the robots that can move
    // (1, and 2 when 1 cannot) passes it; robots 0 and 3 have no triangle among the others.
    const auto p = formation::initialStrip(4, 1.5);
    EXPECT_FALSE(formation::nextMove(p, {10, 0.65}, {{{1.125, kH / 2}, 0.05}}, {}));
    EXPECT_THROW(formation::nextMove({p[0], p[1], p[2]}, {10, 0}, {}, {}), Error);
}

TEST(Formation, EveryMoveKeepsTheFormationOnePieceOfEquilateralTriangles) {
    // Marching a strip of 7 towards a far point and back: after every move the target was
    // free and the robots still stand on triangles of side 1.5 (within 1 %).
    auto p = formation::initialStrip(7, 1.5);
    for (const TPoint2D destination : {TPoint2D{30, 20}, TPoint2D{-10, -5}}) {
        const auto near = [&] {
            for (const auto& q : p)
                if ((q - destination).norm() <= 1.5 / std::sqrt(3.0) + 1e-9) return true;
            return false;
        };
        int moves = 0;
        for (; !near() && moves < 400; ++moves) {
            const auto move = formation::nextMove(p, destination, {}, {});
            ASSERT_TRUE(move) << "move " << moves;
            for (size_t i = 0; i < p.size(); ++i)
                if (i != move->robot) {
                    EXPECT_GT((p[i] - move->target).norm(), 0.75);
                }
            EXPECT_NEAR((p[move->base[0]] - move->target).norm(), 1.5, 1e-9);
            EXPECT_NEAR((p[move->base[1]] - move->target).norm(), 1.5, 1e-9);
            p[move->robot] = move->target;
        }
        EXPECT_TRUE(near()) << "after " << moves << " moves";
    }
}
