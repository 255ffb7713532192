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
    // A rise of at least the corridor's height leaves no opening between the steps: a shaft
    // joins each step's right end to the next step's left end instead, narrow enough that no
    // sight line passes two of them (a step looks like the next from inside).
    const double shaft = R >= C ? o.shaftWidth : 0;
    if (R >= C && !(shaft > 0 && shaft < W))
        throw Error(
            mrpt::format("steps map: a rise of %g m, at least the corridor height %g m, "
                         "needs a shaft width between 0 and the step width %g m (%g)",
                         R, C, W, o.shaftWidth));

    std::vector<TPoint2D> v;
    std::vector<TPoint2D> sites;
    for (int i = 0; i < o.steps; ++i)  // the floor; a shaft's right wall between two steps
        v.insert(v.end(), {{i * W + (i > 0 ? shaft : 0), i * R},
                           {(i + 1) * W + (i + 1 < o.steps ? shaft : 0), i * R}});
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

std::string roomsLayoutName(RoomsLayout layout) {
    switch (layout) {
        case RoomsLayout::Side:
            return "side";
        case RoomsLayout::Row:
            return "row";
        case RoomsLayout::Mirrored:
            return "mirrored";
    }
    return "?";
}

RoomsLayout roomsLayoutFromName(const std::string& name) {
    for (const auto l : kRoomsLayouts)
        if (roomsLayoutName(l) == name) return l;
    throw Error("rooms layout '" + name + "': expected side, row or mirrored");
}

