// Triangle search and identification (seed 000): the seed-and-grow search against the
// paper's brute force (eq. (9), then identification by votes). N robots, all mutually
// visible, at the density of 30 robots in a 20 m square (the side grows with sqrt(N)),
// bearing noise 0.02 deg. Target: N = 30 under 50 ms.
#include <benchmark/benchmark.h>
#include <mrloc/omnivision/TriangleSearch.h>

#include "../omnivision/Swarm.h"

using namespace mrloc;

namespace {

testing_omni::Swarm swarm(long n) {
    return testing_omni::randomSwarm(size_t(n), unsigned(n), 0.02, 20 * std::sqrt(n / 30.0));
}

/** The tolerances [omnivision] derives from the bearing noise: 6 and 4 sigma. */
omnivision::SearchOptions options() {
    omnivision::SearchOptions o;
    o.sumTolerance = 6 * 0.02 * M_PI / 180;
    o.bearingTolerance = 4 * 0.02 * M_PI / 180;
    return o;
}

void BM_FastSearch(benchmark::State& state) {
    const auto sw = swarm(state.range(0));
    size_t triangles = 0, seeds = 0;
    for (auto _ : state) {
        const auto id = omnivision::identify(sw.snapshot, options());
        triangles = id.triangles.size();
        seeds = id.candidates;
        benchmark::DoNotOptimize(triangles);
    }
    state.counters["triangles"] = double(triangles);
    state.counters["seeds"] = double(seeds);
    state.counters["true_triangles"] =
        double(sw.poses.size() * (sw.poses.size() - 1) * (sw.poses.size() - 2) / 6);
}

void BM_BruteForce(benchmark::State& state) {
    const auto sw = swarm(state.range(0));
    size_t triangles = 0, candidates = 0;
    for (auto _ : state) {
        const auto id = omnivision::identifyBruteForce(sw.snapshot, options());
        triangles = id.triangles.size();
        candidates = id.candidates;
        benchmark::DoNotOptimize(triangles);
    }
    state.counters["triangles"] = double(triangles);
    state.counters["angle_triples_summing_to_180"] = double(candidates);
}

}  // namespace

BENCHMARK(BM_FastSearch)->Arg(5)->Arg(10)->Arg(20)->Arg(30)->Arg(40)->Unit(benchmark::kMillisecond);
// At N = 50 the hull seeds mostly fail to grow and the search spends its seed budget.
BENCHMARK(BM_FastSearch)->Arg(50)->Unit(benchmark::kMillisecond)->Iterations(1);
// O(N^9) triples, then votes over every pair of chance triangles: N = 15 takes minutes.
BENCHMARK(BM_BruteForce)->Arg(5)->Arg(10)->Unit(benchmark::kMillisecond)->Iterations(1);

BENCHMARK_MAIN();
