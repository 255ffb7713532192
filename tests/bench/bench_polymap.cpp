// Speed of the polygon-map geometry (seed 002): the triangulation, visibility by triangular
// expansion, hypothesis generation, shortest paths and the overlay region, on the steps
// family (n = 24 s + 4: 148, 988, 1996, 4996 for s = 6, 41, 83, 208 steps, k = 2 s sites) and
// on star5000.poly (a random star of 5000 vertices), and on maps with holes: pillar halls of
// 100 pillars (10 x 10) of 10 and of 20 vertices each (n = 1004 and 2004, 100 holes).
// Run: build/tests/bench/bench_polymap --benchmark_repetitions=5
//      --benchmark_report_aggregates_only=true   (report the medians)
#include <benchmark/benchmark.h>
#include <mrloc/polymap/Hypotheses.h>
#include <mrloc/polymap/MapGenerators.h>
#include <mrloc/polymap/Overlay.h>
#include <mrloc/polymap/ScanPolygon.h>
#include <mrloc/polymap/ShortestPath.h>
#include <mrloc/sim/Scanner.h>

#include <map>

#include "TestPaths.h"

using namespace mrloc;
using common::Polygon;
using common::TPoint2D;

namespace {

/** The steps map with n vertices (n = 24 s + 4), star5000.poly for n = 5000, or a hall of
 *  10 x 10 pillars for n = 1004 (pillars of 10 vertices) and 2004 (of 20). */
const polymap::GeneratedMap& mapOfSize(int n) {
    static std::map<int, polymap::GeneratedMap> cache;
    if (const auto it = cache.find(n); it != cache.end()) return it->second;
    if (n == 1004 || n == 2004) {
        mrpt::random::CRandomGenerator rng(3);
        return cache.emplace(n, polymap::pillarHall(10, 10, (n - 4) / 100, 2.0, rng)).first->second;
    }
    if (n == 5000) {
        auto P =
            Polygon::load(std::string(MRLOC_SOURCE_DIR) + "/tests/data/bad-inputs/star5000.poly");
        return cache.emplace(n, polymap::GeneratedMap{std::move(P), {}, "star5000"}).first->second;
    }
    polymap::StepsMapOptions o;
    o.steps = (n - 4) / 24;
    return cache.emplace(n, polymap::stepsMap(o)).first->second;
}

/** 256 viewpoints of one kind: 0 random interior points, 1 edge midpoints, 2 vertices. */
std::vector<TPoint2D> viewpoints(const Polygon& P, int kind) {
    mrpt::random::CRandomGenerator rng(1);
    std::vector<TPoint2D> out;
    while (out.size() < 256) {
        const size_t i = (size_t)rng.drawUniform32bit() % P.size();
        if (kind == 1) {
            out.push_back((P[i] + P[P.next(i)]) * 0.5);
        } else if (kind == 2) {
            out.push_back(P[i]);
        } else {
            const TPoint2D p{rng.drawUniform(P.min().x, P.max().x),
                             rng.drawUniform(P.min().y, P.max().y)};
            if (P.locate(p) == Polygon::Where::Inside) out.push_back(p);
        }
    }
    return out;
}

const char* kindName(int kind) { return kind == 0 ? "interior" : kind == 1 ? "edge" : "vertex"; }

void BM_PolygonBuild(benchmark::State& state) {
    const auto& P = mapOfSize((int)state.range(0)).polygon;
    for (auto _ : state) benchmark::DoNotOptimize(Polygon::fromVertices(P.vertices(), "bench"));
    state.counters["n"] = double(P.size());
}

void BM_Triangulation(benchmark::State& state) {
    const auto& P = mapOfSize((int)state.range(0)).polygon;
    for (auto _ : state) benchmark::DoNotOptimize(polymap::Triangulation(P));
    state.counters["n"] = double(P.size());
}

/** One visibility polygon by triangular expansion (the triangulation built beforehand). */
void BM_Visibility(benchmark::State& state) {
    const auto& P = mapOfSize((int)state.range(0)).polygon;
    const polymap::Triangulation T(P);
    const auto points = viewpoints(P, (int)state.range(1));
    size_t i = 0, vertices = 0;
    for (auto _ : state) {
        const auto V = polymap::visibilityPolygon(T, points[i++ % points.size()]);
        vertices += V.size();
    }
    state.counters["n"] = double(P.size());
    state.counters["|V|"] = double(vertices) / double(state.iterations());
    state.SetLabel(kindName((int)state.range(1)));
}

/** All k hypotheses from the exact V at the first site (the generator, with its
 *  triangulation, built beforehand: once per map). */
void BM_Hypotheses_Exact(benchmark::State& state) {
    const auto& map = mapOfSize((int)state.range(0));
    const polymap::HypothesisGenerator gen(map.polygon, {1e-6, 1e-6});
    const auto V = polymap::visibilityPolygon(map.polygon, map.sites[0]);
    size_t k = 0;
    for (auto _ : state) k = gen.generate(V).size();
    state.counters["n"] = double(map.polygon.size());
    state.counters["k"] = double(k);
}

/** From a 1440-beam scan with 5 mm noise at the first site (tolerance 0.1 m). */
void BM_Hypotheses_FromScan(benchmark::State& state) {
    const auto& map = mapOfSize((int)state.range(0));
    mrpt::random::CRandomGenerator rng(2);
    const auto scan =
        sim::scanFloorPlan(map.polygon, {map.sites[0].x, map.sites[0].y, 0.4}, {}, rng);
    // The app's automatic tolerance: 6 sigma + a beam step times the farthest range + 1 cm.
    double rMax = 0;
    for (const auto& v : polymap::visibilityFromScan(*scan, 0.4, {}).vertices)
        rMax = std::max(rMax, v.norm());
    const polymap::HypothesisGenerator gen(
        map.polygon, {6 * 0.005 + 2 * M_PI / 1440 * rMax + 0.01, 3 * M_PI / 180});
    size_t k = 0;
    for (auto _ : state) k = gen.generate(polymap::visibilityFromScan(*scan, 0.4, {})).size();
    state.counters["n"] = double(map.polygon.size());
    state.counters["k"] = double(k);
}

void BM_ScanToPolygon(benchmark::State& state) {
    const auto& map = mapOfSize(148);
    mrpt::random::CRandomGenerator rng(2);
    const auto scan = sim::scanFloorPlan(map.polygon, {map.sites[0].x, map.sites[0].y, 0}, {}, rng);
    for (auto _ : state) benchmark::DoNotOptimize(polymap::visibilityFromScan(*scan, 0, {}));
}

/** Shortest path between random interior points. */
void BM_ShortestPath(benchmark::State& state) {
    const auto& P = mapOfSize((int)state.range(0)).polygon;
    const polymap::Triangulation T(P);
    const polymap::ShortestPaths paths(T);
    const auto points = viewpoints(P, 0);
    size_t i = 0;
    double length = 0;
    for (auto _ : state) {
        length += paths.distance(points[i % 256], points[(i * 7 + 3) % 256]);
        ++i;
    }
    state.counters["n"] = double(P.size());
    state.counters["mean m"] = length / double(state.iterations());
}

/** OI of the steps map's k = 2 s hypotheses. */
void BM_OverlayRegion(benchmark::State& state) {
    const auto& map = mapOfSize((int)state.range(0));
    for (auto _ : state) benchmark::DoNotOptimize(polymap::overlayRegion(map.polygon, map.sites));
    state.counters["n"] = double(map.polygon.size());
    state.counters["k"] = double(map.sites.size());
}

}  // namespace