namespace {

/** The room's shape, shared by every copy: neck position, skyline and the site. */
struct Room {
    double neckX = 0;                     ///< the neck's left wall, from the room's left
    std::vector<double> breaks, heights;  ///< skyline: heights[i] over breaks[i]..breaks[i+1]
    TPoint2D site;                        ///< from the room's floor at its left wall
};

Room randomRoom(const RoomsMapOptions& o, mrpt::random::CRandomGenerator& rng) {
    const double Wr = o.roomWidth;
    Room room;
    room.neckX = snap8(rng.drawUniform(0.5, Wr - o.neckWidth - 0.5));
    room.breaks = {0};
    for (int i = 1; i < o.roomSteps; ++i) room.breaks.push_back(Wr * i / o.roomSteps);
    for (size_t i = 1; i < room.breaks.size(); ++i)
        room.breaks[i] = snap8(room.breaks[i] + rng.drawUniform(-0.3, 0.3) * Wr / o.roomSteps);
    room.breaks.push_back(Wr);
    for (int i = 0; i < o.roomSteps; ++i) {
        double h;
        do h = snap8(rng.drawUniform(o.roomHeightMin, o.roomHeightMax));
        while (!room.heights.empty() && std::abs(h - room.heights.back()) < 0.25);
        room.heights.push_back(h);
    }
    room.site = {snap8(rng.drawUniform(0.3, Wr - 0.3)) + 1.0 / 16,
                 snap8(rng.drawUniform(0.3, o.roomHeightMin - 0.3)) + 1.0 / 16};
    return room;
}

/** The skyline of a room whose left wall is at x0 and floor at y0, counter-clockwise (right
 *  to left), from the top of its right wall to the top of its left wall. */
void appendSkyline(std::vector<TPoint2D>& v, const Room& room, double x0, double y0) {
    for (size_t i = room.heights.size(); i-- > 0;)
        v.insert(v.end(), {{x0 + room.breaks[i + 1], y0 + room.heights[i]},
                           {x0 + room.breaks[i], y0 + room.heights[i]}});
}

/** The pillar of a room whose left wall is at x0 and floor at y0 (empty if none): a square,
 *  clockwise (a hole), the same spot in every copy. */
std::vector<TPoint2D> pillarOf(const RoomsMapOptions& o, const Room& room, double x0, double y0) {
    if (o.pillar <= 0) return {};
    const double cx =
        x0 + snap8(room.site.x < o.roomWidth / 2 ? 0.75 * o.roomWidth : 0.25 * o.roomWidth);
    const double cy = y0 + snap8(o.roomHeightMin / 2), h = o.pillar / 2;
    return {{cx - h, cy - h}, {cx - h, cy + h}, {cx + h, cy + h}, {cx + h, cy - h}};
}

/** The map's polygon: the outer ring and the rooms' pillars, if any. */
common::Polygon withPillars(std::vector<TPoint2D> outer, std::vector<std::vector<TPoint2D>> pillars,
                            const std::string& what) {
    std::vector<std::vector<TPoint2D>> rings{std::move(outer)};
    for (auto& p : pillars)
        if (!p.empty()) rings.push_back(std::move(p));
    return common::Polygon::fromRings(std::move(rings), what);
}

/** Rooms in a row: room r spans [r * pitch, r * pitch + Wr] from floor y = 0; between room r
 *  and r + 1 (and beyond both ends, as dead ends) a Z passage: a leg of length hn low on r's
 *  right wall, a jog up by twice its width, a leg into r + 1 high on its left wall. A sight
 *  line through one leg climbs at most w * w / hn across the jog, less than the w it would
 *  need, so no room sees through. */
GeneratedMap roomsInARow(const RoomsMapOptions& o, const Room& room) {
    const double Wr = o.roomWidth, hn = o.neckLength;
    const double w = snap8(std::min(o.neckWidth, (o.roomHeightMin - 0.5) / 3));
    const double d = 0.25;  // the low leg's floor above the room's floor
    if (w < 0.125 || hn <= w)
        throw Error(
            "rooms map (row): the passages need room_height_min >= 0.875 and neck_length > "
            "their width");
    const double pitch = Wr + 2 * hn + w;
    const int k = o.rooms;
    const auto X = [&](int r) { return r * pitch; };
    std::vector<TPoint2D> v;
    // The floor side, left to right: passage r's lower walls, then room r + 1's floor.
    for (int r = -1; r < k; ++r) {
        const double a = X(r) + Wr, b = X(r + 1);
        v.insert(v.end(), {{a, d}, {a + hn + w, d}, {a + hn + w, d + 2 * w}, {b, d + 2 * w}});
        if (r + 1 < k) v.insert(v.end(), {{b, 0}, {b + Wr, 0}});
    }
    // The ceiling side, right to left: passage r's upper walls, then room r's skyline.
    for (int r = k - 1; r >= -1; --r) {
        const double a = X(r) + Wr, b = X(r + 1);
        v.insert(v.end(), {{b, d + 3 * w}, {a + hn, d + 3 * w}, {a + hn, d + w}, {a, d + w}});
        if (r >= 0) appendSkyline(v, room, X(r), 0);
    }
    std::vector<TPoint2D> sites;
    std::vector<std::vector<TPoint2D>> pillars;
    for (int r = 0; r < k; ++r) {
        sites.push_back({X(r) + room.site.x, room.site.y});
        pillars.push_back(pillarOf(o, room, X(r), 0));
    }
    const std::string what = mrpt::format("rooms map (%d rooms in a row)", k);
    return {withPillars(std::move(v), std::move(pillars), what), sites, what};
}

}  // namespace

