#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/report/TopView.h>
#include <mrpt/core/format.h>
#include <mrpt/opengl/CBox.h>
#include <mrpt/opengl/CDisk.h>
#include <mrpt/opengl/CFBORender.h>
#include <mrpt/opengl/CGridPlaneXY.h>
#include <mrpt/opengl/CSetOfLines.h>

#include <algorithm>
#include <cmath>

namespace mrloc::report {

using namespace mrpt::opengl;

namespace {
/** A marker seen from above. A disk, not a CSphere: CSphere's constructor, inline in MRPT's
 *  header, touches its virtual base at an address misaligned for the base's 32-byte alignment
 *  (undefined behaviour, fatal under UBSan; doc/hardening.md). */
CDisk::Ptr disk(float radius) { return CDisk::Create(radius, 0.0f); }
}  // namespace

namespace {

CSetOfLines::Ptr pathLines(const common::Trajectory& traj, mrpt::img::TColor color, float z) {
    auto lines = CSetOfLines::Create();
    lines->setLineWidth(4.0f);
    lines->setColor_u8(color);
    for (size_t i = 1; i < traj.size(); ++i) {
        const auto& a = traj[i - 1].pose;
        const auto& b = traj[i].pose;
        lines->appendLine(a.x(), a.y(), z, b.x(), b.y(), z);
    }
    return lines;
}

/** A scale bar (a round length near a fifth of the width) bottom left, on a white box so
 *  that it stays readable over the drawing. */
void drawScale(mrpt::img::CImage& img, double metresPerPixel) {
    const int W = int(img.getWidth()), H = int(img.getHeight());
    img.selectTextFont("9x15");
    const double target = 0.2 * W * metresPerPixel;
    double bar = std::pow(10.0, std::floor(std::log10(target)));
    for (double f : {5.0, 2.0})
        if (bar * f <= target) {
            bar *= f;
            break;
        }
    const int px = int(std::lround(bar / metresPerPixel));
    const mrpt::img::TColor black(0, 0, 0), white(255, 255, 255);
    img.filledRectangle(8, H - 46, 24 + px, H - 8, white);
    img.line(16, H - 16, 16 + px, H - 16, black, 3);
    img.line(16, H - 22, 16, H - 10, black, 2);
    img.line(16 + px, H - 22, 16 + px, H - 10, black, 2);
    img.textOut(16, H - 40, mrpt::format("%g m", bar), black);
}

constexpr int kLegendRow = 18;

/** The width of the legend's panel: its longest entry. */
int legendWidth(const Legend& legend) {
    if (legend.empty()) return 0;
    size_t longest = 0;
    for (const auto& [name, c] : legend) longest = std::max(longest, name.size());
    return 48 + 9 * int(longest);
}

/** The legend in the panel right of the drawing (x0 onwards): it can hide no data. */
void drawLegend(mrpt::img::CImage& img, int x0, const Legend& legend) {
    if (legend.empty()) return;
    img.selectTextFont("9x15");
    const mrpt::img::TColor black(0, 0, 0);
    int y = 14;
    for (const auto& [name, colour] : legend) {
        img.filledRectangle(x0 + 8, y + 4, x0 + 28, y + 10, colour);
        img.textOut(x0 + 34, y, name, black);
        y += kLegendRow;
    }
}

/** True if every pose lies within 2 cm of the first: a robot that does not move. */
bool standsStill(const common::Trajectory& t) {
    return std::all_of(t.begin(), t.end(), [&](const common::StampedPose& p) {
        return std::hypot(p.pose.x() - t.front().pose.x(), p.pose.y() - t.front().pose.y()) < 0.02;
    });
}

struct Extent {
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    void add(double x, double y) {
        x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
    }
};

}  // namespace

mrpt::img::TColor robotColour(size_t i) {
    // gnuplot's default line colours, so that a robot has one colour in every picture.
    static const mrpt::img::TColor palette[] = {{148, 0, 211}, {0, 158, 115},  {86, 180, 233},
                                                {230, 159, 0}, {240, 228, 66}, {0, 114, 178},
                                                {229, 30, 16}, {0, 0, 0}};
    return palette[i % (sizeof palette / sizeof palette[0])];
}

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
    for (const auto& [robot, t] : c.odometry)  // drawn whole, however far it drifts
        for (const auto& p : t) ext.add(p.pose.x(), p.pose.y());
    for (const auto& b : c.landmarks) ext.add(b.x, b.y);
    if (ext.x0 > ext.x1) throw Error("top view: nothing to draw");

