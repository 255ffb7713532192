#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/polymap/WallMap.h>
#include <mrpt/core/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <sstream>

namespace mrloc::polymap {

RayCaster::RayCaster(std::vector<WallSegment> walls, double cellSize)
    : walls_(std::move(walls)), cell_(cellSize) {
    if (walls_.empty()) return;
    TPoint2D lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
    for (const auto& w : walls_)
        for (const auto& p : {w.a, w.b})
            lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)},
            hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    // at most ~4 million cells: a larger map gets larger cells
    const double area = (hi.x - lo.x + cell_) * (hi.y - lo.y + cell_);
    cell_ = std::max(cell_, std::sqrt(area / 4e6));
    min_ = lo;
    nx_ = int((hi.x - lo.x) / cell_) + 1;
    ny_ = int((hi.y - lo.y) / cell_) + 1;
    std::vector<std::vector<uint32_t>> cells(size_t(nx_) * size_t(ny_));
    for (uint32_t k = 0; k < walls_.size(); ++k) {
        // every cell of the segment's box: a few more than it crosses, never fewer
        const auto& w = walls_[k];
        const int x0 = std::clamp(int((std::min(w.a.x, w.b.x) - min_.x) / cell_), 0, nx_ - 1);
        const int x1 = std::clamp(int((std::max(w.a.x, w.b.x) - min_.x) / cell_), 0, nx_ - 1);
        const int y0 = std::clamp(int((std::min(w.a.y, w.b.y) - min_.y) / cell_), 0, ny_ - 1);
        const int y1 = std::clamp(int((std::max(w.a.y, w.b.y) - min_.y) / cell_), 0, ny_ - 1);
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) {
                // skip box cells the segment's line passes farther from than half a diagonal
                const TPoint2D c{min_.x + (x + 0.5) * cell_, min_.y + (y + 0.5) * cell_};
                if (common::distanceToSegment(c, w.a, w.b) > 0.71 * cell_) continue;
                cells[size_t(y) * nx_ + x].push_back(k);
            }
    }
    start_.assign(cells.size() + 1, 0);
    for (size_t c = 0; c < cells.size(); ++c) start_[c + 1] = start_[c] + uint32_t(cells[c].size());
    items_.reserve(start_.back());
    for (const auto& c : cells) items_.insert(items_.end(), c.begin(), c.end());
}

double RayCaster::cast(const TPoint2D& o, double angle, double maxRange) const {
    if (walls_.empty()) return maxRange;
    const double dx = std::cos(angle), dy = std::sin(angle);
    // enter the grid's box (a scanner outside it sees walls only if the ray enters it)
    double tEnter = 0, tExit = maxRange;
    const double bx0 = min_.x, bx1 = min_.x + nx_ * cell_, by0 = min_.y, by1 = min_.y + ny_ * cell_;
    for (const auto& [o1, d1, lo, hi] : {std::tuple{o.x, dx, bx0, bx1}, {o.y, dy, by0, by1}}) {
        if (std::abs(d1) < 1e-15) {
            if (o1 < lo || o1 > hi) return maxRange;
            continue;
        }
        double t0 = (lo - o1) / d1, t1 = (hi - o1) / d1;
        if (t0 > t1) std::swap(t0, t1);
        tEnter = std::max(tEnter, t0);
        tExit = std::min(tExit, t1);
    }
    if (tEnter > tExit) return maxRange;
    const double px = o.x + tEnter * dx - min_.x, py = o.y + tEnter * dy - min_.y;
    int cx = std::clamp(int(px / cell_), 0, nx_ - 1), cy = std::clamp(int(py / cell_), 0, ny_ - 1);
    const int stepX = dx > 0 ? 1 : -1, stepY = dy > 0 ? 1 : -1;
    const double inf = std::numeric_limits<double>::infinity();
    double tMaxX = std::abs(dx) < 1e-15 ? inf : tEnter + ((cx + (dx > 0)) * cell_ - px) / dx;
    double tMaxY = std::abs(dy) < 1e-15 ? inf : tEnter + ((cy + (dy > 0)) * cell_ - py) / dy;
    const double tDeltaX = std::abs(dx) < 1e-15 ? inf : cell_ / std::abs(dx);
    const double tDeltaY = std::abs(dy) < 1e-15 ? inf : cell_ / std::abs(dy);
    const TVector2D dir{dx, dy};
    double best = maxRange;
    for (;;) {
        const size_t c = size_t(cy) * nx_ + cx;
        for (uint32_t k = start_[c]; k < start_[c + 1]; ++k) {
            const auto& w = walls_[items_[k]];
            if (const auto t = common::raySegmentHit(w.a, w.b, o, dir, 0); t && *t < best)
                best = *t;
        }
        const double cellExit = std::min(tMaxX, tMaxY);
        if (best <= cellExit || cellExit > tExit) return best;
        if (tMaxX < tMaxY) {
            cx += stepX;
            tMaxX += tDeltaX;
            if (cx < 0 || cx >= nx_) return best;
        } else {
            cy += stepY;
            tMaxY += tDeltaY;
            if (cy < 0 || cy >= ny_) return best;
        }
    }
}

bool FreeCells::at(const TPoint2D& p) const {
    const double fx = std::floor((p.x - min.x) / resolution);
    const double fy = std::floor((p.y - min.y) / resolution);
    // compared as doubles first: a far point must not overflow the int conversion
    if (!(fx >= 0 && fy >= 0 && fx < width && fy < height)) return false;
    return free[size_t(fy) * size_t(width) + size_t(fx)] != 0;
}

