#include <mrloc/common/Error.h>
#include <mrloc/polymap/MapGenerators.h>
#include <mrpt/core/format.h>

#include <algorithm>
#include <cmath>

namespace mrloc::polymap {

using common::TPoint2D;

namespace {

/** The ten vertices of one branch rising from the ceiling at x0 (left wall) and height yc,
 *  in counter-clockwise order as the ceiling is walked right to left: up the right wall,
 *  three bends to the dead end on the right, back along the left wall. */
void appendBranch(std::vector<TPoint2D>& v, double x0, double yc, double w, double leg) {
    const double h1 = yc + leg, h2 = yc + 2 * leg;
    v.insert(v.end(), {{x0 + w, yc},
                       {x0 + w, h1},
                       {x0 + leg + w, h1},
                       {x0 + leg + w, h2},
                       {x0 + 2 * leg + w, h2},
                       {x0 + 2 * leg + w, h2 + w},
                       {x0 + leg, h2 + w},
                       {x0 + leg, h1 + w},
                       {x0, h1 + w},
                       {x0, yc}});
}

double snap8(double x) { return std::round(x * 8) / 8; }

}  // namespace

GeneratedMap stepsMap(const StepsMapOptions& o) {
    const double W = o.stepWidth, R = o.stepRise, C = o.corridorHeight, w = o.branchWidth;
    const double leg = o.branchLeg, branch = 2 * leg + w;
    const int b = o.branchesPerStep;
    if (o.steps < 1 || b < 1) throw Error("steps map: steps and branches per step must be >= 1");
    if (w <= 0 || leg < w || C <= 0 || R <= 0)
        throw Error(
            "steps map: need branch width > 0, branch leg >= width, corridor height and "
            "step rise > 0");
    const double gap = (W - b * branch) / (b + 1);
    if (gap <= 0)
        throw Error(mrpt::format("steps map: %d branches of width %g do not fit a step of %g m", b,
                                 branch, W));
    if (R >= C) throw Error("steps map: the step rise must be below the corridor height");

    std::vector<TPoint2D> v;
    std::vector<TPoint2D> sites;
    for (int i = 0; i < o.steps; ++i) v.insert(v.end(), {{i * W, i * R}, {(i + 1) * W, i * R}});
    for (int i = o.steps - 1; i >= 0; --i) {
        const double yc = i * R + C;
        v.push_back({(i + 1) * W, yc});
        for (int j = b - 1; j >= 0; --j) {
            const double x0 = i * W + gap + j * (branch + gap);
            appendBranch(v, x0, yc, w, leg);
        }
        v.push_back({i * W, yc});
    }
    // Entrance alcove on the left end wall: the two ends differ, as in the paper's figures.
    v.insert(v.end(), {{0, 2 * C / 3}, {-2 * w, 2 * C / 3}, {-2 * w, C / 3}, {0, C / 3}});
    for (int i = 0; i < o.steps; ++i)
        for (int j = 0; j < b; ++j) {
            const double x0 = i * W + gap + j * (branch + gap);
            sites.push_back({x0 + 2 * leg + w / 2, i * R + C + 2 * leg + w / 2});
        }
    const std::string what = mrpt::format("steps map (%d steps, %d branches each)", o.steps, b);
    return {common::Polygon::fromVertices(std::move(v), what), sites, what};
}

GeneratedMap roomsMap(const RoomsMapOptions& o, mrpt::random::CRandomGenerator& rng) {
    if (o.rooms < 1 || o.roomSteps < 1) throw Error("rooms map: rooms and room steps must be >= 1");
    const double Wr = o.roomWidth, wn = o.neckWidth, hn = o.neckLength, C = o.corridorHeight;
    if (Wr < wn + 1 || hn <= 0 || C <= 0 || o.roomHeightMin <= 0.5 ||
        o.roomHeightMax < o.roomHeightMin || o.roomGap <= 0 || o.rightMargin < 0)
        throw Error(
            "rooms map: need room width >= neck width + 1, room height min > 0.5 <= max, "
            "and positive neck, corridor and gap sizes");
    // The room: neck position, skyline breaks and heights (shared by every copy).
    const double nx = snap8(rng.drawUniform(0.5, Wr - wn - 0.5));
    std::vector<double> breaks{0};
    for (int i = 1; i < o.roomSteps; ++i) breaks.push_back(Wr * i / o.roomSteps);
    for (size_t i = 1; i < breaks.size(); ++i)
        breaks[i] = snap8(breaks[i] + rng.drawUniform(-0.3, 0.3) * Wr / o.roomSteps);
    breaks.push_back(Wr);
    std::vector<double> heights;
    for (int i = 0; i < o.roomSteps; ++i) {
        double h;
        do h = snap8(rng.drawUniform(o.roomHeightMin, o.roomHeightMax));
        while (!heights.empty() && std::abs(h - heights.back()) < 0.25);
        heights.push_back(h);
    }
    const double floorY = C + hn;  // the rooms' floor
    const TPoint2D site{snap8(rng.drawUniform(0.3, Wr - 0.3)) + 1.0 / 16,
                        floorY + snap8(rng.drawUniform(0.3, o.roomHeightMin - 0.3)) + 1.0 / 16};

    // Rays through a neck drift at most wn / hn sideways per metre down; keep the corridor
    // ends out of that cone.
    const double margin = snap8(C * wn / hn + wn + 1);
    const double pitch = Wr + o.roomGap;
    const double left = 0, right = 2 * margin + o.rooms * pitch - o.roomGap + o.rightMargin;
    std::vector<TPoint2D> v{{left, 0}, {right, 0}, {right, C}};
    std::vector<TPoint2D> sites;
    for (int r = o.rooms - 1; r >= 0; --r) {
        const double x0 = margin + r * pitch;
        v.insert(v.end(), {{x0 + nx + wn, C}, {x0 + nx + wn, floorY}, {x0 + Wr, floorY}});
        for (int i = o.roomSteps - 1; i >= 0; --i)
            v.insert(v.end(), {{x0 + breaks[i + 1], floorY + heights[i]},
                               {x0 + breaks[i], floorY + heights[i]}});
        v.insert(v.end(), {{x0, floorY}, {x0 + nx, floorY}, {x0 + nx, C}});
    }
    v.push_back({left, C});
    for (int r = 0; r < o.rooms; ++r) sites.push_back({margin + r * pitch + site.x, site.y});
    const std::string what = mrpt::format("rooms map (%d rooms)", o.rooms);
    return {common::Polygon::fromVertices(std::move(v), what), sites, what};
}

common::Polygon randomStarPolygon(int n, double rMin, double rMax,
                                  mrpt::random::CRandomGenerator& rng) {
    std::vector<double> angles;
    for (int i = 0; i < n; ++i) angles.push_back(rng.drawUniform(0.0, 2 * M_PI));
    std::sort(angles.begin(), angles.end());
    std::vector<TPoint2D> v;
    for (double a : angles) {
        const double r = rng.drawUniform(rMin, rMax);
        v.push_back({r * std::cos(a), r * std::sin(a)});
    }
    return common::Polygon::fromVertices(std::move(v), "random star polygon");
}

}  // namespace mrloc::polymap
