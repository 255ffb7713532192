#pragma once
// Seed 001's figures (Shin, Choi & Park's active ultrasonic beacons), in one place: the
// headline, the study and the report set the runs beside these.
namespace mrloc::beacons::paper {

/** Section 5.3 (active beacons, Table 4's points, Fig. 11): "the average error over 30 mm,
 *  the maximal over 60 mm", measured in a 4000 x 5700 mm room, 10 trials per point. */
constexpr double kActiveMeanErrorM = 0.030, kActiveMaxErrorM = 0.060;
constexpr double kActiveRoomX = 4.0, kActiveRoomY = 5.7;
/** Section 5.2 (fixed angles, Table 3, Fig. 10): a 3000 x 3000 mm room; the errors are a
 *  chart whose values the text does not give, only that active beacons halve them. */
constexpr double kFixedRoomX = 3.0, kFixedRoomY = 3.0;

/** Section 6, the next goals: a maximal error under 50 mm, one set of beacons covering over
 *  6 m x 6 m. */
constexpr double kGoalMaxErrorM = 0.050, kGoalCoverageSide = 6.0;
/** Tables 3/4: the successful receiving rate the paper reports as good (90 % and above). */
constexpr double kGoodReception = 0.9;
/** Section 1: a section is 3 beacons. */
constexpr int kSectionBeacons = 3;
/** Abstract: active beacons need "about the half" of a fixed system's beacons. */
constexpr double kActiveBeaconShare = 0.5;

}  // namespace mrloc::beacons::paper