BENCHMARK(BM_PolygonBuild)->Arg(148)->Arg(988)->Arg(4996)->Arg(5000)->Unit(benchmark::kMillisecond);
/** The same with holes: every ring validated, then the sweep over all rings' edges. */
void BM_PolygonBuildWithHoles(benchmark::State& state) {
    const auto& P = mapOfSize((int)state.range(0)).polygon;
    std::vector<std::vector<TPoint2D>> rings;
    for (size_t r = 0; r < P.ringCount(); ++r) rings.push_back(P.ringVertices(r));
    for (auto _ : state) benchmark::DoNotOptimize(Polygon::fromRings(rings, "bench"));
    state.counters["n"] = double(P.size());
    state.counters["holes"] = double(P.ringCount() - 1);
}
BENCHMARK(BM_PolygonBuildWithHoles)->Arg(1004)->Arg(2004)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Triangulation)
    ->Arg(148)
    ->Arg(1004)
    ->Arg(2004)
    ->Arg(988)
    ->Arg(4996)
    ->Arg(5000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Visibility)
    ->ArgsProduct({{148, 988, 4996, 5000, 1004, 2004}, {0, 1, 2}})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Hypotheses_Exact)
    ->Arg(148)
    ->Arg(1004)
    ->Arg(2004)
    ->Arg(988)
    ->Arg(1996)
    ->Arg(4996)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Hypotheses_FromScan)
    ->Arg(148)
    ->Arg(988)
    ->Arg(1004)
    ->Arg(2004)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ScanToPolygon)->Unit(benchmark::kMicrosecond);
// with holes the first query builds the reflex vertices' visibility graph (in the
// constructor: not timed) and each query runs Dijkstra from its start
BENCHMARK(BM_ShortestPath)
    ->Arg(148)
    ->Arg(988)
    ->Arg(4996)
    ->Arg(5000)
    ->Arg(1004)
    ->Arg(2004)
    ->Unit(benchmark::kMicrosecond);
/** Building the shortest-path structure: the dual tree, or with holes the visibility graph. */
void BM_ShortestPathsBuild(benchmark::State& state) {
    const auto& P = mapOfSize((int)state.range(0)).polygon;
    const polymap::Triangulation T(P);
    for (auto _ : state) benchmark::DoNotOptimize(polymap::ShortestPaths(T));
    state.counters["n"] = double(P.size());
}
BENCHMARK(BM_ShortestPathsBuild)->Arg(148)->Arg(1004)->Arg(2004)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OverlayRegion)->Arg(148)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
