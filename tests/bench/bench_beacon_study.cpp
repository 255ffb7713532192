// Speed of the beacon study ([beacons_study], issue 30): one trial (the loudest beacons
// picked, every shot through the link, the fix with its delay refits) over several rooms,
// beacon counts and aimings, and one coverage evaluation of a room on one thread.
// Run: build/tests/bench/bench_beacon_study --benchmark_repetitions=5
//      --benchmark_report_aggregates_only=true   (report the medians)
#include <benchmark/benchmark.h>
#include <mrloc/beacons/BeaconStudy.h>
#include <mrloc/common/ParallelFor.h>

using namespace mrloc::beacons;

namespace {

StudyRoom roomOf(double side, int beacons, bool active) {
    return spreadRoom(side, side, 2.5, beacons, active);
}

StudyHardware hardware() {
    StudyHardware hw;
    hw.sensors.dropout = 0;
    hw.sensors.outlierProbability = 0;
    hw.sensors.rangeSigma = 0.01;
    return hw;
}

// args: room side (m), beacons, active (1) or fixed (0), shots per beacon
void BM_StudyTrial(benchmark::State& state) {
    const auto room = roomOf(double(state.range(0)), int(state.range(1)), state.range(2) != 0);
    const auto hw = hardware();
    const StudyMethod method{false, Residual::Range, true, int(state.range(3))};
    const auto points = testGrid(room.sizeX, room.sizeY, 0.5, 0.5);
    mrpt::random::CRandomGenerator rng(1);
    size_t i = 0;
    for (auto _ : state) {
        const auto t = runTrial(room, hw, method, points[i++ % points.size()], rng);
        benchmark::DoNotOptimize(t);
    }
    state.SetItemsProcessed(int64_t(state.iterations()));
}
BENCHMARK(BM_StudyTrial)
    ->Args({4, 3, 1, 1})
    ->Args({4, 3, 1, 4})
    ->Args({6, 4, 1, 4})
    ->Args({6, 12, 1, 4})
    ->Args({6, 12, 0, 4})
    ->Args({8, 24, 0, 4})
    ->Unit(benchmark::kMicrosecond);

// A whole room's coverage on one thread: 10 trials per test point, 0.5 m grid
void BM_CoverageOneThread(benchmark::State& state) {
    const auto room = roomOf(double(state.range(0)), int(state.range(1)), true);
    const auto hw = hardware();
    const StudyMethod method{false, Residual::Range, true, 4};
    const auto points = testGrid(room.sizeX, room.sizeY, 0.5, 0.5);
    mrloc::common::setThreadCount(1);
    for (auto _ : state) {
        const auto r = evaluateCoverage(room, hw, method, points, 10, 1, {}, false);
        benchmark::DoNotOptimize(r);
    }
    mrloc::common::setThreadCount(0);
    state.counters["trials"] = double(points.size() * 10);
}
BENCHMARK(BM_CoverageOneThread)
    ->Args({4, 3})
    ->Args({6, 4})
    ->Args({8, 8})
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
