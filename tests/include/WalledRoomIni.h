#pragma once
// The simulator tests' room: 4 x 4 m with a wall across it at x = 2, one robot r1 driving
// north along x = 0.5 at 0.5 m/s for 10 s. [robot.r1] comes last, so a test may append keys
// to it, then sections of its own (the beacon tests do).
namespace mrloc::testing_room {

inline const char* kWalledRoomIni = R"(
[scenario]
name = simtest
seed = 7
duration = 10
robots = r1
[world]
size = 4 4 2.5
obstacle_wall = 1.9 0 0 2.1 4 2.5
[robot.r1]
start = 0.5 0.5 90
waypoints = 0.5 3.5
loop = false
speed = 0.5
)";

}  // namespace mrloc::testing_room
