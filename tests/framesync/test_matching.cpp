// Matching and redefinition (seed 004 secs. 4.3-4.5): each threshold, the redefinition's
// geometry, the priority of reference, aging and frame versions in the database, the bus,
// and no reference loop among three robots.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/framesync/FrameManager.h>
#include <mrloc/framesync/Matching.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/math/wrap2pi.h>

#include <cmath>

using namespace mrloc;
using namespace mrloc::framesync;
using mrpt::DEG2RAD;
using mrpt::poses::CPose2D;

namespace {

/** The wall y = 2 from x0 to x1, seen from below (normal +y). */
Wall northWall(double x0, double x1, double y = 2) {
    Wall w;
    w.a = {x0, y}, w.b = {x1, y};
    w.normal = M_PI / 2;
    return w;
}

}  // namespace

TEST(Matching, TheRedefinitionPutsTheOwnWallOnTheReference) {
    // The robot at (3, 1) believes the wall is 0.2 m nearer and turned by 8 deg: its frame
    // is the true one turned by 8 deg about it and moved 0.2 m along +y.
    const TPoint2D robot(3, 1);
    const Wall reference = northWall(2, 4);
    const CPose2D error =
        redefinitionTransform(robot, DEG2RAD(8.0), {0, 1}, 0) + CPose2D(0, -0.2, 0);
    const Wall own = reference.transformed(error);
    const auto r = matchWalls(own, reference, robot, {});
    ASSERT_TRUE(r.has_value());
    EXPECT_NEAR(r->rotation, DEG2RAD(-8.0), 1e-12);
    EXPECT_NEAR(r->shift, 0.2, 1e-12);
    // sec. 4.4: the own wall then lies on the reference's line with its bearing
    const Wall moved = own.transformed(r->correction);
    EXPECT_NEAR(mrpt::math::wrapToPi(moved.normal - reference.normal), 0, 1e-12);
    EXPECT_NEAR(moved.a.y, 2, 1e-12);
    EXPECT_NEAR(moved.b.y, 2, 1e-12);
    // the rotation is about the robot: its position does not move but along the normal
    const TPoint2D after = composePoint(r->correction, robot);
    EXPECT_NEAR(after.x, 3, 1e-12);
    EXPECT_NEAR(after.y, 1.2, 1e-12);
    EXPECT_NEAR(r->correction.phi(), DEG2RAD(-8.0), 1e-12);
    // one wall fixes two degrees of freedom: sliding along the wall is not seen
    EXPECT_NEAR(r->overlap, 2.0 * std::cos(DEG2RAD(8.0)) - 0, 0.3);
}

TEST(Matching, EachThresholdDecides) {
    const TPoint2D robot(3, 1);
    const Wall reference = northWall(2, 4);
    MatchOptions o;  // 20 deg, 0.5 m, 0.3 m of overlap
    auto turned = [&](double deg) {
        return reference.transformed(redefinitionTransform(robot, DEG2RAD(deg), {0, 1}, 0));
    };
    EXPECT_TRUE(matchWalls(turned(19.9), reference, robot, o).has_value());
    EXPECT_FALSE(matchWalls(turned(20.1), reference, robot, o).has_value());
    EXPECT_TRUE(matchWalls(turned(-19.9), reference, robot, o).has_value());
    // the distances from the robot: 1 m against 1.49 and 1.51 m
    EXPECT_TRUE(matchWalls(northWall(2, 4, 2.49), reference, robot, o).has_value());
    EXPECT_FALSE(matchWalls(northWall(2, 4, 2.51), reference, robot, o).has_value());
    EXPECT_FALSE(matchWalls(northWall(2, 4, 1.49), reference, robot, o).has_value());
    // the two segments must share 0.3 m once redefined: [3.75, 5] shares 0.25 m of [2, 4]
    EXPECT_FALSE(matchWalls(northWall(3.75, 5), reference, robot, o).has_value());
    EXPECT_TRUE(matchWalls(northWall(3.65, 5), reference, robot, o).has_value());
    o.minOverlap = 0;  // the paper's "intersected": any overlap
    EXPECT_TRUE(matchWalls(northWall(3.75, 5), reference, robot, o).has_value());
    EXPECT_FALSE(matchWalls(northWall(4.1, 5), reference, robot, o).has_value());
    // a wall seen from the other side (opposite normal) is another wall
    Wall back = reference;
    back.normal = -M_PI / 2;
    EXPECT_FALSE(matchWalls(back, reference, robot, o).has_value());
    // the thresholds come from the options: 10 deg turns the 15-degree pair down
    o.maxBearing = DEG2RAD(10.0);
    EXPECT_FALSE(matchWalls(turned(15), reference, robot, o).has_value());
}

