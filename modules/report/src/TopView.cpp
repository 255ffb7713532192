#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/report/Palette.h>
#include <mrloc/report/PictureLayout.h>
#include <mrloc/report/TopView.h>
#include <mrpt/core/format.h>
#include <mrpt/opengl/CBox.h>
#include <mrpt/opengl/CDisk.h>
#include <mrpt/opengl/CFBORender.h>
#include <mrpt/opengl/CGridPlaneXY.h>
#include <mrpt/opengl/CSetOfLines.h>

#include <algorithm>
#include <cmath>
#include <functional>

namespace mrloc::report {

using namespace mrpt::opengl;

namespace {
/** A marker seen from above. A disk, not a CSphere: CSphere's constructor, inline in MRPT's
 *  header, touches its virtual base at an address misaligned for the base's 32-byte alignment
 *  (undefined behaviour, fatal under UBSan; doc/hardening.md). */
CDisk::Ptr disk(float radius) { return CDisk::Create(radius, 0.0f); }
}  // namespace

namespace {

/** The paths drawn over the rendered drawing in pixels (OpenCV's lines have a width, which
 *  OpenGL's have not off screen, and triangles hide lines there whatever their height): each
 *  in its order, so a wide truth band lies under the thin estimate. */
void drawPaths(mrpt::img::CImage& drawing, const std::vector<PicturePath>& paths,
               const std::function<std::pair<double, double>(double, double)>& toPixel) {
    for (const auto& path : paths) {
        double along = 0;  // pixels from the path's start, for the dashes (7 drawn, 5 not)
        for (size_t i = 1; i < path.points.size(); ++i) {
            const auto [ax, ay] = toPixel(path.points[i - 1].x, path.points[i - 1].y);
            const auto [bx, by] = toPixel(path.points[i].x, path.points[i].y);
            const double length = std::hypot(bx - ax, by - ay);
            if (!path.dashed) {
                drawing.line(int(std::lround(ax)), int(std::lround(ay)), int(std::lround(bx)),
                             int(std::lround(by)), path.colour, path.width);
                continue;
            }
            for (double s = 0; s < length;) {
                const double phase = std::fmod(along + s, 12.0);
                const double to = std::min(length, s + (phase < 7 ? 7 - phase : 12 - phase));
                if (phase < 7 && length > 0) {
                    const double f0 = s / length, f1 = to / length;
                    drawing.line(int(std::lround(ax + f0 * (bx - ax))),
                                 int(std::lround(ay + f0 * (by - ay))),
                                 int(std::lround(ax + f1 * (bx - ax))),
                                 int(std::lround(ay + f1 * (by - ay))), path.colour, path.width);
                }
                s = to + 1e-9;
            }
            along += length;
        }
    }
}

constexpr int kLegendRow = 20;
constexpr int kCharWidth = 9;  // the 9x15 font's advance

/** The width of the legend's panel: its longest entry beside a 34-pixel sample. */
int legendWidth(const Legend& legend) {
    if (legend.empty()) return 0;
    size_t longest = 0;
    for (const auto& e : legend) longest = std::max(longest, e.name.size());
    return 60 + kCharWidth * int(longest);
}

/** The legend in the panel from x0 on: each sample drawn as its thing is drawn. */
void drawLegend(mrpt::img::CImage& img, int x0, int y0, const Legend& legend) {
    img.selectTextFont("9x15");
    const mrpt::img::TColor black(0, 0, 0);
    int y = y0;
    for (const auto& e : legend) {
        const int a = x0 + 10, b = x0 + 44, mid = y + 8;
        switch (e.swatch) {
            case Swatch::Patch:  // outlined: a white patch (free space) stays visible
                img.filledRectangle(a, mid - 5, b, mid + 5, e.colour);
                img.rectangle(a, mid - 5, b, mid + 5, mrpt::img::TColor(60, 60, 60));
                break;
            case Swatch::Arrow:
                img.line(a, mid, b, mid, e.colour, 2);
                img.line(b, mid, b - 7, mid - 5, e.colour, 2);
                img.line(b, mid, b - 7, mid + 5, e.colour, 2);
                break;
            case Swatch::Band:
                img.filledRectangle(a, mid - 5, b, mid + 5, e.colour);
                break;
            case Swatch::Line:
                img.line(a, mid, b, mid, e.colour, 2);
                break;
            case Swatch::Dashed:
                for (int u = a; u < b; u += 12)
                    img.line(u, mid, std::min(b, u + 7), mid, e.colour, 2);
                break;
            case Swatch::Dot:
                img.filledRectangle(a + 12, mid - 5, a + 22, mid + 5, e.colour);
                break;
            case Swatch::Ring:
                img.drawCircle(a + 17, mid, 6, e.colour, 2);
                break;
        }
        img.textOut(x0 + 52, y, e.name, black);
        y += kLegendRow;
    }
}

/** A round tick step (1, 2 or 5 x 10^k) for a drawing of `width` x `height` metres at
 *  `metresPerPixel`: about six ticks along the shorter side (so it has some), the same step on
 *  both axes (one grid), at least 60 pixels apart (so the labels never touch). */
double tickStep(double width, double height, double metresPerPixel) {
    const double rough = std::min(width, height) / 6;
    double decade = std::pow(10.0, std::floor(std::log10(rough)));
    int mantissa = 1;  // the step is mantissa x decade, mantissa 1, 2 or 5
    const auto grow = [&] {
        if (mantissa == 5)
            mantissa = 1, decade *= 10;
        else
            mantissa = mantissa == 1 ? 2 : 5;
    };
    while (mantissa * decade < rough) grow();
    while (mantissa * decade / metresPerPixel < 60) grow();
    return mantissa * decade;
}

std::string tickText(double v, double step) {
    const int decimals = std::max(0, int(std::ceil(-std::log10(step) - 1e-9)));
    return mrpt::format("%.*f", decimals, std::abs(v) < 0.5 * step * 1e-6 ? 0.0 : v);
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

/** The share of the drawing that its content spans: the bounding box of the pixels that are
 *  neither the background nor the grid, over the whole drawing. */
double contentShare(const mrpt::img::CImage& drawing) {
    const int W = int(drawing.getWidth()), H = int(drawing.getHeight());
    const uint8_t* bg = drawing(0, 0);
    const int bgR = bg[2], bgG = bg[1], bgB = bg[0];
    int x0 = W, y0 = H, x1 = -1, y1 = -1;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const uint8_t* p = drawing(x, y);
            const bool background =
                std::abs(p[2] - bgR) + std::abs(p[1] - bgG) + std::abs(p[0] - bgB) < 30;
            const bool grid = std::abs(p[2] - p[1]) < 8 && std::abs(p[1] - p[0]) < 8 && p[1] >= 185;
            if (background || grid) continue;
            x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
        }
    if (x1 < 0) return 0;
    return double(x1 - x0 + 1) * double(y1 - y0 + 1) / (double(W) * double(H));
}

}  // namespace

mrpt::img::TColor robotColour(size_t i) { return palette::series(i); }

void renderTopView(const TopViewContent& c, const std::string& pngPath, unsigned width,
                   unsigned height) {
    COpenGLScene scene;
    scene.getViewport()->setCustomBackgroundColor({1.0f, 1.0f, 1.0f});
    Extent ext;
    Legend legend;
    if (c.world) {
        const auto& w = *c.world;
        ext.add(0, 0);
        ext.add(w.sizeX, w.sizeY);
        // Outlines only: in CFBORender's orthographic top view a filled box hides every line
        // drawn with it, whatever the lines' height.
        auto border = CSetOfLines::Create();
        border->setColor_u8(palette::kGrey);
        border->setLineWidth(2.0f);
        const double X = w.sizeX, Y = w.sizeY;
        border->appendLine(0, 0, 0, X, 0, 0);
        border->appendLine(X, 0, 0, X, Y, 0);
        border->appendLine(X, Y, 0, 0, Y, 0);
        border->appendLine(0, Y, 0, 0, 0, 0);
        scene.insert(border);
        for (const auto& b : w.obstacles) {
            auto box = CBox::Create(b.min, b.max, /*wireframe=*/true);
            box->setColor_u8(palette::kGrey);
            scene.insert(box);
        }
        legend.push_back(
            {w.obstacles.empty() ? "walls" : "walls and obstacles", palette::kGrey, Swatch::Line});
    }
    for (const auto& [robot, t] : c.groundTruth)
        for (const auto& p : t) ext.add(p.pose.x(), p.pose.y());
    for (const auto& [robot, t] : c.estimates)
        for (const auto& p : t) ext.add(p.pose.x(), p.pose.y());
    for (const auto& [robot, t] : c.odometry)  // drawn whole, however far it drifts
        for (const auto& p : t) ext.add(p.pose.x(), p.pose.y());
    for (const auto& b : c.landmarks) ext.add(b.x, b.y);
    if (ext.x0 > ext.x1) throw Error("top view: nothing to draw");
    const double size = std::max({ext.x1 - ext.x0, ext.y1 - ext.y0, 0.5});

    std::vector<WorldLabel> labels;
    // Landmarks (beacons on the ceiling, say) drawn at floor level so paths stay visible,
    // each with its name beside it as the tables give it.
    for (size_t k = 0; k < c.landmarks.size(); ++k) {
        const auto& b = c.landmarks[k];
        auto s = disk(float(0.012 * size + 0.02));
        s->setLocation(b.x, b.y, 0.05);
        s->setColor_u8(palette::kOrange);
        scene.insert(s);
        if (k < c.landmarkLabels.size()) labels.push_back({b.x, b.y, c.landmarkLabels[k]});
    }
    if (!c.landmarks.empty()) legend.push_back({c.landmarksName, palette::kOrange, Swatch::Dot});
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
    // Each robot its colour; the truth a wide pale band under the thin estimate, odometry
    // alone dashed: told apart by width and pattern, not by shade alone.
    bool anyStart = false;
    size_t i = 0;
    std::vector<PicturePath> bands, lines;  // the bands first, under every line
    const auto pathOf = [](const common::Trajectory& t, mrpt::img::TColor colour, int width,
                           bool dashed) {
        PicturePath p{{}, colour, width, dashed};
        for (const auto& s : t) p.points.push_back({s.pose.x(), s.pose.y()});
        return p;
    };
    for (const auto& [robot, est] : c.estimates) {
        const auto colour = robotColour(i++);
        const mrpt::img::TColor pale(uint8_t((colour.R + 2 * 255) / 3),
                                     uint8_t((colour.G + 2 * 255) / 3),
                                     uint8_t((colour.B + 2 * 255) / 3));
        const auto gt = c.groundTruth.find(robot);
        if (gt != c.groundTruth.end() && !gt->second.empty()) {
            if (allStill)
                marker(gt->second.front().pose, float(0.012 * size + 0.03), 0.02f, pale);
            else
                bands.push_back(pathOf(gt->second, pale, 9, false));
            legend.push_back({robot + " truth", pale, allStill ? Swatch::Dot : Swatch::Band});
        }
        if (const auto odo = c.odometry.find(robot);
            !allStill && odo != c.odometry.end() && odo->second.size() > 1) {
            lines.push_back(pathOf(odo->second, colour, 2, true));
            legend.push_back({robot + " odometry alone", colour, Swatch::Dashed});
        }
        if (allStill || est.size() == 1) {
            for (const auto& e : est) marker(e.pose, float(0.005 * size + 0.01), 0.04f, colour);
            legend.push_back({robot + " estimate", colour, Swatch::Dot});
        } else {
            lines.push_back(pathOf(est, colour, 2, false));
            legend.push_back({robot + " estimate", colour, Swatch::Line});
        }
        // the start: where the truth begins, else the estimates
        if (!allStill) {
            const auto& from = gt != c.groundTruth.end() && !gt->second.empty() ? gt->second : est;
            if (!from.empty()) {
                const float r = float(0.015 * size + 0.03);
                auto ring = CDisk::Create(r, 0.7f * r);
                ring->setLocation(from.front().pose.x(), from.front().pose.y(), 0.06);
                ring->setColor_u8(palette::kBlack);
                scene.insert(ring);
                anyStart = true;
            }
        }
    }
    if (anyStart) legend.push_back({"start", palette::kBlack, Swatch::Ring});
    bands.insert(bands.end(), lines.begin(), lines.end());
    saveTopDown(scene, ext.x0, ext.y0, ext.x1, ext.y1, pngPath, width, height, legend, labels,
                bands);
}

void saveTopDown(mrpt::opengl::COpenGLScene& scene, double x0, double y0, double x1, double y1,
                 const std::string& pngPath, unsigned width, unsigned height, const Legend& legend,
                 const std::vector<WorldLabel>& labels, const std::vector<PicturePath>& paths) {
    // the drawing takes the extent's shape: one scale for both axes, a margin of 6 % and at
    // least 0.15 m on each side (markers at the extent stay whole), at least 240 px a side
    const double ex = 1.06 * (x1 - x0) + 0.3, ey = 1.06 * (y1 - y0) + 0.3;
    const double metresPerPixel = std::max(ex / double(width), ey / double(height));
    // sides a multiple of 4: the renderer reads its RGB rows back 4-byte aligned, and any
    // other width writes past the picture's buffer (measured: a heap corruption at 901 px)
    const auto side = [](double px) { return std::max(240, (int(std::ceil(px)) + 3) / 4 * 4); };
    const int w = side(ex / metresPerPixel), h = side(ey / metresPerPixel);
    CFBORender render(w, h);
    auto& cam = render.getCamera(scene);
    cam.setOrthogonal(true);
    cam.setElevationDegrees(90);
    cam.setAzimuthDegrees(-90);
    const double cx = (x0 + x1) / 2, cy = (y0 + y1) / 2;
    cam.setPointingAt(cx, cy, 0);
    // CFBORender's orthographic view is zoomDistance/2 across its shorter side (measured:
    // high when wider than high, wide when higher than wide; a tall drawing set by its
    // height was drawn at its width's scale, TopView.OpenGlAndPixelPathsAgreeInEveryShape)
    cam.setZoomDistance(float(2.0 * std::min(w, h) * metresPerPixel));
    // a grid on the axes' ticks, under everything
    const double step = tickStep(w * metresPerPixel, h * metresPerPixel, metresPerPixel);
    const double gx0 = cx - 0.5 * w * metresPerPixel, gx1 = cx + 0.5 * w * metresPerPixel;
    const double gy0 = cy - 0.5 * h * metresPerPixel, gy1 = cy + 0.5 * h * metresPerPixel;
    auto grid = CGridPlaneXY::Create(std::floor(gx0 / step) * step, std::ceil(gx1 / step) * step,
                                     std::floor(gy0 / step) * step, std::ceil(gy1 / step) * step,
                                     0.001, step);
    grid->setColor_u8(palette::kLightGrey);
    grid->setName("mrloc axes grid");
    scene.insert(grid);
    mrpt::img::CImage drawing;
    render.render_RGB(scene, drawing);
    scene.removeObject(grid);
    framePicture(drawing, cx, cy, metresPerPixel, pngPath, legend, labels, paths);
}

void framePicture(mrpt::img::CImage drawing, double cx, double cy, double metresPerPixel,
                  const std::string& pngPath, const Legend& legend,
                  const std::vector<WorldLabel>& labels, const std::vector<PicturePath>& paths,
                  const std::string& title) {
    const int w = int(drawing.getWidth()), h = int(drawing.getHeight());
    const double step = tickStep(w * metresPerPixel, h * metresPerPixel, metresPerPixel);
    const double gx0 = cx - 0.5 * w * metresPerPixel, gx1 = cx + 0.5 * w * metresPerPixel;
    const double gy0 = cy - 0.5 * h * metresPerPixel, gy1 = cy + 0.5 * h * metresPerPixel;
    const auto toPixelX = [&](double x) { return w / 2.0 + (x - cx) / metresPerPixel; };
    const auto toPixelY = [&](double y) { return h / 2.0 - (y - cy) / metresPerPixel; };
    drawPaths(drawing, paths,
              [&](double x, double y) { return std::make_pair(toPixelX(x), toPixelY(y)); });
    std::vector<std::pair<double, std::string>> xTicks, yTicks;
    for (double t = std::ceil(gx0 / step) * step; t <= gx1; t += step)
        xTicks.emplace_back(toPixelX(t), tickText(t, step));
    for (double t = std::ceil(gy0 / step) * step; t <= gy1; t += step)
        yTicks.emplace_back(toPixelY(t), tickText(t, step));
    size_t widest = 5;  // "y (m)"
    for (const auto& [p, text] : yTicks) widest = std::max(widest, text.size());
    // the drawing framed by axes: tick labels left and below, the axes' names, the title above
    const int left = 16 + kCharWidth * int(widest), top = title.empty() ? 26 : 50, bottom = 46,
              right = 14;
    const int panel = legendWidth(legend);
    const int rowsHeight = top + 10 + kLegendRow * int(legend.size());
    const int W = std::max(left + w + right + panel, left + kCharWidth * int(title.size()) + 8);
    const int H = std::max(top + h + bottom, rowsHeight);
    mrpt::img::CImage img(W, H, mrpt::img::CH_RGB);
    const mrpt::img::TColor white(255, 255, 255), ink(30, 30, 30);
    img.filledRectangle(0, 0, W - 1, H - 1, white);
    img.drawImage(left, top, drawing);
    PictureLayout layout;
    layout.width = W, layout.height = H;
    layout.data = {left, top, left + w, top + h};
    layout.inkShare = contentShare(drawing);
    img.rectangle(left - 1, top - 1, left + w, top + h, ink, 1);
    img.selectTextFont("9x15");
    if (!title.empty()) img.textOut(left, 6, title, ink);
    for (const auto& [p, text] : xTicks) {
        const int u = left + int(std::lround(p));
        img.line(u, top + h, u, top + h + 5, ink, 1);
        img.textOut(u - kCharWidth * int(text.size()) / 2, top + h + 8, text, ink);
    }
    for (const auto& [p, text] : yTicks) {
        const int v = top + int(std::lround(p));
        img.line(left - 6, v, left - 1, v, ink, 1);
        img.textOut(left - 8 - kCharWidth * int(text.size()), v - 7, text, ink);
    }
    img.textOut(left + w / 2 - 2 * kCharWidth, top + h + 26, "x (m)", ink);
    img.textOut(4, top - 22, "y (m)", ink);
    img.selectTextFont("10x20");
    for (const auto& l : labels) {
        // names whose place is outside the drawing (a close-up) are left out
        if (l.x < gx0 || l.x > gx1 || l.y < gy0 || l.y > gy1) continue;
        // the name centred above its place, on white, kept inside the drawing
        const int lw = 10 * int(l.text.size()) + 6, lh = 22;
        const int px =
            left + std::clamp(int(std::lround(toPixelX(l.x))) - lw / 2, 0, std::max(0, w - lw));
        const int py =
            top + std::clamp(int(std::lround(toPixelY(l.y))) - 22 - lh, 0, std::max(0, h - lh));
        img.filledRectangle(px, py, px + lw, py + lh, white);
        img.rectangle(px, py, px + lw, py + lh, ink);
        img.textOut(px + 3, py + 1, l.text, ink);
        layout.labels.push_back({px, py, px + lw, py + lh});
    }
    if (!legend.empty()) {
        const int x = left + w + right;
        drawLegend(img, x, top, legend);
        layout.legend = PixelBox{x, top, x + panel, top + kLegendRow * int(legend.size())};
        layout.key = "outside";
    }
    common::PendingFile out(pngPath, ".tmp.png");  // CImage picks the format by extension
    if (!img.saveToFile(out.tempPath())) throw Error("cannot write " + pngPath);
    writeLayout(out.tempPath(), layout);
    out.commit();
}

}  // namespace mrloc::report