    const double grid = std::max(
        0.5,
        std::pow(10.0, std::floor(std::log10(std::max(ext.x1 - ext.x0, ext.y1 - ext.y0)))) / 2);
    auto gridPlane = CGridPlaneXY::Create(
        std::floor(ext.x0 / grid) * grid, std::ceil(ext.x1 / grid) * grid,
        std::floor(ext.y0 / grid) * grid, std::ceil(ext.y1 / grid) * grid, 0.005, grid);
    gridPlane->setColor_u8(200, 200, 200);
    scene.insert(gridPlane);
    Legend legend;
    std::vector<WorldLabel> labels;
    // Landmarks (beacons on the ceiling, say) drawn at floor level so paths stay visible,
    // each with its name beside it as the tables give it.
    const mrpt::img::TColor landmarkColour{30, 90, 220};
    for (size_t k = 0; k < c.landmarks.size(); ++k) {
        const auto& b = c.landmarks[k];
        auto s = disk(0.06f);
        s->setLocation(b.x, b.y, 0.05);
        s->setColor_u8(landmarkColour);
        scene.insert(s);
        if (k < c.landmarkLabels.size()) labels.push_back({b.x, b.y, c.landmarkLabels[k]});
    }
    if (!c.landmarks.empty()) legend.emplace_back(c.landmarksName, landmarkColour);
    // One style for one kind of thing in a picture: paths as lines, unless every robot
    // stands still (test points), when all are markers.
    bool allStill = true;
    for (const auto& [robot, est] : c.estimates) {
        const auto gt = c.groundTruth.find(robot);
        allStill =
            allStill && (gt != c.groundTruth.end() ? standsStill(gt->second) : standsStill(est));
    }
    const auto marker = [&](const mrpt::poses::CPose3D& p, float radius, float z,
                            mrpt::img::TColor col) {
        auto s = disk(radius);
        s->setLocation(p.x(), p.y(), z);
        s->setColor_u8(col);
        scene.insert(s);
    };
    // Each robot its colour: the truth pale, odometry alone dark, the estimates full.
    const mrpt::img::TColor black(0, 0, 0);
    bool anyStart = false;
    size_t i = 0;
    for (const auto& [robot, est] : c.estimates) {
        const auto colour = robotColour(i++);
        const mrpt::img::TColor pale(uint8_t((colour.R + 2 * 255) / 3),
                                     uint8_t((colour.G + 2 * 255) / 3),
                                     uint8_t((colour.B + 2 * 255) / 3));
        const mrpt::img::TColor dark(uint8_t(colour.R / 2), uint8_t(colour.G / 2),
                                     uint8_t(colour.B / 2));
        const auto gt = c.groundTruth.find(robot);
        if (gt != c.groundTruth.end() && !gt->second.empty()) {
            if (allStill)
                marker(gt->second.front().pose, 0.05f, 0.02f, pale);
            else
                scene.insert(pathLines(gt->second, pale, 0.02f));
            legend.emplace_back(robot + " truth", pale);
        }
        if (const auto odo = c.odometry.find(robot);
            !allStill && odo != c.odometry.end() && odo->second.size() > 1) {
            auto lines = pathLines(odo->second, dark, 0.025f);
            lines->setLineWidth(2.0f);
            scene.insert(lines);
            legend.emplace_back(robot + " odometry alone", dark);
        }
        if (allStill || est.size() == 1)
            for (const auto& e : est) marker(e.pose, 0.02f, 0.04f, colour);
        else
            scene.insert(pathLines(est, colour, 0.03f));
        legend.emplace_back(robot + " estimate", colour);
        // the start: where the truth begins, else the estimates
        if (!allStill) {
            const auto& from = gt != c.groundTruth.end() && !gt->second.empty() ? gt->second : est;
            if (!from.empty()) {
                auto ring = CDisk::Create(0.09f, 0.06f);
                ring->setLocation(from.front().pose.x(), from.front().pose.y(), 0.06);
                ring->setColor_u8(black);
                scene.insert(ring);
                anyStart = true;
            }
        }
    }
    if (anyStart) legend.emplace_back("start (ring)", black);
    if (c.world && !c.world->obstacles.empty())
        legend.emplace_back("obstacles", mrpt::img::TColor(90, 90, 90));
    saveTopDown(scene, ext.x0, ext.y0, ext.x1, ext.y1, pngPath, width, height, legend, labels);
}

