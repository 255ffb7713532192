#pragma once
// Plots drawn by gnuplot (pngcairo): the error per robot of a method with one estimate each
// (EvaluationPlots.h draws the truth timeline's), and the runner every method's plots use.
#include <mrloc/common/Metrics.h>

#include <map>
#include <string>
#include <vector>

namespace mrloc::report {

using RobotErrors = std::map<std::string, std::vector<common::TimedError>>;

/** True when no robot has more than one error: a line over time would be empty. */
bool oneErrorPerRobot(const RobotErrors& errors);
/** One marker per estimate, robots along the x axis (a method with one estimate each). */
void plotErrorPerRobot(const RobotErrors& errors, const std::string& pngPath);

/** Runs a gnuplot script (pngcairo, grid, key outside right, the palette's colours as
 *  variables and line types: Palette.h) whose data blocks are inline; writes pngPath
 *  atomically, with the plot area gnuplot chose and the key's placement in the PNG
 *  (PictureLayout.h). Every plot of mrloc, the methods' included, goes through it. */
void runGnuplot(const std::string& body, const std::string& pngPath,
                const std::string& size = "900,500");
/** `text` as a gnuplot single-quoted string, quotes included: every user string (a robot's
 *  name, a label) reaches a script only through this. A quote is doubled, control characters
 *  (a newline would end the command) become '?'; inside single quotes gnuplot expands
 *  neither backticks, macros (@) nor variables. */
std::string gnuplotString(const std::string& text);
/** `text` as one word of an inline data block: blanks, quotes, '#', '\\', '$' and '`' -> '_'. */
std::string gnuplotDataWord(const std::string& text);
/** A PNG whose signature and final IEND chunk are there (not cut short by a full disk). */
bool isCompletePng(const std::string& path);
/** An inline gnuplot data block `$name` of x y rows. */
std::string dataBlock(const std::string& name, const std::vector<std::pair<double, double>>& xy);

}  // namespace mrloc::report
