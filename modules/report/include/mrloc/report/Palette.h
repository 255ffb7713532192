#pragma once
// One colour-blind-safe palette for every picture mrloc draws: Okabe and Ito's eight colours
// ("Color Universal Design", 2008), which readers with any of the common colour-vision
// deficiencies tell apart. The top views (OpenGL) take the colours from here, and every gnuplot
// script is given them as variables (pal_blue, pal_vermillion, ...), so no picture spells a
// colour of its own.
#include <mrpt/img/TColor.h>

#include <cstddef>
#include <string>

namespace mrloc::report::palette {

inline constexpr mrpt::img::TColor kBlack{0, 0, 0};
inline constexpr mrpt::img::TColor kOrange{230, 159, 0};
inline constexpr mrpt::img::TColor kSkyBlue{86, 180, 233};
inline constexpr mrpt::img::TColor kGreen{0, 158, 115};  ///< Okabe and Ito's "bluish green"
inline constexpr mrpt::img::TColor kYellow{240, 228, 66};
inline constexpr mrpt::img::TColor kBlue{0, 114, 178};
inline constexpr mrpt::img::TColor kVermillion{213, 94, 0};
inline constexpr mrpt::img::TColor kPurple{204, 121, 167};  ///< "reddish purple"
/** Things that are not data: walls, a map's outline, what a truth is drawn against. */
inline constexpr mrpt::img::TColor kGrey{110, 110, 110};
inline constexpr mrpt::img::TColor kLightGrey{200, 200, 200};

/** The i-th series' colour (a robot, a curve), the same in every picture: blue, vermillion,
 *  green, purple, orange, sky blue, black, then again (yellow, weak on white, is left out). */
mrpt::img::TColor series(size_t i);

/** "#rrggbb". */
std::string hex(mrpt::img::TColor c);

/** The palette as gnuplot variables (pal_black, pal_orange, pal_sky, pal_green, pal_yellow,
 *  pal_blue, pal_vermillion, pal_purple, pal_grey, pal_lightgrey) and gnuplot's line types 1-7
 *  set to the series' colours (`lc 2` is series(1) in every plot), one per line. */
std::string gnuplotDefinitions();

/** A colour scale for a value (an error) that is ordered and reads in grey too: viridis
 *  (perceptually uniform, colour-blind safe), as a gnuplot `set palette defined` line. */
std::string gnuplotValueScale();

}  // namespace mrloc::report::palette
