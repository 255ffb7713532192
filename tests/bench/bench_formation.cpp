// Speed of seed 003's Monte Carlo in the error-model mode: the target is 100 runs x
// 2 routes x 2 wheel speeds (formation and dead reckoning each) in under 2 s.
// Run: build/tests/bench/bench_formation --benchmark_repetitions=5
//      --benchmark_report_aggregates_only=true   (report the medians)
#include <benchmark/benchmark.h>
#include <mrloc/formation/March.h>
#include <mrloc/formation/Routes.h>

using namespace mrloc;

namespace {

/** One iteration: the whole Table 1 experiment, 400 formation marches and 400 dead-reckoned
 *  drives. */
void BM_TableOneMonteCarlo(benchmark::State& state) {
    const auto manyTurns = formation::route("many_turns"), patrol = formation::route("patrol");
    mrpt::random::CRandomGenerator rng(1);
    size_t moves = 0;
    for (auto _ : state)
        for (const auto* route : {&manyTurns, &patrol})
            for (const double w : {5.8, 2.9})
                for (int run = 0; run < 100; ++run) {
                    formation::MarchOptions o;
                    o.wheelSpeed = w;
                    moves += formation::march(4, *route, {}, o, {}, rng).moves.size();
                    benchmark::DoNotOptimize(
                        formation::deadReckon(*route, o.wheelRadius, w, {}, rng).back().error);
                }
    state.counters["runs/s"] =
        benchmark::Counter(800.0 * double(state.iterations()), benchmark::Counter::kIsRate);
    state.counters["moves per march"] = double(moves) / (400.0 * double(state.iterations()));
}

}  // namespace

BENCHMARK(BM_TableOneMonteCarlo)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
