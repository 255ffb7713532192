// Traced maps in the exact pipeline (issue 55): an MRPT occupancy grid's free space around a
// point becomes an outer ring and holes that common::Polygon::fromRings accepts. Pinch
// vertices (two free cells touching at a corner alone) become two on each pass, the corner cut
// a quarter cell;
// holes below speck size are dropped; MRPT's own building maps trace into valid polygons.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/Polygon.h>
#include <mrloc/polymap/GridTrace.h>
#include <mrloc/polymap/Triangulation.h>
#include <mrloc/polymap/Visibility.h>

#include <filesystem>
#include <iostream>

using namespace mrloc;
using common::TPoint2D;

namespace {

/** A grid of `cols` x `rows` cells of 0.1 m, at the origin, occupied but for the cells
 *  `isFree(x, y)` says. */
template <class Free>
mrpt::maps::COccupancyGridMap2D gridOf(int cols, int rows, Free isFree) {
    mrpt::maps::COccupancyGridMap2D grid(0, cols * 0.1f, 0, rows * 0.1f, 0.1f);
    for (int y = 0; y < rows; ++y)
        for (int x = 0; x < cols; ++x) grid.setCell(x, y, isFree(x, y) ? 0.95f : 0.05f);
    return grid;
}

double areaOf(const std::vector<std::vector<TPoint2D>>& rings) {
    return common::Polygon::fromRings(rings, "traced").area();
}

}  // namespace

TEST(FreeSpaceTrace, ARoomWithAPillarAndASpeckIsAnOuterRingAndOneHole) {
    // free 1..8 x 1..8 (64 cells), a 3 x 3 pillar at 3..5, one occupied speck at (7, 2)
    const auto grid = gridOf(10, 10, [](int x, int y) {
        const bool room = x >= 1 && x <= 8 && y >= 1 && y <= 8;
        const bool pillar = x >= 3 && x <= 5 && y >= 3 && y <= 5;
        return room && !pillar && !(x == 7 && y == 2);
    });
    const auto rings = polymap::traceFreeSpace(grid, {}, {0.15, 0.15}, "room");
    ASSERT_EQ(rings.size(), 2u);  // the speck (1 cell, below 4) dropped
    EXPECT_EQ(rings[0].size(), 4u);
    EXPECT_EQ(rings[1].size(), 4u);
    // 64 - 9 cells: the speck's cell counts as free once dropped (the grid's float
    // resolution: 1e-6 m)
    EXPECT_NEAR(areaOf(rings), (64 - 9) * 0.01, 1e-6);
    for (const auto& ring : rings)
        for (const auto& p : ring) {  // along the cells' edges, not through their centres
            EXPECT_NEAR(p.x * 10, std::round(p.x * 10), 1e-5) << p.x;
            EXPECT_NEAR(p.y * 10, std::round(p.y * 10), 1e-5) << p.y;
        }
}

TEST(FreeSpaceTrace, APinchVertexBecomesTwoAndTheRingsValidate) {
    // Two 4 x 4 blocks touching at one corner (5, 5), joined round the side by a column; the
    // cell at (4, 5) occupied: the free space's boundary meets itself at (0.5 0.5) m.
    const auto grid = gridOf(10, 10, [](int x, int y) {
        const bool a = x >= 1 && x <= 4 && y >= 1 && y <= 4,
                   b = x >= 5 && x <= 8 && y >= 5 && y <= 8;
        const bool column = x >= 1 && x <= 3 && y >= 5 && y <= 8;
        return a || b || column || (x == 4 && y >= 6 && y <= 8);
    });
    polymap::GridTraceOptions exact;
    exact.simplify = 1e-9;  // below a 64th of a cell: as traced
    const auto rings = polymap::traceFreeSpace(grid, exact, {0.25, 0.25}, "pinch");
    ASSERT_EQ(rings.size(), 1u) << "the one-cell notch joins the outside through the pinch";
    int near = 0;
    for (const auto& p : rings[0]) {
        const double d = (p - TPoint2D{0.5, 0.5}).norm();
        EXPECT_GT(d, 0.01);
        if (d < 0.05) {
            ++near;  // each block's corner cut a quarter cell from the pinch
            EXPECT_NEAR(d, 0.025, 1e-6);
        }
    }
    EXPECT_EQ(near, 4);
    // 16 + 16 + 12 + 3 cells, less the two corners cut (a 32nd of a cell each)
    EXPECT_NEAR(areaOf(rings), 47 * 0.01 - 2 * 0.01 / 32, 1e-6);
    // simplified (half a cell, the default): still valid, the area within a few cells
    const auto simple = polymap::traceFreeSpace(grid, {}, {0.25, 0.25}, "pinch");
    EXPECT_LT(simple[0].size(), rings[0].size());
    EXPECT_NEAR(areaOf(simple), 0.47, 0.04);
    // and the exact pipeline takes it
    const auto P = common::Polygon::fromRings(rings, "pinch");
    const polymap::Triangulation T(P);
    EXPECT_GT(polymap::visibilityPolygon(T, {0.25, 0.25}).size(), 3u);
}

