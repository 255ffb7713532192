#pragma once
// Top view of a run rendered off screen with mrpt::opengl::CFBORender (EGL, no display).
#include <mrloc/common/BeaconMap.h>
#include <mrloc/common/Trajectory.h>
#include <mrloc/sim/World.h>
#include <mrpt/opengl/COpenGLScene.h>

#include <map>
#include <optional>
#include <string>

namespace mrloc::report {

struct TopViewContent {
    std::optional<sim::WorldOptions> world;
    common::BeaconMap beacons;
    std::map<std::string, common::Trajectory> groundTruth, estimates;  ///< per robot
};

/** Renders to a PNG (written to a temporary name, then renamed). */
void renderTopView(const TopViewContent& content, const std::string& pngPath, unsigned width = 900,
                   unsigned height = 900);

/** Renders a scene seen from above, fitted to [x0, x1] x [y0, y1], off screen to a PNG
 *  (temporary name, then rename). Shared by every top-down picture. */
void saveTopDown(mrpt::opengl::COpenGLScene& scene, double x0, double y0, double x1, double y1,
                 const std::string& pngPath, unsigned width, unsigned height);

}  // namespace mrloc::report
