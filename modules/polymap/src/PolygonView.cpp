#include <mrloc/common/Error.h>
#include <mrloc/polymap/PolygonView.h>
#include <mrloc/report/TopView.h>
#include <mrpt/opengl/CDisk.h>
#include <mrpt/opengl/CSetOfLines.h>

#include <algorithm>

namespace mrloc::polymap {

using namespace mrpt::opengl;
using common::TPoint2D;

namespace {

CSetOfLines::Ptr outline(const std::vector<TPoint2D>& v, const TPoint2D& at,
                         mrpt::img::TColor color, float width, float z) {
    auto lines = CSetOfLines::Create();
    lines->setLineWidth(width);
    lines->setColor_u8(color);
    for (size_t i = 0; i < v.size(); ++i) {
        const TPoint2D a = v[i] + at, b = v[(i + 1) % v.size()] + at;
        lines->appendLine(a.x, a.y, z, b.x, b.y, z);
    }
    return lines;
}

CDisk::Ptr marker(const TPoint2D& p, double radius, mrpt::img::TColor color, float z) {
    auto d = CDisk::Create(float(radius), 0);
    d->setLocation(p.x, p.y, z);
    d->setColor_u8(color);
    return d;
}

}  // namespace

void renderPolygonView(const PolygonViewContent& c, const std::string& pngPath, unsigned width,
                       unsigned height) {
    if (!c.map) throw Error("polygon view: no map to draw");
    const auto& P = *c.map;
    COpenGLScene scene;
    scene.getViewport()->setCustomBackgroundColor({1, 1, 1});
    const double size = std::max(P.max().x - P.min().x, P.max().y - P.min().y);
    const double dot = std::max(0.004 * size, 0.05);
    // Orange: V placed at each hypothesis; green: at the true start; red: hypotheses.
    for (const auto& h : c.hypotheses) scene.insert(outline(c.sensed, h, {240, 140, 20}, 2, 0.01f));
    if (c.truth && !c.sensed.empty())
        scene.insert(outline(c.sensed, *c.truth, {20, 150, 50}, 3, 0.02f));
    scene.insert(outline(P.vertices(), {0, 0}, {30, 30, 30}, 2, 0.03f));
    for (const auto& h : c.hypotheses) scene.insert(marker(h, 1.6 * dot, {220, 40, 30}, 0.04f));
    if (c.truth) scene.insert(marker(*c.truth, dot, {20, 150, 50}, 0.05f));
    const double m = 0.02 * size;
    report::Legend legend = {{"map P", {30, 30, 30}}, {"V at each hypothesis", {240, 140, 20}}};
    if (c.truth) legend.push_back({"V at the true start", {20, 150, 50}});
    legend.push_back({"hypotheses", {220, 40, 30}});
    report::saveTopDown(scene, P.min().x - m, P.min().y - m, P.max().x + m, P.max().y + m, pngPath,
                        width, height, legend);
}

}  // namespace mrloc::polymap