TEST(Priority, TheLowerPriorityRobotRedefinesAndTheHighestNever) {
    const PriorityOrder order({"a", "b"});
    EXPECT_TRUE(order.higher("a", "b"));
    EXPECT_FALSE(order.higher("b", "a"));
    EXPECT_TRUE(order.higher("b", "z"));  // listed before unlisted
    EXPECT_TRUE(order.higher("x", "z"));  // unlisted: by name
    EXPECT_THROW(PriorityOrder({"a", "b", "a"}), Error);

    InProcessBus bus;
    FrameManager a("a", order, {}, bus), b("b", order, {}, bus);
    a.setPose(10, CPose2D(3, 1, 0));
    b.setPose(10, CPose2D(3, 1.1, 0.02));  // b's frame: 0.1 m off and turned
    a.announce(northWall(2, 4));
    b.announce(northWall(2, 4, 2.1).transformed(CPose2D(0, 0, 0)));
    EXPECT_EQ(a.version(), 0u);  // the highest priority never moves
    EXPECT_EQ(b.version(), 1u);
    EXPECT_NEAR(b.correction().y(), -0.1, 1e-12);
    // a's wall reached b first: b searched its own walls when its own arrived, and found it
    EXPECT_EQ(b.database().walls().size(), 2u);
    // an own wall redefines the frame once: a's next wall finds no unused wall of b's
    a.announce(northWall(2, 4));
    EXPECT_EQ(b.version(), 1u);
    // b's next wall (in its new frame, 0.02 m off now) does
    b.announce(northWall(2, 4, 2.02));
    EXPECT_EQ(b.version(), 2u);
    EXPECT_NEAR(b.correction().y(), -0.12, 1e-9);
}

TEST(WallDatabase, OldWallsArePurgedAndOlderFramesDropped) {
    WallDatabase db(30);
    WallMessage m;
    m.sender = "a";
    m.time = 100;
    m.wall = northWall(0, 1);
    EXPECT_TRUE(db.add(m));
    m.time = 125;
    EXPECT_TRUE(db.add(m));
    EXPECT_EQ(db.purge(129), 0u);
    EXPECT_EQ(db.purge(131), 1u);  // 31 s old
    EXPECT_EQ(db.walls().size(), 1u);
    // a newer frame of a: its walls of the older frame go
    m.frameVersion = 2;
    m.time = 130;
    EXPECT_TRUE(db.add(m));
    ASSERT_EQ(db.walls().size(), 1u);
    EXPECT_EQ(db.walls()[0].frameVersion, 2u);
    // a late message from a's older frame is refused
    m.frameVersion = 1;
    EXPECT_FALSE(db.add(m));
    // the owner's own walls move with its frame
    WallMessage own = m;
    own.sender = "b";
    own.frameVersion = 0;
    EXPECT_TRUE(db.add(own));
    db.reframe("b", CPose2D(0, 0.5, 0), 1);
    EXPECT_NEAR(db.walls().back().wall.a.y, 2.5, 1e-12);
    EXPECT_EQ(db.walls().back().frameVersion, 1u);
}

TEST(FrameManager, AnAgedReferenceWallIsNotMatched) {
    const PriorityOrder order({"a", "b"});
    InProcessBus bus;
    ManagerOptions o;
    o.maxAge = 30;
    FrameManager a("a", order, o, bus), b("b", order, o, bus);
    a.setPose(0, CPose2D(3, 1, 0));
    b.setPose(0, CPose2D(3, 1, 0));
    a.announce(northWall(2, 4));
    b.setPose(31, CPose2D(3, 1, 0));  // 31 s later b sees the same wall 0.1 m off
    b.announce(northWall(2, 4, 2.1));
    EXPECT_EQ(b.version(), 0u);
    b.setPose(20, CPose2D(3, 1, 0));  // (a log may run back only in a test)
    a.setPose(20, CPose2D(3, 1, 0));
    a.announce(northWall(2, 4));
    EXPECT_EQ(b.version(), 1u);  // a fresh reference wall matches
}

