#include <mrloc/common/Error.h>
#include <mrloc/polymap/PolygonView.h>
#include <mrloc/report/Palette.h>
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
    const TPoint2D lo = c.box ? c.box->first : P.min(), hi = c.box ? c.box->second : P.max();
    const double size = std::max(hi.x - lo.x, hi.y - lo.y);
    const double dot = std::max(0.004 * size, 0.05);
    // The map, V and the hypotheses in black and greys; V at the true start a yellow band
    // under the map; each route in a series colour of the palette (Palette.h), so the routes
    // are the only colours in the picture.
    using namespace report::palette;
    using report::Swatch;
    // Drawn in pixels over the rendering, in this order (OpenGL's lines are one pixel wide
    // off screen, and its triangles would hide them): V at the true start and OI as wide
    // bands, then the map's rings and the routes over them, so that no band hides a wall.
    std::vector<report::PicturePath> paths;
    const auto ring = [](const std::vector<TPoint2D>& v, const TPoint2D& at,
                         mrpt::img::TColor colour, int width) {
        report::PicturePath p{{}, colour, width, false};
        for (const auto& q : v) p.points.push_back(q + at);
        if (!v.empty()) p.points.push_back(v.front() + at);
        return p;
    };
    if (c.truth && !c.sensed.empty()) paths.push_back(ring(c.sensed, *c.truth, kYellow, 6));
    if (!c.overlay.empty()) paths.push_back(ring(c.overlay, {0, 0}, kLightGrey, 5));
    for (const auto& h : c.hypotheses) scene.insert(outline(c.sensed, h, kGrey, 1.5, 0.01f));
    for (size_t r = 0; r < P.ringCount(); ++r)  // the outer boundary and each hole
        paths.push_back(ring(P.ringVertices(r), {0, 0}, kBlack, 2));
    for (const auto& h : c.hypotheses) scene.insert(marker(h, 1.6 * dot, kBlack, 0.04f));
    if (c.truth) scene.insert(marker(*c.truth, dot, kYellow, 0.05f));
    for (const auto& p : c.candidates.second) scene.insert(marker(p, 0.35 * dot, kGrey, 0.055f));
    // Routes: one colour each, drawn a little apart so that shared legs stay visible.
    for (size_t k = 0; k < c.routes.size(); ++k) {
        const auto colour = series(k);
        const double shift = 0.6 * dot * (double(k) - 0.5 * double(c.routes.size() - 1));
        report::PicturePath route{{}, colour, 2, false};
        for (const auto& q : c.routes[k].path) route.points.push_back({q.x + shift, q.y + shift});
        paths.push_back(std::move(route));
        for (const auto& p : c.routes[k].probes)
            scene.insert(marker({p.x + shift, p.y + shift}, 0.9 * dot, colour, 0.07f));
    }
    const double m = 0.02 * size;
    report::Legend legend = {{"map P", kBlack, Swatch::Line}};
    if (!c.hypotheses.empty()) {
        legend.push_back({"hypotheses (#: the tables' numbers)", kBlack, Swatch::Dot});
        legend.push_back({"V placed at each hypothesis", kGrey, Swatch::Line});
    }
    if (c.truth) legend.push_back({"the true start and V there", kYellow, Swatch::Band});
    if (!c.overlay.empty()) legend.push_back({"OI at the true start", kLightGrey, Swatch::Band});
    if (!c.candidates.second.empty())
        legend.push_back({c.candidates.first + ": first candidates", kGrey, Swatch::Dot});
    for (size_t k = 0; k < c.routes.size(); ++k)
        legend.push_back({c.routes[k].label + ": route, probes as dots", series(k), Swatch::Line});
    // each hypothesis numbered as the report's tables number it (#1 first)
    std::vector<report::WorldLabel> labels;
    for (size_t k = 0; k < c.hypotheses.size() && c.hypotheses.size() <= 40; ++k)
        labels.push_back({c.hypotheses[k].x, c.hypotheses[k].y, "#" + std::to_string(k + 1)});
    report::saveTopDown(scene, lo.x - m, lo.y - m, hi.x + m, hi.y + m, pngPath, width, height,
                        legend, labels, paths);
}

}  // namespace mrloc::polymap
