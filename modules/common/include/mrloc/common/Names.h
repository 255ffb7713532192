#pragma once
// Names that come from files (an INI's robots and scenario name, a rawlog's sensor labels)
// end up in file names, gnuplot scripts and HTML. They are checked where they enter, with
// one grammar for all of mrloc.
#include <optional>
#include <string>
#include <vector>

namespace mrloc::common {

/** At most this many bytes in a robot's or a scenario's name, and 4 times this in a label. */
inline constexpr size_t kMaxNameLength = 64;

/** A robot's name: 1 to 64 of A-Z a-z 0-9 _ -, not starting with '-'. */
bool isRobotName(const std::string& name);
/** Throws mrloc::Error "<where>: robot name '<name>' ..." unless isRobotName(name). */
void checkRobotName(const std::string& name, const std::string& where);
/** A scenario's name (the run folder's and the rawlog's file name): as a robot's, and '.'
 *  too, but not first (neither ".." nor a hidden file). */
void checkName(const std::string& name, const std::string& where);

/** A sensor label split where mrloc splits it: at the first dot, "<robot>.<sensor>"
 *  ("r1.lidar.r2" is robot r1's sensor "lidar.r2"); a label without a dot (rawlogs recorded by
 *  other MRPT tools) is the sensor of robot "robot". */
struct SensorLabel {
    std::string robot, sensor;
};
SensorLabel parseSensorLabel(const std::string& label);
/** Throws mrloc::Error naming `where` when a label cannot be taken in: a control character
 *  or over 256 bytes, or a robot part (before the first dot) that is not a robot name. */
void checkSensorLabel(const std::string& label, const std::string& where);

/** `s` with every byte outside printable ASCII written as \xNN, quotes kept: for messages. */
std::string printable(const std::string& s);

/** Edit distance (insertions, deletions, substitutions, adjacent swaps), case-insensitive. */
size_t editDistance(const std::string& a, const std::string& b);
/** The candidate `word` looks like a misspelling of: within one edit (two for candidates of
 *  6 letters or more), any case; the closest if several. "did you mean" messages. */
std::optional<std::string> nearMiss(const std::string& word,
                                    const std::vector<std::string>& candidates);

}  // namespace mrloc::common
