// Speed of hypothesis elimination (seed 002 steps 4-10): one whole localization in closed
// loop with exact views, from every start of the steps map, per probe strategy; the paper's
// n = 148, k = 12 (its Table 2: 403 s for algorithm 1 down to about 8 s for algorithm 4) and
// n = 1012, k = 84 (and the sizes between, for Figs. 6-7); and on identical rooms with a pillar
// each (maps with holes).
// Run: build/tests/bench/bench_elimination --benchmark_repetitions=5
//      --benchmark_report_aggregates_only=true   (report the medians)
#include <benchmark/benchmark.h>
#include <mrloc/polymap/Elimination.h>
#include <mrloc/polymap/MapGenerators.h>
#include <mrloc/polymap/VerificationTour.h>

#include <cmath>

using namespace mrloc;

namespace {

/** Localizes from each start of `map` in turn, one per iteration, with the strategy of
 *  kind (0 cells, 1 randomized X = 100, 2 randomized X = 500, 3 triangulation, 4 windows:
 *  the paper's algorithms 1, 2, 2', 3, 4). */
void localizeEveryStart(benchmark::State& state, const polymap::GeneratedMap& map, int kind) {
    polymap::EliminationOptions o;
    const polymap::ProbeStrategy strategies[] = {
        polymap::ProbeStrategy::VisibilityCells, polymap::ProbeStrategy::Randomized,
        polymap::ProbeStrategy::Randomized, polymap::ProbeStrategy::Triangulation,
        polymap::ProbeStrategy::Windows};
    o.strategy = strategies[kind];
    o.randomPoints = kind == 2 ? 500 : 100;
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
    state.counters["holes"] = double(map.polygon.ringCount() - 1);
    state.counters["path m"] = travel / runs;
    const char* names[] = {"1 cells", "2 randomized X=100", "2' randomized X=500",
                           "3 triangulation (LUT)", "4 windows (LUW)"};
    state.SetLabel(names[kind]);
}

/** Arguments: n (a steps map: 24 s + 4 vertices), strategy as in localizeEveryStart. */
void BM_Elimination(benchmark::State& state) {
    polymap::StepsMapOptions s;
    s.steps = ((int)state.range(0) - 4) / 24;
    localizeEveryStart(state, polymap::stepsMap(s), (int)state.range(1));
}

/** The bound the report divides by: the verification tour from every start (k = 12) over the
 *  first step's candidates of every algorithm, searched exactly. One iteration: all starts. */
void BM_VerificationTours(benchmark::State& state) {
    polymap::StepsMapOptions s;
    s.steps = ((int)state.range(0) - 4) / 24;
    const auto map = polymap::stepsMap(s);
    std::vector<size_t> all(map.sites.size());
    for (size_t i = 0; i < all.size(); ++i) all[i] = i;
    std::vector<polymap::TPoint2D> sites;
    polymap::EliminationOptions o;
    for (const auto strategy :
         {polymap::ProbeStrategy::VisibilityCells, polymap::ProbeStrategy::Randomized,
          polymap::ProbeStrategy::Triangulation, polymap::ProbeStrategy::Windows}) {
        o.strategy = strategy;
        const auto c =
            polymap::Eliminator(map.polygon, map.sites, o).candidatesAndRegion(all).first;
        sites.insert(sites.end(), c.begin(), c.end());
    }
    const polymap::Eliminator eliminator(map.polygon, map.sites, {});
    double length = 0;
    for (auto _ : state) {
        length = 0;
        for (const auto& tour : polymap::verificationTours(eliminator, sites, {}))
            length += tour ? tour->length / double(map.sites.size()) : NAN;
    }
    state.counters["n"] = double(map.polygon.size());
    state.counters["k"] = double(map.sites.size());
    state.counters["sites"] = double(sites.size());
    state.counters["mean tour m"] = length;
}

}  // namespace

/** Arguments: rooms (identical rooms side by side, a 0.5 m pillar in each: a map and an OI
 *  with holes; map seed 7, 6 ceiling steps), strategy as in localizeEveryStart. */
void BM_EliminationRoomsWithPillars(benchmark::State& state) {
    mrpt::random::CRandomGenerator rng(7);
    polymap::RoomsMapOptions r;
    r.rooms = (int)state.range(0);
    r.roomSteps = 6;
    r.pillar = 0.5;
    localizeEveryStart(state, polymap::roomsMap(r, rng), (int)state.range(1));
}

BENCHMARK(BM_VerificationTours)->Arg(76)->Arg(148)->Unit(benchmark::kMillisecond);

BENCHMARK(BM_Elimination)
    ->ArgsProduct({{76, 148, 292, 508, 1012}, {0, 1, 2, 3, 4}})
    ->Unit(benchmark::kMillisecond);

BENCHMARK(BM_EliminationRoomsWithPillars)
    ->ArgsProduct({{3, 10}, {0, 1, 3, 4}})
    ->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
