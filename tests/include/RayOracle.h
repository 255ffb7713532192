#pragma once
// A ray-casting oracle for visibility polygons, independent of the triangulation: the
// distance a viewer at q sees along a direction, from P's edges alone. Edges are bucketed in
// a uniform grid and a ray visits the cells it crosses in order (Amanatides and Woo 1987),
// so maps of 5000 vertices can be checked at thousands of viewpoints.
#include <mrloc/common/Polygon.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace mrloc::testing {

class RayOracle {
 public:
    explicit RayOracle(const common::Polygon& P) : P_(P) {
        const auto size = P.max() - P.min();
        cells_ = std::max(1, (int)std::ceil(2 * std::sqrt((double)P.size())));
        cell_ = std::max(size.x, size.y) / cells_ * (1 + 1e-9);
        grid_.resize((size_t)cells_ * (size_t)cells_);
        for (size_t e = 0; e < P.size(); ++e) {
            const auto &a = P[e], &b = P[P.next(e)];
            // Every cell the edge's bounding box touches (edges are short against the map,
            // or the grid is coarse where they are long: good enough for a test).
            const int x0 = cellX(std::min(a.x, b.x)), x1 = cellX(std::max(a.x, b.x));
            const int y0 = cellY(std::min(a.y, b.y)), y1 = cellY(std::max(a.y, b.y));
            for (int y = y0; y <= y1; ++y)
                for (int x = x0; x <= x1; ++x) grid_[(size_t)(y * cells_ + x)].push_back(e);
        }
    }

    /** Distance from q along unit dir to the first edge beyond tMin (0 if none). */
    double cast(const common::TPoint2D& q, const common::TVector2D& dir, double tMin) const {
        int x = cellX(q.x), y = cellY(q.y);
        const int stepX = dir.x > 0 ? 1 : -1, stepY = dir.y > 0 ? 1 : -1;
        const auto boundary = [&](double origin, double lo, int c, int step, double d) {
            if (d == 0) return std::numeric_limits<double>::infinity();
            const double edge = lo + (c + (step > 0 ? 1 : 0)) * cell_;
            return (edge - origin) / d;
        };
        double tX = boundary(q.x, P_.min().x, x, stepX, dir.x);
        double tY = boundary(q.y, P_.min().y, y, stepY, dir.y);
        const double dX = dir.x == 0 ? INFINITY : cell_ / std::abs(dir.x);
        const double dY = dir.y == 0 ? INFINITY : cell_ / std::abs(dir.y);
        while (x >= 0 && y >= 0 && x < cells_ && y < cells_) {
            const double cellExit = std::min(tX, tY);
            double best = INFINITY;
            for (size_t e : grid_[(size_t)(y * cells_ + x)])
                if (const auto t = common::raySegmentHit(P_[e], P_[P_.next(e)], q, dir, tMin))
                    best = std::min(best, *t);
            if (best <= cellExit + 1e-12 * cell_) return best;
            if (tX < tY)
                tX += dX, x += stepX;
            else
                tY += dY, y += stepY;
        }
        return 0;
    }

 private:
    int cellX(double v) const { return std::clamp((int)((v - P_.min().x) / cell_), 0, cells_ - 1); }
    int cellY(double v) const { return std::clamp((int)((v - P_.min().y) / cell_), 0, cells_ - 1); }

    const common::Polygon& P_;
    int cells_;
    double cell_;
    std::vector<std::vector<size_t>> grid_;
};

}  // namespace mrloc::testing
