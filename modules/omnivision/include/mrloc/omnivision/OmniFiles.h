#pragma once
// The files the omnivision method writes into the run directory for its report section,
// each defined once, write and read side by side:
//   layout.txt     the layout in the paper's frame: paper, refined (+ covariance), truth
//   accuracy.txt   the Monte Carlo accuracy sweep (an experiment step, Accuracy.h)
#include <mrloc/omnivision/Accuracy.h>

#include <optional>
#include <string>
#include <vector>

namespace mrloc::omnivision {

/** One robot of a relative layout (seed 000): the paper's position, the refined one with
 *  its covariance, and the truth, all in the layout's frame. NaN where unknown. */
struct LayoutPoint {
    std::string robot;
    double paperX, paperY, refinedX, refinedY, cxx, cxy, cyy, trueX, trueY;
    /** Headings (rad) in the layout's frame: the paper layout's (headingsFromLayout), the
     *  refined one with its variance (rad^2), the truth's. */
    double paperPhi = NAN, refinedPhi = NAN, cphiphi = NAN, truePhi = NAN;
};

/** The refined position's error weighed by its covariance, per coordinate the gauge leaves
 *  free (B's y is fixed by the frame): e' P^-1 e / dof; nothing for A or without truth. */
std::optional<double> normalisedSquaredError(const LayoutPoint& p);

struct LayoutFile {
    double time = 0;   ///< of the layout (s)
    std::string a, b;  ///< the frame: a at the origin, b on the x axis
    std::vector<LayoutPoint> points;

    static std::string path(const std::string& dir) { return dir + "/layout.txt"; }
    void write(const std::string& dir) const;
    /** Throws mrloc::Error naming the file and line on a malformed line. */
    static LayoutFile read(const std::string& dir);
};

struct AccuracyFile {
    std::string distanceName;  ///< what the distance noise is on: "odometer" or "LiDAR"
    std::vector<AccuracyPoint> points;

    static std::string path(const std::string& dir) { return dir + "/accuracy.txt"; }
    void write(const std::string& dir) const;
    static AccuracyFile read(const std::string& dir);
};

/** True and recovered layouts, with 3-sigma ellipses of the refined positions. */
void plotLayout(const LayoutFile& layout, const std::string& pngPath);
/** Two panels: the error against the angle noise and against the distance noise. */
void plotAccuracy(const AccuracyFile& sweep, const std::string& pngPath);

}  // namespace mrloc::omnivision
