#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/report/TopView.h>
#include <mrpt/opengl/CBox.h>
#include <mrpt/opengl/CFBORender.h>
#include <mrpt/opengl/CGridPlaneXY.h>
#include <mrpt/opengl/CSetOfLines.h>
#include <mrpt/opengl/CSphere.h>

#include <algorithm>
#include <cmath>

namespace mrloc::report {

using namespace mrpt::opengl;

namespace {

CSetOfLines::Ptr pathLines(const common::Trajectory& traj, mrpt::img::TColor color, float z) {
    auto lines = CSetOfLines::Create();
    lines->setLineWidth(2.5f);
    lines->setColor_u8(color);
    for (size_t i = 1; i < traj.size(); ++i) {
        const auto& a = traj[i - 1].pose;
        const auto& b = traj[i].pose;
        lines->appendLine(a.x(), a.y(), z, b.x(), b.y(), z);
    }
    return lines;
}

struct Extent {
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    void add(double x, double y) {
        x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
    }
};

}  // namespace

void renderTopView(const TopViewContent& c, const std::string& pngPath, unsigned width,
                   unsigned height) {
    COpenGLScene scene;
    scene.getViewport()->setCustomBackgroundColor({0.97f, 0.97f, 0.97f});
    Extent ext;
    if (c.world) {
        const auto& w = *c.world;
        ext.add(0, 0);
        ext.add(w.sizeX, w.sizeY);
        // Outlines only: in CFBORender's orthographic top view a filled box hides every line
        // drawn with it, whatever the lines' height.
        auto border = CSetOfLines::Create();
        border->setColor_u8(40, 40, 40);
        const double X = w.sizeX, Y = w.sizeY;
        border->appendLine(0, 0, 0, X, 0, 0);
        border->appendLine(X, 0, 0, X, Y, 0);
        border->appendLine(X, Y, 0, 0, Y, 0);
        border->appendLine(0, Y, 0, 0, 0, 0);
        scene.insert(border);
        for (const auto& b : w.obstacles) {
            auto box = CBox::Create(b.min, b.max, /*wireframe=*/true);
            box->setColor_u8(90, 90, 90);
            scene.insert(box);
        }
    }
    for (const auto& [robot, t] : c.groundTruth)
        for (const auto& p : t) ext.add(p.pose.x(), p.pose.y());
    for (const auto& [robot, t] : c.estimates)
        for (const auto& p : t) ext.add(p.pose.x(), p.pose.y());
    for (const auto& [id, b] : c.beacons) ext.add(b.x, b.y);
    if (ext.x0 > ext.x1) throw Error("top view: nothing to draw");

    const double grid = std::max(
        0.5,
        std::pow(10.0, std::floor(std::log10(std::max(ext.x1 - ext.x0, ext.y1 - ext.y0)))) / 2);
    auto gridPlane = CGridPlaneXY::Create(
        std::floor(ext.x0 / grid) * grid, std::ceil(ext.x1 / grid) * grid,
        std::floor(ext.y0 / grid) * grid, std::ceil(ext.y1 / grid) * grid, 0.005, grid);
    gridPlane->setColor_u8(200, 200, 200);
    scene.insert(gridPlane);
    // Beacons sit on the ceiling; drawn at floor level as discs so paths stay visible.
    for (const auto& [id, b] : c.beacons) {
        auto s = CSphere::Create(0.06f);
        s->setLocation(b.x, b.y, 0.05);
        s->setColor_u8(30, 90, 220);
        scene.insert(s);
    }
    for (const auto& [robot, t] : c.groundTruth) scene.insert(pathLines(t, {20, 150, 50}, 0.02f));
    for (const auto& [robot, t] : c.estimates) scene.insert(pathLines(t, {220, 40, 30}, 0.03f));

    saveTopDown(scene, ext.x0, ext.y0, ext.x1, ext.y1, pngPath, width, height);
}

void saveTopDown(mrpt::opengl::COpenGLScene& scene, double x0, double y0, double x1, double y1,
                 const std::string& pngPath, unsigned width, unsigned height) {
    CFBORender render(width, height);
    auto& cam = render.getCamera(scene);
    cam.setOrthogonal(true);
    cam.setElevationDegrees(90);
    cam.setAzimuthDegrees(-90);
    cam.setPointingAt((x0 + x1) / 2, (y0 + y1) / 2, 0);
    // CFBORender's orthographic view is zoomDistance/2 high (measured); fit with a margin.
    const double aspect = double(width) / double(height);
    cam.setZoomDistance(float(2.2 * std::max(y1 - y0, (x1 - x0) / aspect) + 0.2));
    mrpt::img::CImage img;
    render.render_RGB(scene, img);
    common::PendingFile out(pngPath, ".tmp.png");  // CImage picks the format by extension
    if (!img.saveToFile(out.tempPath())) throw Error("cannot write " + pngPath);
    out.commit();
}

}  // namespace mrloc::report
