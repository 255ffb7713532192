#include <mrloc/common/Error.h>
#include <mrloc/common/Polygon.h>
#include <mrloc/common/RawlogProbe.h>
#include <mrloc/polymap/GridTrace.h>
#include <mrloc/report/Palette.h>
#include <mrloc/report/TopView.h>
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/core/format.h>
#include <mrpt/img/CImage.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/maps/CSimpleMap.h>
#include <mrpt/serialization/CArchive.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <unordered_map>

namespace mrloc::polymap {

namespace {

bool endsWith(const std::string& s, const std::string& tail) {
    return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

std::string withoutGz(const std::string& path) {
    return endsWith(path, ".gz") ? path.substr(0, path.size() - 3) : path;
}

void checkGridSize(const mrpt::maps::COccupancyGridMap2D& grid, const std::string& path) {
    const double cells = double(grid.getSizeX()) * double(grid.getSizeY());
    if (cells > kMaxGridCells || grid.getResolution() <= 0 || !std::isfinite(grid.getXMin()) ||
        !std::isfinite(grid.getYMin()))
        throw Error(mrpt::format(
            "map %s: a grid of %u x %u cells of %g m, beyond the %.0f "
            "cells mrloc takes (doc/errors.md)",
            path.c_str(), grid.getSizeX(), grid.getSizeY(), grid.getResolution(), kMaxGridCells));
}

mrpt::maps::COccupancyGridMap2D readGrid(const std::string& path, const GridTraceOptions& o) {
    mrpt::maps::COccupancyGridMap2D grid;
    if (endsWith(withoutGz(path), ".gridmap")) {
        mrpt::io::CFileGZInputStream in(path);
        mrpt::serialization::archiveFrom(in) >> grid;
        checkGridSize(grid, path);
        return grid;
    }
    mrpt::maps::CSimpleMap simple;
    {
        mrpt::io::CFileGZInputStream in(path);
        mrpt::serialization::archiveFrom(in) >> simple;
    }
    if (simple.empty()) throw Error("map " + path + ": the simplemap holds no observations");
    // the grid's size follows the poses: bound them before MRPT allocates anything
    for (size_t i = 0; i < simple.size(); ++i) {
        const auto& [pose, frame] = simple.get(i);
        if (!pose || !frame)
            throw Error(mrpt::format("map %s: entry %zu is empty", path.c_str(), i));
        const auto mean = pose->getMeanVal();
        if (!std::isfinite(mean.x()) || !std::isfinite(mean.y()) || std::abs(mean.x()) > 1e5 ||
            std::abs(mean.y()) > 1e5)
            throw Error(mrpt::format("map %s: entry %zu's pose (%g, %g) is not a building's",
                                     path.c_str(), i, mean.x(), mean.y()));
    }
    grid = mrpt::maps::COccupancyGridMap2D(-1, 1, -1, 1, float(o.resolution));
    if (o.insertOptions)
        grid.insertionOptions.loadFromConfigFile(*o.insertOptions, o.insertSection);
    grid.loadFromSimpleMap(simple);
    checkGridSize(grid, path);
    return grid;
}

}  // namespace

bool isMrptMapFile(const std::string& path) {
    const std::string p = withoutGz(path);
    return endsWith(p, ".gridmap") || endsWith(p, ".simplemap");
}

mrpt::maps::COccupancyGridMap2D loadGridMap(const std::string& path,
                                            const GridTraceOptions& options) {
    if (!isMrptMapFile(path))
        throw Error("map " + path + ": expected a .gridmap or .simplemap (optionally .gz)");
    // a stranger's file is deserialized first where a crash or a huge allocation cannot harm
    common::probeFile(path, "map", [&] { readGrid(path, options); });
    try {
        return readGrid(path, options);
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error("map " + path + ": " + oneLine(e.what()));
    }
}

WallMap traceGrid(const mrpt::maps::COccupancyGridMap2D& grid, const GridTraceOptions& o,
                  const std::string& description, TraceStats* stats) {
    const int w = int(grid.getSizeX()), h = int(grid.getSizeY());
    const double res = grid.getResolution();
    cv::Mat occupied = cv::Mat::zeros(h, w, CV_8U), freeMask = cv::Mat::zeros(h, w, CV_8U);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float p = grid.getCell(x, y);
            occupied.at<uint8_t>(y, x) = p < o.occupied;
            freeMask.at<uint8_t>(y, x) = p > o.free;
        }
    TraceStats s;
    s.gridWidth = w;
    s.gridHeight = h;
    s.resolution = res;
    // specks: 8-connected occupied blobs of fewer than speckCells cells
    cv::Mat labels, blobStats, centroids;
    const int blobs = cv::connectedComponentsWithStats(occupied, labels, blobStats, centroids, 8);
    std::vector<uint8_t> keep(size_t(blobs), 1);
    for (int b = 1; b < blobs; ++b)
        if (blobStats.at<int>(b, cv::CC_STAT_AREA) < o.speckCells) keep[b] = 0, ++s.specksDropped;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (!keep[size_t(labels.at<int>(y, x))]) occupied.at<uint8_t>(y, x) = 0;
    // every boundary of every blob (outer and inner), as chains of boundary cells' centres
    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(occupied, contours, cv::RETR_LIST, cv::CHAIN_APPROX_NONE);
    s.simplify = o.simplify > 0 ? o.simplify : 0.5 * res;
    const double x0 = grid.getXMin(), y0 = grid.getYMin();
    std::vector<std::vector<TPoint2D>> rings;
    size_t vertices = 0;
    for (const auto& c : contours) {
        s.contourPoints += c.size();
        std::vector<cv::Point> simple;
        cv::approxPolyDP(c, simple, s.simplify / res, true);
        auto& ring = rings.emplace_back();
        for (const auto& p : simple)
            ring.push_back({x0 + (p.x + 0.5) * res, y0 + (p.y + 0.5) * res});
        vertices += ring.size();
        if (rings.size() > kMaxRings || vertices > kMaxWallVertices)
            throw Error(description + mrpt::format(": more than %zu rings or %zu vertices traced",
                                                   kMaxRings, kMaxWallVertices));
    }
    // walls: every ring's edges (a one-cell-thick wall traces as a ring folded on itself, which
    // a beam still stops at); the free cells clear of them
    WallMap map;
    map.description = description;
    std::vector<WallSegment> walls;
    for (const auto& ring : rings) {
        if (ring.size() == 1) {  // a blob traced to one point: a short wall across it
            const TPoint2D d{0.25 * res, 0};
            walls.push_back({ring[0] - d, ring[0] + d});
            continue;
        }
        for (size_t i = 0; i < ring.size(); ++i)
            walls.push_back({ring[i], ring[(i + 1) % ring.size()]});
    }
    cv::Mat notWall = 1 - occupied;
    cv::Mat dist;
    cv::distanceTransform(notWall, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE);
    map.freeCells.min = {x0, y0};
    map.freeCells.resolution = res;
    map.freeCells.width = w;
    map.freeCells.height = h;
    map.freeCells.free.assign(size_t(w) * h, 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            map.freeCells.free[size_t(y) * w + x] =
                freeMask.at<uint8_t>(y, x) && dist.at<float>(y, x) * res >= o.clearance;
    map.min = {x0, y0};
    map.max = {grid.getXMax(), grid.getYMax()};
    map.caster = RayCaster(std::move(walls), std::max(0.25, 5 * res));
    map.outer.assign(rings.size(), false);
    map.rings = std::move(rings);
    if (stats) *stats = s;
    return map;
}

namespace {

/** Twice the signed area of a ring (positive: counter-clockwise). */
double twiceArea(const std::vector<TPoint2D>& ring) {
    double a = 0;
    for (size_t i = 0; i < ring.size(); ++i)
        a += common::cross(ring[i], ring[(i + 1) % ring.size()]);
    return a;
}

/** Douglas-Peucker within `tolerance` (m), by OpenCV, in cells from `origin` (OpenCV takes
 *  floats: a quarter cell is exact in them); a ring too small to simplify is kept. */
std::vector<TPoint2D> simplified(const std::vector<TPoint2D>& ring, double tolerance,
                                 const TPoint2D& origin, double res) {
    if (tolerance <= 0) return ring;
    std::vector<cv::Point2f> in, out;
    for (const auto& p : ring)
        in.push_back({float((p.x - origin.x) / res), float((p.y - origin.y) / res)});
    cv::approxPolyDP(in, out, tolerance / res, true);
    if (out.size() < 3) return ring;
    std::vector<TPoint2D> r;
    for (const auto& p : out) r.push_back({origin.x + p.x * res, origin.y + p.y * res});
    return r;
}

}  // namespace

std::vector<std::vector<TPoint2D>> traceFreeSpace(const mrpt::maps::COccupancyGridMap2D& grid,
                                                  const GridTraceOptions& o, const TPoint2D& inside,
                                                  const std::string& description) {
    const int w = int(grid.getSizeX()), h = int(grid.getSizeY());
    const double res = grid.getResolution(), x0 = grid.getXMin(), y0 = grid.getYMin();
    const int sx = grid.x2idx(inside.x), sy = grid.y2idx(inside.y);
    if (sx < 0 || sy < 0 || sx >= w || sy >= h || !(grid.getCell(sx, sy) > o.free))
        throw Error(description + mrpt::format(": (%g %g) is not on a free cell of the map (free "
                                               "probability above %g)",
                                               inside.x, inside.y, o.free));
    // free cells, the passages narrower than `open` closed (an opening: erosion, then
    // dilation, by a square of the fewest odd number of cells at least that wide)
    cv::Mat freeCells(h, w, CV_8U);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) freeCells.at<uint8_t>(y, x) = grid.getCell(x, y) > o.free;
    const int openCells = 2 * int(std::ceil(0.5 * (o.open / res - 1) - 1e-9)) + 1;
    if (openCells > 1)
        cv::morphologyEx(freeCells, freeCells, cv::MORPH_OPEN,
                         cv::getStructuringElement(cv::MORPH_RECT, {openCells, openCells}));
    if (!freeCells.at<uint8_t>(sy, sx))
        throw Error(description + mrpt::format(": (%g %g) is in free space narrower than %g m "
                                               "(trace_open)",
                                               inside.x, inside.y, openCells * res));
    // the region: free cells 4-connected to the start's
    std::vector<uint8_t> region(size_t(w) * h, 0);
    const auto in = [&](int x, int y) {
        return x >= 0 && y >= 0 && x < w && y < h && region[size_t(y) * w + x];
    };
    std::vector<std::pair<int, int>> stack{{sx, sy}};
    region[size_t(sy) * w + sx] = 1;
    while (!stack.empty()) {
        const auto [x, y] = stack.back();
        stack.pop_back();
        for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
            const int nx = x + dx, ny = y + dy;
            if (nx < 0 || ny < 0 || nx >= w || ny >= h || region[size_t(ny) * w + nx] ||
                !freeCells.at<uint8_t>(ny, nx))
                continue;
            region[size_t(ny) * w + nx] = 1;
            stack.push_back({nx, ny});
        }
    }
    // The boundary along cell edges, region on the left: edge e runs from corner from[e] in
    // direction dir[e] (a unit step); corners are numbered y * (w + 1) + x.
    struct Edge {
        int x, y, dx, dy;
    };
    std::vector<Edge> edges;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (!in(x, y)) continue;
            if (!in(x, y - 1)) edges.push_back({x, y, 1, 0});
            if (!in(x + 1, y)) edges.push_back({x + 1, y, 0, 1});
            if (!in(x, y + 1)) edges.push_back({x + 1, y + 1, -1, 0});
            if (!in(x - 1, y)) edges.push_back({x, y + 1, 0, -1});
            if (edges.size() > 4 * kMaxWallVertices)
                throw Error(description + mrpt::format(": the free space's boundary has more "
                                                       "than %zu cell edges",
                                                       4 * kMaxWallVertices));
        }
    const auto corner = [w](int x, int y) { return int64_t(y) * (w + 1) + x; };
    std::unordered_map<int64_t, std::array<int, 2>> leaving;  // at most two: a pinch
    for (size_t e = 0; e < edges.size(); ++e) {
        auto [it, fresh] = leaving.try_emplace(corner(edges[e].x, edges[e].y), std::array{-1, -1});
        it->second[fresh ? 0 : 1] = int(e);
    }
    std::vector<uint8_t> used(edges.size(), 0);
    std::vector<std::vector<TPoint2D>> rings;
    for (size_t first = 0; first < edges.size(); ++first) {
        if (used[first]) continue;
        std::vector<TPoint2D> ring;
        int e = int(first);
        do {
            used[size_t(e)] = 1;
            const Edge& E = edges[size_t(e)];
            const int cx = E.x + E.dx, cy = E.y + E.dy;
            const auto& out = leaving.at(corner(cx, cy));
            int next = out[0];
            const bool pinch = out[1] >= 0;
            if (pinch)  // turn left: stay around the cell on the left (4-connected region)
                next = edges[size_t(out[0])].dx == -E.dy && edges[size_t(out[0])].dy == E.dx
                           ? out[0]
                           : out[1];
            const Edge& N = edges[size_t(next)];
            if (pinch) {  // the pinch vertex becomes two: the corner cut a quarter cell
                ring.push_back({x0 + (cx - 0.25 * E.dx) * res, y0 + (cy - 0.25 * E.dy) * res});
                ring.push_back({x0 + (cx + 0.25 * N.dx) * res, y0 + (cy + 0.25 * N.dy) * res});
            } else if (N.dx != E.dx || N.dy != E.dy) {
                ring.push_back({x0 + cx * res, y0 + cy * res});
            }
            e = next;
            if (used[size_t(e)] && e != int(first))  // every edge is walked once
                throw Error(description +
                            ": the free space's boundary did not close "
                            "(internal error)");
        } while (e != int(first));
        rings.push_back(std::move(ring));
    }
    // the outer ring (the one counter-clockwise ring of a connected region) first, then the
    // holes not below speckCells cells
    std::vector<std::vector<TPoint2D>> kept;
    for (auto& r : rings)
        if (twiceArea(r) > 0) kept.insert(kept.begin(), std::move(r));
    if (kept.size() != 1)
        throw Error(description + ": the free space traced into " + std::to_string(kept.size()) +
                    " outer rings (internal error)");
    const double sliver = 2 * o.speckCells * res * res;
    for (auto& r : rings)
        if (!r.empty() && twiceArea(r) <= -sliver) kept.push_back(std::move(r));
    // simplified within the tolerance, halved until every ring and the whole validate
    for (double tolerance = o.simplify > 0 ? o.simplify : 0.5 * res;; tolerance /= 2) {
        if (tolerance < res / 64) tolerance = 0;  // as traced: valid by construction
        std::vector<std::vector<TPoint2D>> out;
        for (const auto& r : kept) out.push_back(simplified(r, tolerance, {x0, y0}, res));
        try {
            common::Polygon::fromRings(out, description, kMaxWallVertices);
            return out;
        } catch (const Error&) {
            if (tolerance == 0) throw;
        }
    }
}

