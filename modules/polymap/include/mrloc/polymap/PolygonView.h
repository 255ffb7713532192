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
};

void renderPolygonView(const PolygonViewContent& content, const std::string& pngPath,
                       unsigned width = 1200, unsigned height = 600);

}  // namespace mrloc::polymap
