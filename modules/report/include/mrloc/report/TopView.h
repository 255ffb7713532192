#pragma once
// Top view of a run rendered off screen with mrpt::opengl::CFBORender (EGL, no display),
// with axes in metres and a legend panel drawn into the picture so that it reads on its own.
#include <mrloc/common/Localizer.h>
#include <mrloc/sim/World.h>
#include <mrpt/img/CImage.h>
#include <mrpt/img/TColor.h>
#include <mrpt/math/TPoint2D.h>
#include <mrpt/math/TPoint3D.h>
#include <mrpt/opengl/COpenGLScene.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace mrloc::report {

struct TopViewContent {
    std::optional<sim::WorldOptions> world;
    /** Static points a method adds (beacons, say), drawn as markers at floor level. */
    std::vector<mrpt::math::TPoint3D> landmarks;
    /** Each landmark's name written beside it ("2" for beacon 2, as the tables name it);
     *  empty, or one per landmark. */
    std::vector<std::string> landmarkLabels;
    std::string landmarksName = "landmarks";  ///< their legend entry
    common::Trajectories groundTruth, estimates;
    /** Odometry alone per robot, in the estimates' frame (the baseline's path). */
    common::Trajectories odometry;
};

/** One colour per robot, in the order robots are listed (the error plots use the same):
 *  palette::series. */
mrpt::img::TColor robotColour(size_t index);

/** Renders to a PNG (written to a temporary name, then renamed). Each robot has its colour;
 *  its truth is a wide pale band, its estimate a thin line over it and odometry alone a
 *  dashed line, so that they differ by more than their shade. */
void renderTopView(const TopViewContent& content, const std::string& pngPath, unsigned width = 900,
                   unsigned height = 900);

/** How a legend entry's sample is drawn: as the thing it names is drawn. */
enum class Swatch { Patch, Band, Line, Dashed, Dot, Ring, Arrow };

struct LegendEntry {
    std::string name;
    mrpt::img::TColor colour;
    Swatch swatch = Swatch::Patch;
};
using Legend = std::vector<LegendEntry>;

/** A name written at a place of the world (a beacon's number beside it). */
struct WorldLabel {
    double x = 0, y = 0;
    std::string text;
};

/** A path drawn over a top view's rendered drawing, in world coordinates (metres). */
struct PicturePath {
    std::vector<mrpt::math::TPoint2D> points;
    mrpt::img::TColor colour;
    int width = 2;  ///< pixels
    bool dashed = false;
};

/** Renders a scene seen from above, fitted to [x0, x1] x [y0, y1] at one scale for both
 *  axes, off screen to a PNG (temporary name, then rename). The drawing is at most width x
 *  height pixels and takes the extent's shape (a long corridor gives a wide, low picture, not
 *  one half empty); `paths` are drawn over it in their order; axes in metres frame it, labels sit
 * above their places (those whose place lies outside the extent are left out), and the legend is a
 * panel to the right, where it hides nothing. The layout goes into the PNG (PictureLayout.h).
 * Shared by every top-down picture. */
void saveTopDown(mrpt::opengl::COpenGLScene& scene, double x0, double y0, double x1, double y1,
                 const std::string& pngPath, unsigned width, unsigned height, const Legend& legend,
                 const std::vector<WorldLabel>& labels = {},
                 const std::vector<PicturePath>& paths = {});

/** Frames a drawing already made (a map seen from above, `metresPerPixel`, its centre at
 *  (cx, cy)) as saveTopDown does: the paths over it, axes in metres, the labels, a title above
 *  when given, the legend panel beside it; writes the PNG with its layout. */
void framePicture(mrpt::img::CImage drawing, double cx, double cy, double metresPerPixel,
                  const std::string& pngPath, const Legend& legend,
                  const std::vector<WorldLabel>& labels = {},
                  const std::vector<PicturePath>& paths = {}, const std::string& title = "");

}  // namespace mrloc::report