GeneratedMap roomsMap(const RoomsMapOptions& o, mrpt::random::CRandomGenerator& rng) {
    if (o.rooms < 1 || o.roomSteps < 1) throw Error("rooms map: rooms and room steps must be >= 1");
    const double Wr = o.roomWidth, wn = o.neckWidth, hn = o.neckLength, C = o.corridorHeight;
    if (Wr < wn + 1 || hn <= 0 || C <= 0 || o.roomHeightMin <= 0.5 ||
        o.roomHeightMax < o.roomHeightMin || o.roomGap <= 0 || o.rightMargin < 0)
        throw Error(
            "rooms map: need room width >= neck width + 1, room height min > 0.5 <= max, "
            "and positive neck, corridor and gap sizes");
    if (o.pillar < 0 || o.pillar > std::min(o.roomHeightMin - 0.25, o.roomWidth / 4))
        throw Error(
            mrpt::format("rooms map: pillar %g m: at most room_height_min - 0.25 and a "
                         "quarter of room_width (%g m)",
                         o.pillar, std::min(o.roomHeightMin - 0.25, o.roomWidth / 4)));
    const Room room = randomRoom(o, rng);
    if (o.layout == RoomsLayout::Row) return roomsInARow(o, room);
    const double floorY = C + hn;  // the rooms' floor
    const double nx = room.neckX;

    // Rays through a neck drift at most wn / hn sideways per metre down; keep the corridor
    // ends out of that cone.
    const double margin = snap8(C * wn / hn + wn + 1);
    const double pitch = Wr + o.roomGap;
    const double left = 0, right = 2 * margin + o.rooms * pitch - o.roomGap + o.rightMargin;
    // Room r above the corridor, counter-clockwise (right to left).
    const auto upper = [&](int r) {
        const double x0 = margin + r * pitch;
        std::vector<TPoint2D> u{{x0 + nx + wn, C}, {x0 + nx + wn, floorY}, {x0 + Wr, floorY}};
        appendSkyline(u, room, x0, floorY);
        u.insert(u.end(), {{x0, floorY}, {x0 + nx, floorY}, {x0 + nx, C}});
        return u;
    };
    std::vector<TPoint2D> v{{left, 0}};
    if (o.layout == RoomsLayout::Mirrored)
        for (int r = 0; r < o.rooms; ++r) {  // the mirror image in y = C / 2, left to right
            const auto u = upper(r);
            for (auto p = u.rbegin(); p != u.rend(); ++p) v.push_back({p->x, C - p->y});
        }
    v.insert(v.end(), {{right, 0}, {right, C}});
    for (int r = o.rooms - 1; r >= 0; --r) {
        const auto u = upper(r);
        v.insert(v.end(), u.begin(), u.end());
    }
    v.push_back({left, C});
    std::vector<TPoint2D> sites;
    std::vector<std::vector<TPoint2D>> pillars;
    for (int r = 0; r < o.rooms; ++r) {
        sites.push_back({margin + r * pitch + room.site.x, floorY + room.site.y});
        pillars.push_back(pillarOf(o, room, margin + r * pitch, floorY));
        if (o.layout == RoomsLayout::Mirrored && !pillars.back().empty()) {
            auto mirrored = pillars.back();  // in y = C / 2; reversed to stay clockwise
            for (auto& p : mirrored) p.y = C - p.y;
            pillars.push_back({mirrored.rbegin(), mirrored.rend()});
        }
    }
    const std::string what =
        o.layout == RoomsLayout::Mirrored
            ? mrpt::format("rooms map (%d rooms and their mirror images)", o.rooms)
            : mrpt::format("rooms map (%d rooms)", o.rooms);
    return {withPillars(std::move(v), std::move(pillars), what), sites, what};
}

GeneratedMap pillarHall(int columns, int rows, int pillarVertices, double spacing,
                        mrpt::random::CRandomGenerator& rng) {
    if (columns < 1 || rows < 1 || pillarVertices < 3 || !(spacing > 0))
        throw Error("pillar hall: columns, rows >= 1, pillar vertices >= 3, spacing > 0");
    const double W = (columns + 1) * spacing, H = (rows + 1) * spacing;
    std::vector<std::vector<TPoint2D>> rings{{{0, 0}, {W, 0}, {W, H}, {0, H}}};
    for (int i = 1; i <= columns; ++i)
        for (int j = 1; j <= rows; ++j) {
            const TPoint2D c{i * spacing + rng.drawUniform(-0.1, 0.1) * spacing,
                             j * spacing + rng.drawUniform(-0.1, 0.1) * spacing};
            // a star about c: angles evenly spread, jittered by under half their step, so no
            // two edges cross
            std::vector<TPoint2D> ring;
            const double step = 2 * M_PI / pillarVertices, phase = rng.drawUniform(0.0, step);
            for (int k = 0; k < pillarVertices; ++k) {
                const double a = phase + step * (k + rng.drawUniform(-0.3, 0.3));
                const double r = rng.drawUniform(0.2, 0.45) * spacing;
                ring.push_back({c.x + r * std::cos(a), c.y + r * std::sin(a)});
            }
            rings.push_back(std::move(ring));
        }
    const std::string what =
        mrpt::format("pillar hall (%d x %d pillars of %d vertices)", columns, rows, pillarVertices);
    return {
        common::Polygon::fromRings(std::move(rings), what), {{0.1 * spacing, 0.1 * spacing}}, what};
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