TEST(FrameManager, ThreeRobotsFormNoReferenceLoop) {
    // Every robot's wall matches every other's (each sees the wall at its own offset): a
    // naive "match and move" would chase in a loop. With priorities a > b > c, a never
    // moves, b moves only on a's walls, c on a's or b's.
    const PriorityOrder order({"a", "b", "c"});
    InProcessBus bus;
    std::vector<RedefinitionEvent> events;
    struct Log : FrameListener {
        std::vector<RedefinitionEvent>& e;
        explicit Log(std::vector<RedefinitionEvent>& e) : e(e) {}
        void onRedefinition(const RedefinitionEvent& ev) override { e.push_back(ev); }
    } log(events);
    FrameManager a("a", order, {}, bus), b("b", order, {}, bus), c("c", order, {}, bus);
    for (auto* m : {&a, &b, &c}) m->addListener(&log);
    const std::map<std::string, double> offset{{"a", 0.0}, {"b", 0.2}, {"c", -0.15}};
    for (int round = 0; round < 5; ++round)
        for (auto* m : {&c, &b, &a}) {  // the lowest announces first
            m->setPose(round, CPose2D(3, 1, 0));
            // the robot's wall in its current frame: the truth offset by its frame's error
            const double y = 2 + offset.at(m->robot()) + m->correction().y();
            m->announce(northWall(2, 4, y));
        }
    EXPECT_EQ(a.version(), 0u);
    ASSERT_FALSE(events.empty());
    for (const auto& e : events) {
        EXPECT_TRUE(order.higher(e.reference, e.robot)) << e.robot << " on " << e.reference;
        EXPECT_NE(e.robot, "a");
    }
    // all three end in a's frame: each sees the wall where a does
    EXPECT_NEAR(2 + offset.at("b") + b.correction().y(), 2, 1e-9);
    EXPECT_NEAR(2 + offset.at("c") + c.correction().y(), 2, 1e-9);
}

TEST(InProcessBus, DeliversInOrderToEverySubscriberWithoutReentry) {
    InProcessBus bus;
    std::vector<std::string> seen;
    int depth = 0, maxDepth = 0;
    bus.subscribe("x", [&](const WallMessage& m) {
        maxDepth = std::max(maxDepth, ++depth);
        seen.push_back("x:" + m.sender);
        if (m.sender == "first") {
            WallMessage reply;
            reply.sender = "reply";
            bus.publish(reply);  // waits until "first" reached everybody
        }
        --depth;
    });
    bus.subscribe("y", [&](const WallMessage& m) { seen.push_back("y:" + m.sender); });
    WallMessage m;
    m.sender = "first";
    bus.publish(m);
    EXPECT_EQ(seen, (std::vector<std::string>{"x:first", "y:first", "x:reply", "y:reply"}));
    EXPECT_EQ(maxDepth, 1);
    EXPECT_EQ(bus.delivered(), 2u);
}

TEST(FrameManager, ASecondWallOfAnotherDirectionFixesTheThirdDegreeOfFreedom) {
    // b's frame is off by (0.2, 0.1) from a's. A wall facing +y fixes y only; a wall facing
    // +x then fixes x: b ends in a's frame.
    const PriorityOrder order({"a", "b"});
    InProcessBus bus;
    FrameManager a("a", order, {}, bus), b("b", order, {}, bus);
    const CPose2D offset(0.2, 0.1, 0);  // b's frame = offset (+) a's
    a.setPose(1, CPose2D(3, 1, 0));
    b.setPose(1, offset + CPose2D(3, 1, 0));
    a.announce(northWall(2, 4));
    b.announce(northWall(2, 4).transformed(offset));
    EXPECT_NEAR(b.correction().y(), -0.1, 1e-12);
    EXPECT_NEAR(b.correction().x(), 0, 1e-12);  // along the wall: not seen
    // the east wall x = 5 from y = 0 to 2, seen from the west (normal +x)
    Wall east;
    east.a = {5, 0}, east.b = {5, 2};
    east.normal = 0;
    a.setPose(2, CPose2D(4, 1, 0));
    b.setPose(2, b.correction() + offset + CPose2D(4, 1, 0));
    a.announce(east);
    b.announce(east.transformed(b.correction() + offset));
    EXPECT_NEAR(b.correction().x(), -0.2, 1e-12);
    EXPECT_NEAR(b.correction().y(), -0.1, 1e-12);
    EXPECT_NEAR((b.correction() + offset).norm(), 0, 1e-12);  // b's frame is a's
}