size_t FreeCells::count() const { return size_t(std::count(free.begin(), free.end(), 1)); }

namespace {

std::vector<TPoint2D> validRing(std::vector<TPoint2D> ring, const std::string& what) {
    // the one-ring checks of every .poly: O(n log n), exact orientations
    return common::Polygon::fromVertices(std::move(ring), what).vertices();
}

}  // namespace

std::vector<std::vector<TPoint2D>> loadPolyRings(const std::string& path) {
    const auto read = common::Polygon::readRings(path, kMaxWallVertices, kMaxRings);
    if (read.empty()) throw Error("polygon map " + path + ": no vertices");
    std::vector<std::vector<TPoint2D>> rings;
    std::vector<int> firstLine;
    for (size_t r = 0; r < read.size(); ++r) {
        firstLine.push_back(read[r].firstLine);
        rings.push_back(validRing(read[r].vertices, path + mrpt::format(" (ring %zu, from line %d)",
                                                                        r + 1, read[r].firstLine)));
    }
    // holes inside the outer ring and outside each other, no two rings crossing or touching:
    // the exact pipeline's own check (common::Polygon::fromRings, one sweep over all edges on
    // exact orientations; Boost.Geometry's is_valid overflowed its integer rescaling on maps
    // a fuzzer wrote)
    if (rings.size() > 1) common::Polygon::fromRings(rings, path, kMaxWallVertices, firstLine);
    return rings;
}

void savePolyRings(const std::string& path, const std::vector<std::vector<TPoint2D>>& rings,
                   const std::string& comment) {
    std::ostringstream out;
    out << "# polygon map with holes: the first ring is the outer boundary, the others holes;"
           " rings separated by a blank line\n";
    if (!comment.empty()) out << "# " << comment << "\n";
    out.precision(17);
    for (size_t r = 0; r < rings.size(); ++r) {
        if (r) out << "\n";
        for (const auto& p : rings[r]) out << p.x << " " << p.y << "\n";
    }
    common::writeFileAtomically(path, out.str());
}

namespace {

/** The cells of `free` (1 inside the free space) at least `clearance` from every wall. */
FreeCells clearCells(const cv::Mat& freeMask, const std::vector<WallSegment>& walls,
                     const TPoint2D& min, double resolution, double clearance) {
    cv::Mat open = freeMask.clone();
    const auto pix = [&](const TPoint2D& p) {
        return cv::Point(int(std::lround((p.x - min.x) / resolution * 16 - 8)),
                         int(std::lround((p.y - min.y) / resolution * 16 - 8)));
    };
    for (const auto& w : walls) cv::line(open, pix(w.a), pix(w.b), 0, 1, cv::LINE_8, 4);
    cv::Mat dist;
    cv::distanceTransform(open, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE);
    FreeCells cells;
    cells.min = min;
    cells.resolution = resolution;
    cells.width = freeMask.cols;
    cells.height = freeMask.rows;
    cells.free.assign(size_t(cells.width) * cells.height, 0);
    for (int y = 0; y < dist.rows; ++y)
        for (int x = 0; x < dist.cols; ++x)
            cells.free[size_t(y) * cells.width + x] =
                freeMask.at<uint8_t>(y, x) && dist.at<float>(y, x) * resolution >= clearance;
    return cells;
}

}  // namespace

WallMap wallMapOfRings(std::vector<std::vector<TPoint2D>> rings, double resolution,
                       double clearance, const std::string& description) {
    WallMap map;
    map.description = description;
    std::vector<WallSegment> walls;
    TPoint2D lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
    for (const auto& ring : rings)
        for (size_t i = 0; i < ring.size(); ++i) {
            walls.push_back({ring[i], ring[(i + 1) % ring.size()]});
            lo = {std::min(lo.x, ring[i].x), std::min(lo.y, ring[i].y)};
            hi = {std::max(hi.x, ring[i].x), std::max(hi.y, ring[i].y)};
        }
    map.min = lo;
    map.max = hi;
    // the free mask: the outer ring filled, the holes cut out (even-odd over all rings), on a
    // grid with a margin of empty cells (the distance transform measures from them)
    const double extent = std::max(hi.x - lo.x, hi.y - lo.y);
    resolution = std::max(resolution, extent / 4000);  // at most 4000 x 4000 cells
    lo = lo - TPoint2D{3 * resolution, 3 * resolution};
    const int w = int((hi.x - lo.x) / resolution) + 5, h = int((hi.y - lo.y) / resolution) + 5;
    cv::Mat mask = cv::Mat::zeros(h, w, CV_8U);
    std::vector<std::vector<cv::Point>> contours;
    for (const auto& ring : rings) {
        auto& c = contours.emplace_back();
        for (const auto& p : ring)
            c.emplace_back(int(std::lround((p.x - lo.x) / resolution * 16 - 8)),
                           int(std::lround((p.y - lo.y) / resolution * 16 - 8)));
    }
    cv::fillPoly(mask, contours, 1, cv::LINE_8, 4);
    map.freeCells = clearCells(mask, walls, lo, resolution, clearance);
    map.caster = RayCaster(std::move(walls), std::max(0.25, 5 * resolution));
    map.outer.assign(rings.size(), false);
    if (!rings.empty()) map.outer[0] = true;
    map.rings = std::move(rings);
    return map;
}

}  // namespace mrloc::polymap