void renderMap(const mrpt::maps::COccupancyGridMap2D* grid, const WallMap& map,
               const MapOverlay& overlay, const std::string& pngPath, const std::string& title) {
    // the box drawn: the overlay's (with a margin), else the grid's known part, else the map's
    TPoint2D lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
    const auto grow = [&](const TPoint2D& p) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    };
    if (overlay.cropToOverlay) {
        for (const auto& h : overlay.hypotheses) grow({h.x, h.y});
        for (const auto& path : overlay.paths)
            for (const auto& p : path.points) grow(p);
    }
    if (!std::isfinite(lo.x) && grid) {
        const int w = int(grid->getSizeX()), h = int(grid->getSizeY());
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                if (std::abs(grid->getCell(x, y) - 0.5f) > 0.05f)
                    grow({grid->idx2x(x), grid->idx2y(y)});
    }
    if (!std::isfinite(lo.x)) lo = map.min, hi = map.max;
    const double pad = std::max(1.0, 0.05 * std::max(hi.x - lo.x, hi.y - lo.y));
    lo = lo - TPoint2D{pad, pad};
    hi = hi + TPoint2D{pad, pad};
    const double scale = std::min(1400.0 / (hi.x - lo.x), 900.0 / (hi.y - lo.y));  // px per m
    const int W = std::max(200, int((hi.x - lo.x) * scale)),
              H = std::max(100, int((hi.y - lo.y) * scale));
    cv::Mat view(H, W, CV_8UC3);  // the map alone: it clips what lies outside the box
    const auto world = [&](int x, int y) {
        return TPoint2D{lo.x + (x + 0.5) / scale, hi.y - (y + 0.5) / scale};
    };
    const auto pix = [&](const TPoint2D& p) {
        return cv::Point(int(std::clamp((p.x - lo.x) * scale, -1e6, 1e6)),
                         int(std::clamp((hi.y - p.y) * scale, -1e6, 1e6)));
    };
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const TPoint2D p = world(x, y);
            uint8_t v = 255;
            if (grid) {
                const int gx = grid->x2idx(p.x), gy = grid->y2idx(p.y);
                v = gx >= 0 && gy >= 0 && gx < int(grid->getSizeX()) && gy < int(grid->getSizeY())
                        ? uint8_t(std::clamp(grid->getCell(gx, gy), 0.f, 1.f) * 255)
                        : 128;
            }
            cv::Vec3b px{v, v, v};
            if (map.freeCells.at(p)) px = {uint8_t(v * 0.8), v, uint8_t(v * 0.8)};
            view.at<cv::Vec3b>(y, x) = px;
        }
    // the palette's colours (report/Palette.h), as OpenCV's blue-green-red
    const auto bgr = [](mrpt::img::TColor c) { return cv::Scalar(c.B, c.G, c.R); };
    namespace pal = report::palette;
    for (const auto& ring : map.rings) {
        std::vector<cv::Point> pts;
        for (const auto& p : ring) pts.push_back(pix(p));
        cv::polylines(view, pts, true, bgr(pal::kPurple), scale > 40 ? 2 : 1, cv::LINE_AA);
    }
    for (size_t k = 0; k < overlay.paths.size(); ++k) {
        std::vector<cv::Point> pts;
        for (const auto& p : overlay.paths[k].points) pts.push_back(pix(p));
        cv::polylines(view, pts, false, bgr(pal::series(k)), 2, cv::LINE_AA);
        if (!pts.empty()) cv::circle(view, pts.front(), 4, bgr(pal::series(k)), -1, cv::LINE_AA);
    }
    const double arrow = std::max(0.6, 18 / scale);  // m
    for (const auto& h : overlay.hypotheses) {
        const cv::Point a = pix({h.x, h.y});
        const cv::Point b = pix({h.x + arrow * std::cos(h.phi), h.y + arrow * std::sin(h.phi)});
        cv::arrowedLine(view, a, b, bgr(pal::kBlack), 2, cv::LINE_AA, 0, 0.35);
    }
    using report::Swatch;
    report::Legend legend;
    if (grid) {
        legend.push_back({"free (grid)", {255, 255, 255}, Swatch::Patch});
        legend.push_back({"unknown (grid)", {128, 128, 128}, Swatch::Patch});
        legend.push_back({"occupied (grid)", {0, 0, 0}, Swatch::Patch});
    }
    legend.push_back({"where the scanner may stand", {204, 255, 204}, Swatch::Patch});
    legend.push_back(
        {grid ? "traced rings (walls)" : "the map's rings (walls)", pal::kPurple, Swatch::Line});
    if (!overlay.hypotheses.empty())
        legend.push_back({"hypotheses, first scan (heading)", pal::kBlack, Swatch::Arrow});
    for (size_t k = 0; k < overlay.paths.size(); ++k)
        legend.push_back({overlay.paths[k].label + " (dot: start)", pal::series(k), Swatch::Line});
    mrpt::img::CImage drawing(view, mrpt::img::DEEP_COPY);
    report::framePicture(drawing, lo.x + 0.5 * W / scale, hi.y - 0.5 * H / scale, 1 / scale,
                         pngPath, legend, {}, {}, title);
}

}  // namespace mrloc::polymap
