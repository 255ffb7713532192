#pragma once
// The polygon-map picture (seed 002 fig. 1): the map P, the sensed visibility polygon V
// placed at every hypothesis, the hypotheses and the true start. Off screen, PNG.
#include <mrloc/common/Polygon.h>

#include <optional>
#include <string>
#include <vector>

namespace mrloc::polymap {

struct PolygonViewContent {
    std::optional<common::Polygon> map;
    std::vector<common::TPoint2D> sensed;      ///< V in the robot frame
    std::vector<common::TPoint2D> hypotheses;  ///< where V fits the map
    std::optional<common::TPoint2D> truth;
    /** Elimination routes from the true start (map frame), each with its probes. */
    struct Route {
        std::string label;
        std::vector<common::TPoint2D> path, probes;
    };
    std::vector<Route> routes;
    std::vector<common::TPoint2D> overlay;  ///< OI at the true start (map frame), if drawn
    /** Candidate probes (map frame) and whose they are. */
    std::pair<std::string, std::vector<common::TPoint2D>> candidates;
    /** Draw only this box (min, max corners; map frame): a close-up. Default: all of P. */
    std::optional<std::pair<common::TPoint2D, common::TPoint2D>> box;
};

void renderPolygonView(const PolygonViewContent& content, const std::string& pngPath,
                       unsigned width = 1200, unsigned height = 600);

}  // namespace mrloc::polymap
