#pragma once
// Top view of a run rendered off screen with mrpt::opengl::CFBORender (EGL, no display),
// with a legend and a scale bar drawn into the picture so that it reads on its own.
#include <mrloc/common/Localizer.h>
#include <mrloc/sim/World.h>
#include <mrpt/img/TColor.h>
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

/** One colour per robot, in the order robots are listed (the error plots use the same). */
mrpt::img::TColor robotColour(size_t index);

/** Renders to a PNG (written to a temporary name, then renamed). */
void renderTopView(const TopViewContent& content, const std::string& pngPath, unsigned width = 900,
                   unsigned height = 900);

using Legend = std::vector<std::pair<std::string, mrpt::img::TColor>>;

/** A name written at a place of the world (a beacon's number beside it). */
struct WorldLabel {
    double x = 0, y = 0;
    std::string text;
};

/** Renders a scene seen from above, fitted to [x0, x1] x [y0, y1], off screen to a PNG
 *  (temporary name, then rename), with a scale bar in metres in the picture, the labels
 *  beside their places, and the legend in a panel to the right of the drawing, where it
 *  hides nothing. Shared by every top-down picture. */
void saveTopDown(mrpt::opengl::COpenGLScene& scene, double x0, double y0, double x1, double y1,
                 const std::string& pngPath, unsigned width, unsigned height, const Legend& legend,
                 const std::vector<WorldLabel>& labels = {});

}  // namespace mrloc::report
