// Speed of hypothesis elimination (seed 002 steps 4-10): one whole localization in closed
// loop with exact views, from every start of the steps map, per probe strategy; the paper's
// n = 148, k = 12 (its Table 2: 403 s for algorithm 1 down to about 8 s for algorithm 4) and
// n = 988, k = 82.
// Run: build/tests/bench/bench_elimination --benchmark_repetitions=5
//      --benchmark_report_aggregates_only=true   (report the medians)
#include <benchmark/benchmark.h>
#include <mrloc/polymap/Elimination.h>
#include <mrloc/polymap/MapGenerators.h>

using namespace mrloc;

namespace {

/** Arguments: n (148 or 988), strategy (0 randomized X = 100, 1 randomized X = 500,
 *  2 triangulation, 3 windows). One iteration localizes from every start in turn. */
void BM_Elimination(benchmark::State& state) {
    polymap::StepsMapOptions s;
    s.steps = ((int)state.range(0) - 4) / 24;
    const auto map = polymap::stepsMap(s);
    polymap::EliminationOptions o;
    const int kind = (int)state.range(1);
    o.strategy = kind <= 1 ? polymap::ProbeStrategy::Randomized
                           : kind == 2 ? polymap::ProbeStrategy::Triangulation
                                       : polymap::ProbeStrategy::Windows;
    o.randomPoints = kind == 1 ? 500 : 100;
    const polymap::Eliminator eliminator(map.polygon, map.sites, o);
    size_t truth = 0;
    double travel = 0;
    int runs = 0;
    for (auto _ : state) {
        const auto run = polymap::eliminateExactly(eliminator, truth);
        if (run.survivors.size() != 1) state.SkipWithError("did not end with one hypothesis");
        travel += run.travel;
        ++runs;
        truth = (truth + 1) % map.sites.size();
    }
    state.counters["n"] = double(map.polygon.size());
    state.counters["k"] = double(map.sites.size());
    state.counters["path m"] = travel / runs;
    state.SetLabel(kind == 0 ? "randomized X=100" : kind == 1 ? "randomized X=500"
                   : kind == 2 ? "triangulation (LUT)" : "windows (LUW)");
}

}  // namespace

BENCHMARK(BM_Elimination)->ArgsProduct({{148, 988}, {0, 1, 2, 3}})->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