void saveTopDown(mrpt::opengl::COpenGLScene& scene, double x0, double y0, double x1, double y1,
                 const std::string& pngPath, unsigned width, unsigned height, const Legend& legend,
                 const std::vector<WorldLabel>& labels) {
    CFBORender render(width, height);
    auto& cam = render.getCamera(scene);
    cam.setOrthogonal(true);
    cam.setElevationDegrees(90);
    cam.setAzimuthDegrees(-90);
    const double cx = (x0 + x1) / 2, cy = (y0 + y1) / 2;
    cam.setPointingAt(cx, cy, 0);
    // CFBORender's orthographic view is zoomDistance/2 high (measured); fit with a margin.
    const double aspect = double(width) / double(height);
    // a margin of 6 % and at least 0.15 m on each side: markers at the extent stay whole
    const double extent = std::max(y1 - y0, (x1 - x0) / aspect);
    const double zoom = 2.2 * (1.12 * extent + 0.3);
    cam.setZoomDistance(float(zoom));
    mrpt::img::CImage drawing;
    render.render_RGB(scene, drawing);
    const double metresPerPixel = 0.5 * zoom / double(height);
    drawScale(drawing, metresPerPixel);
    drawing.selectTextFont("10x20");
    for (const auto& l : labels) {
        // x to the right and y up from the centre of the picture, as the camera looks down;
        // the name centred above its place, on white, kept inside the picture
        const int w = 10 * int(l.text.size()) + 6, h = 22;
        const int px =
            std::clamp(int(std::lround(width / 2.0 + (l.x - cx) / metresPerPixel)) - w / 2, 0,
                       std::max(0, int(width) - w));
        const int py =
            std::clamp(int(std::lround(height / 2.0 - (l.y - cy) / metresPerPixel)) - 22 - h, 0,
                       std::max(0, int(height) - h));
        drawing.filledRectangle(px, py, px + w, py + h, mrpt::img::TColor(255, 255, 255));
        drawing.rectangle(px, py, px + w, py + h, mrpt::img::TColor(20, 20, 20));
        drawing.textOut(px + 3, py + 1, l.text, mrpt::img::TColor(20, 20, 20));
    }
    const int panel = legendWidth(legend);
    const int rowsHeight = 28 + kLegendRow * int(legend.size());
    mrpt::img::CImage img(int(width) + panel, std::max(int(height), rowsHeight), mrpt::img::CH_RGB);
    img.filledRectangle(0, 0, int(img.getWidth()) - 1, int(img.getHeight()) - 1,
                        mrpt::img::TColor(255, 255, 255));
    img.drawImage(0, 0, drawing);
    drawLegend(img, int(width), legend);
    common::PendingFile out(pngPath, ".tmp.png");  // CImage picks the format by extension
    if (!img.saveToFile(out.tempPath())) throw Error("cannot write " + pngPath);
    out.commit();
}

}  // namespace mrloc::report
