#pragma once
// Seed 003's published values (the formation paper: triangle formations seen through
// monocular cameras), in one place: the error model, the experiment's defaults and the report
// quote them from here. What the paper does not give (its wheel radius, its tables lost in
// extraction) is not here: doc/formation.md says what mrloc chose instead.
#include <cstddef>

namespace mrloc::formation::paper {

/** Fig. 11: the real robots' per-step errors at the vertex over 60 lab runs, mean absolute
 *  error and standard deviation (m), along the new triangle's base (lateral) and across it
 *  (longitudinal). */
constexpr double kLateralMean = 0.036, kLateralSd = 0.021;
constexpr double kLongitudinalMean = 0.013, kLongitudinalSd = 0.009;
constexpr size_t kFig11Runs = 60;

/** Sec. 5: the intended wheel speeds of Table 1 and fig. 14 (rad/s), the first the default. */
constexpr double kWheelSpeedFast = 5.8, kWheelSpeedSlow = 2.9;

}  // namespace mrloc::formation::paper
