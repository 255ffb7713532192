#pragma once
// The files the polygon-map localizer writes into the run directory for its report
// section, each defined once, write and read side by side:
//   map.poly                  the map P (common::Polygon's own format)
//   hypotheses.<robot>.txt    the sensed V (robot frame) and the hypotheses H
#include <mrloc/polymap/Hypotheses.h>

#include <string>
#include <vector>

namespace mrloc::polymap {

inline std::string mapFilePath(const std::string& dir) { return dir + "/map.poly"; }

/** One robot's result: V as sensed (robot frame) and H. */
struct HypothesesFile {
    double time = 0;               ///< of the scan (s)
    std::vector<TPoint2D> sensed;  ///< V's vertices, robot frame
    std::vector<Hypothesis> hypotheses;

    static std::string path(const std::string& dir, const std::string& robot);
    void write(const std::string& dir, const std::string& robot) const;
    /** Throws mrloc::Error naming the file and line on a malformed line. */
    static HypothesesFile read(const std::string& dir, const std::string& robot);
};

}  // namespace mrloc::polymap