TEST(FreeSpaceTrace, AStartOffTheFreeSpaceIsRefused) {
    const auto grid = gridOf(4, 4, [](int x, int y) { return x == 1 && y == 1; });
    try {
        polymap::traceFreeSpace(grid, {}, {0.35, 0.35}, "map m");
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("map m: (0.35 0.35) is not on a free cell"),
                  std::string::npos)
            << e.what();
    }
}

TEST(FreeSpaceTrace, MrptsBuildingMapsTraceIntoValidPolygonsWithHoles) {
    // MRPT's example maps (mrpt-common): the free space around a robot's start, traced as the
    // exact pipeline takes it (before: "edge 5-6 meets edge 7-8" on every traced map)
    struct Case {
        std::string file;
        TPoint2D start;
        double resolution;
    };
    for (const auto& c : {Case{"localization_demo.simplemap.gz", {0, 0}, 0.06},
                          Case{"malaga-cs-fac-building.simplemap.gz", {0, 0}, 0.05}}) {
        const std::string path = "/usr/share/mrpt/datasets/" + c.file;
        ASSERT_TRUE(std::filesystem::exists(path)) << "mrpt-common: scripts/install-deps.sh";
        polymap::GridTraceOptions o;
        o.resolution = c.resolution;
        const auto grid = polymap::loadGridMap(path, o);
        const auto rings = polymap::traceFreeSpace(grid, o, c.start, c.file);
        size_t vertices = 0;
        for (const auto& r : rings) vertices += r.size();
        const auto P = common::Polygon::fromRings(rings, c.file, 400000);
        std::cout << c.file << ": " << rings.size() << " rings, " << vertices << " vertices, "
                  << P.area() << " m^2\n";
        EXPECT_GT(rings.size(), 1u);
        const polymap::Triangulation T(P);
        EXPECT_GT(polymap::visibilityPolygon(T, c.start).size(), 3u);
    }
}

// A mapping run's laser fan leaves rays of free cells into unknown space: `open` closes free
// space narrower than it (an opening by a square of the fewest odd cells at least that wide)
// before tracing. A 10 x 10-cell room with a ray one cell wide and 8 long, and a passage two
// cells wide to a second room: open = 0.3 m (3 cells) drops the ray and the passage with the
// room behind it (a robot does not pass), and keeps the room whole (its area exactly); a start
// in the ray is one line naming the width. Measured on MRPT's maps with the exact pipeline's
// 0.3 m: malaga-cs-fac-building from 531 rings and 17,299 vertices to 71 and 1,891.
TEST(FreeSpaceTrace, AnOpeningClosesLaserFanRaysAndPassagesTooNarrowForARobot) {
    const auto grid = gridOf(40, 14, [](int x, int y) {
        const bool room = x >= 1 && x <= 10 && y >= 2 && y <= 11;
        const bool ray = x >= 11 && x <= 18 && y == 6;                   // 1 cell wide
        const bool passage = x >= 11 && x <= 24 && (y == 9 || y == 10);  // 2 cells wide
        const bool second = x >= 25 && x <= 34 && y >= 2 && y <= 11;
        return room || ray || passage || second;
    });
    polymap::GridTraceOptions o;
    const double all = areaOf(polymap::traceFreeSpace(grid, o, {0.55, 0.55}, "room"));
    EXPECT_NEAR(all, (100 + 8 + 28 + 100) * 0.01, 1e-6);
    o.open = 0.3;
    const auto rings = polymap::traceFreeSpace(grid, o, {0.55, 0.55}, "room");
    ASSERT_EQ(rings.size(), 1u);
    EXPECT_EQ(rings[0].size(), 4u);
    EXPECT_NEAR(areaOf(rings), 100 * 0.01, 1e-6);
    try {
        polymap::traceFreeSpace(grid, o, {1.45, 0.65}, "room");
        ADD_FAILURE() << "a start in a ray narrower than open";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("(1.45 0.65) is in free space narrower than 0.3 m "
                                             "(trace_open)"),
                  std::string::npos)
            << e.what();
    }
}
