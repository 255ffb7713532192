// Fuzzes the .poly reader, the polygon validation behind it, and the geometry built on a map
// that loads: any input must give a valid polygon (holes allowed) or mrloc::Error. A polygon
// that loads must have positive area, triangulate into n + 2h - 2 triangles inside it (h
// holes), and give a
// visibility polygon from a vertex, an edge midpoint and a triangle's centroid, and a
// shortest path between two vertices, without an error: the target aborts otherwise. The same
// input read as rings (polymap's scan localizer: an outer ring and holes) must load or give
// mrloc::Error, and rings that load must give a wall map whose casts end within the range.
// fuzz-seeds: maps/*.poly tests/data/bad-inputs/*.poly
// fuzz-max-len: 65536
#include <mrloc/common/Error.h>
#include <mrloc/common/Polygon.h>
#include <mrloc/polymap/ShortestPath.h>
#include <mrloc/polymap/Visibility.h>
#include <mrloc/polymap/WallMap.h>

#include <cstdio>
#include <cstdlib>
#include <optional>

#include "FuzzInput.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string& path = mrloc::fuzz::writeInput(data, size, ".poly");
    try {
        const auto walls =
            mrloc::polymap::wallMapOfRings(mrloc::polymap::loadPolyRings(path), 0.05, 0.1, "fuzz");
        const auto& v = walls.rings.front();
        for (int k = 0; k < 16; ++k) {
            const double r = walls.caster.cast(v[0] * 0.5 + v[v.size() / 2] * 0.5, k * 0.4, 1e7);
            if (!(r >= 0 && r <= 1e7)) std::abort();
        }
    } catch (const mrloc::Error&) {
    }
    std::optional<mrloc::common::Polygon> P;
    try {
        P = mrloc::common::Polygon::load(path);
    } catch (const mrloc::Error&) {
        return 0;
    }
    if (!(P->area() > 0)) std::abort();  // validation let a degenerate polygon through
    try {
        using namespace mrloc::polymap;
        const Triangulation T(*P);
        if (T.insideCount() + 2 != P->size() + 2 * (P->ringCount() - 1)) std::abort();  // Euler
        int inside = 0;
        while (!T[inside].inside) ++inside;
        const auto& tri = T[inside];
        const auto centroid =
            (T.point(tri.v[0]) + T.point(tri.v[1]) + T.point(tri.v[2])) * (1.0 / 3);
        const size_t n = P->size();
        for (const auto& q : {(*P)[0], ((*P)[n / 2] + (*P)[P->next(n / 2)]) * 0.5, centroid})
            if (visibilityPolygon(T, q).size() < 3) std::abort();
        const ShortestPaths paths(T);
        if (!(paths.distance((*P)[0], (*P)[n / 2]) >= ((*P)[0] - (*P)[n / 2]).norm() * (1 - 1e-12)))
            std::abort();  // a path shorter than the straight line
    } catch (const mrloc::Error& e) {
        std::fprintf(stderr, "geometry failed on a valid map: %s\n", e.what());
        std::abort();
    }
    return 0;
}
