// The team's on-board logic (Team): it plans only once every robot has scanned, accepts an
// arrival only from the moving robot, places a scan where its robot believes it stands (the
// mover: at its target), and shares one obstacle per cell.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/formation/Team.h>
#include <mrpt/obs/CObservationComment.h>

using namespace mrloc;
using formation::TPoint2D;

namespace {

formation::TeamOptions fourRobots() {
    formation::TeamOptions o;
    o.names = {"f1", "f2", "f3", "f4"};
    o.start = formation::initialStrip(4, 1.5);
    o.route = {{1.5, 0.65}, {9, 0.65}};
    return o;
}

/** A scan of 4 beams (east, north, west, south in the robot frame); range 0: no return. */
mrpt::obs::CObservation2DRangeScan::Ptr scan(const std::string& robot, std::array<float, 4> r) {
    auto s = mrpt::obs::CObservation2DRangeScan::Create();
    s->sensorLabel = robot + ".obstacles";
    s->aperture = float(2 * M_PI * 3 / 4);  // beams 90 degrees apart, the first at -135
    s->rightToLeft = true;
    s->resizeScan(4);
    for (size_t i = 0; i < 4; ++i) {
        s->setScanRange(i, r[i]);
        s->setScanRangeValidity(i, r[i] > 0);
    }
    return s;
}

mrpt::obs::CObservation::Ptr arrival(const std::string& robot) {
    auto c = mrpt::obs::CObservationComment::Create();
    c->text = formation::arrivalText(robot);
    return c;
}

}  // namespace

TEST(FormationTeam, PlansAfterEveryRobotScannedAndAcceptsOnlyTheMoversArrival) {
    formation::Team team(fourRobots());
    for (const char* r : {"f1", "f2", "f3"}) EXPECT_FALSE(team.observe(scan(r, {0, 0, 0, 0})));
    EXPECT_EQ(team.state(), formation::Team::State::Waiting);
    EXPECT_THROW(team.observe(arrival("f1")), Error);  // nobody moves yet
    EXPECT_TRUE(team.observe(scan("f4", {0, 0, 0, 0})));
    ASSERT_EQ(team.state(), formation::Team::State::Moving);
    // the farthest from (9, 0.65): f2 at (0, 1.30), to (3, 1.30) (as test_formation's first move)
    EXPECT_EQ(team.current()->robot, 1u);
    EXPECT_NEAR(team.current()->target.x, 3.0, 1e-12);
    try {
        team.observe(arrival("f3"));
        FAIL() << "an arrival from a robot that does not move";
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(),
                     "formation: f3.arrived reports an arrival, but the moving robot is f2; was "
                     "the rawlog recorded with another [formation] section?");
    }
    EXPECT_TRUE(team.observe(arrival("f2")));
    ASSERT_EQ(team.moves().size(), 1u);
    EXPECT_NEAR(team.believed()[1].x, 3.0, 1e-12);
    // facing away from the anchor, f1 at (0.75, 0): atan2(1.30, 2.25) = 30 degrees
    EXPECT_NEAR(team.believedHeading(1), M_PI / 6, 1e-9);
    EXPECT_FALSE(team.observe(arrival("someone else")));  // not a team member: ignored
}

TEST(FormationTeam, ScansArePlacedWhereTheirRobotBelievesItStandsOnePerCell) {
    formation::Team team(fourRobots());
    // f1 at (0.75, 0) facing east: its beam at -135 degrees returns at 1 m
    team.observe(scan("f1", {1, 0, 0, 0}));
    ASSERT_EQ(team.obstacles().size(), 1u);
    EXPECT_NEAR(team.obstacles()[0].centre.x, 0.75 - std::sqrt(0.5), 1e-6);
    EXPECT_NEAR(team.obstacles()[0].centre.y, -std::sqrt(0.5), 1e-6);
    // a beam stands for half the 90-degree gap to its neighbours: r sin 45
    EXPECT_NEAR(team.obstacles()[0].radius, std::sqrt(0.5), 1e-6);
    team.observe(scan("f1", {1.01f, 0, 0, 0}));  // the same 0.1 m cell: shared once
    EXPECT_EQ(team.obstacles().size(), 1u);
    for (const char* r : {"f2", "f3", "f4"}) team.observe(scan(r, {0, 0, 0, 0}));
    ASSERT_EQ(team.state(), formation::Team::State::Moving);
    // The mover scans on arrival, from its target (3, 1.30) at 30 degrees: the beam at
    // -135 + 30 = -105 degrees, 2 m out.
    team.observe(scan("f2", {2, 0, 0, 0}));
    ASSERT_EQ(team.obstacles().size(), 2u);
    const double a = (-105.0) * M_PI / 180;
    EXPECT_NEAR(team.obstacles()[1].centre.x, 3 + 2 * std::cos(a), 1e-6);
    EXPECT_NEAR(team.obstacles()[1].centre.y, 1.5 * std::sqrt(3.0) / 2 + 2 * std::sin(a), 1e-6);
}

TEST(FormationTeam, ReachesTheDestinationAndRefusesBadTeams) {
    formation::Team team(fourRobots());
    for (const char* r : {"f1", "f2", "f3", "f4"}) team.observe(scan(r, {0, 0, 0, 0}));
    int moves = 0;
    while (team.state() == formation::Team::State::Moving && moves < 100) {
        team.observe(arrival(team.options().names[team.current()->robot]));
        ++moves;
    }
    EXPECT_EQ(team.state(), formation::Team::State::Arrived);
    EXPECT_EQ(moves, 9);  // 7.5 m at 0.75 m per move, the strip's 4 robots leapfrogging
    auto three = fourRobots();
    three.names.pop_back(), three.start.pop_back();
    EXPECT_THROW(formation::Team{three}, Error);
}
