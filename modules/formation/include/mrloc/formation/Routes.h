#pragma once
// The two routes of seed 003's simulations, rebuilt from the text (its figures give no
// coordinates; doc/formation.md): one with many turns (fig. 12) and a patrol loop (fig. 13).
// Both start beside the four robots' first triangle, facing east.
#include <mrpt/math/TPoint2D.h>

#include <string>
#include <vector>

namespace mrloc::formation {

/** "many_turns" (seed 003 fig. 12: six turns, 113 m) or "patrol" (fig. 13: a 28.5 m x
 *  19.35 m loop back to the start, 96 m). Throws mrloc::Error naming the valid ones. */
std::vector<mrpt::math::TPoint2D> route(const std::string& name);

}  // namespace mrloc::formation
