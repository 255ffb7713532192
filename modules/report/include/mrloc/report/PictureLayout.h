#pragma once
// Where a picture put its parts, kept in the PNG itself (a tEXt chunk, "mrloc layout"), so
// that a test or a reader can check a picture's layout from the boxes its renderer used
// (gnuplot's plot area, the top view's drawing and legend panel) rather than from pixels.
#include <optional>
#include <string>
#include <vector>

namespace mrloc::report {

/** A box in pixels, x to the right and y down from the picture's top left corner. */
struct PixelBox {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    int width() const { return x1 - x0; }
    int height() const { return y1 - y0; }
    bool overlaps(const PixelBox& o) const {
        return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1;
    }
    bool inside(const PixelBox& o) const {
        return x0 >= o.x0 && y0 >= o.y0 && x1 <= o.x1 && y1 <= o.y1;
    }
};

struct PictureLayout {
    int width = 0, height = 0;  ///< the whole picture
    PixelBox data;  ///< where the data are drawn (gnuplot's plot area, a top view's map)
    /** Panels of the same size side by side or stacked (gnuplot's multiplot): `data` is the
     *  last one's. */
    int panels = 1;
    /** Where the legend is, when the renderer knows its box (the top views' panel). */
    std::optional<PixelBox> legend;
    /** gnuplot's key: "outside" (beside, above or below the plot area, which gnuplot shrinks
     *  to make room), "inside" (over the data) or "none". */
    std::string key = "none";
    std::vector<PixelBox> labels;  ///< names written over the data (a beacon's number)
    /** The data box's share drawn on (not background), when the renderer measured it. */
    std::optional<double> inkShare;
};

/** Writes the layout into the PNG at `pngPath` (a tEXt chunk before IEND). */
void writeLayout(const std::string& pngPath, const PictureLayout& layout);

/** The layout a PNG of mrloc's carries; nullopt if it has none. */
std::optional<PictureLayout> readLayout(const std::string& pngPath);

/** The key placement a gnuplot script body leaves: its last `set key` / `unset key`
 *  ("outside", "inside" or "none"), the script's preamble putting it outside. */
std::string gnuplotKeyPlacement(const std::string& body);

}  // namespace mrloc::report
