// Speed of the polygon-map path (seed 002, part 1): exact visibility polygons, the scan's
// polygon, and hypothesis generation, for the paper's n = 148 steps map (k = 12) and an
// n = 1000 map (6 rooms with 80-step ceilings along a corridor, k = 6).
// Run: build/tests/bench/bench_polymap --benchmark_repetitions=5
//      --benchmark_report_aggregates_only=true   (report the medians)
#include <benchmark/benchmark.h>
#include <mrloc/polymap/Hypotheses.h>
#include <mrloc/polymap/MapGenerators.h>
#include <mrloc/polymap/ScanPolygon.h>
#include <mrloc/sim/Scanner.h>

using namespace mrloc;
using common::TPoint2D;

namespace {

/** n = 148 (arg 148) or n = 1000 (arg 1000). */
polymap::GeneratedMap mapOfSize(int n) {
    if (n == 148) return polymap::stepsMap({});
    mrpt::random::CRandomGenerator rng(3);
    polymap::RoomsMapOptions o;
    o.rooms = 6;
    o.roomSteps = 80;  // 4 + 6 * (6 + 2 * 80) = 1000
    o.roomWidth = 40;
    return polymap::roomsMap(o, rng);
}

/** Random interior viewpoints (corridor and rooms alike). */
std::vector<TPoint2D> viewpoints(const common::Polygon& P, int count) {
    mrpt::random::CRandomGenerator rng(1);
    std::vector<TPoint2D> out;
    while ((int)out.size() < count) {
        const TPoint2D p{rng.drawUniform(P.min().x, P.max().x),
                         rng.drawUniform(P.min().y, P.max().y)};
        if (P.locate(p) == common::Polygon::Where::Inside) out.push_back(p);
    }
    return out;
}

void BM_VisibilityPolygon(benchmark::State& state) {
    const auto map = mapOfSize((int)state.range(0));
    const auto points = viewpoints(map.polygon, 64);
    size_t i = 0;
    for (auto _ : state)
        benchmark::DoNotOptimize(polymap::visibilityPolygon(map.polygon, points[i++ % 64]));
    state.counters["n"] = double(map.polygon.size());
}

/** From the exact V at the first site: all k hypotheses. */
void BM_Hypotheses_Exact(benchmark::State& state) {
    const auto map = mapOfSize((int)state.range(0));
    const auto V = polymap::visibilityPolygon(map.polygon, map.sites[0]);
    const polymap::HypothesisGenerator gen(map.polygon, {1e-6, 1e-6});
    size_t k = 0;
    for (auto _ : state) k = gen.generate(V).size();
    state.counters["n"] = double(map.polygon.size());
    state.counters["k"] = double(k);
}

/** From a 1440-beam scan with 5 mm noise at the first site (tolerance 0.1 m). */
void BM_Hypotheses_FromScan(benchmark::State& state) {
    const auto map = mapOfSize((int)state.range(0));
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
    const auto map = mapOfSize(148);
    mrpt::random::CRandomGenerator rng(2);
    const auto scan = sim::scanFloorPlan(map.polygon, {map.sites[0].x, map.sites[0].y, 0}, {}, rng);
    for (auto _ : state) benchmark::DoNotOptimize(polymap::visibilityFromScan(*scan, 0, {}));
}

}  // namespace

BENCHMARK(BM_VisibilityPolygon)->Arg(148)->Arg(1000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Hypotheses_Exact)->Arg(148)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Hypotheses_FromScan)->Arg(148)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ScanToPolygon)->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
