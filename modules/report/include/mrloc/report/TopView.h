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
    std::string landmarksName = "landmarks";  ///< their legend entry
    common::Trajectories groundTruth, estimates;
};

/** One colour per robot, in the order robots are listed (the error plots use the same). */
mrpt::img::TColor robotColour(size_t index);

/** Renders to a PNG (written to a temporary name, then renamed). */
void renderTopView(const TopViewContent& content, const std::string& pngPath, unsigned width = 900,
                   unsigned height = 900);

using Legend = std::vector<std::pair<std::string, mrpt::img::TColor>>;

/** Renders a scene seen from above, fitted to [x0, x1] x [y0, y1], off screen to a PNG
 *  (temporary name, then rename), with the legend and a scale bar in metres. Shared by
 *  every top-down picture. */
void saveTopDown(mrpt::opengl::COpenGLScene& scene, double x0, double y0, double x1, double y1,
                 const std::string& pngPath, unsigned width, unsigned height, const Legend& legend);

}  // namespace mrloc::report
