// Speed of the beacon path: multilateration fixes per second (4 and 8 beacons, both
// residuals, 2-D and 3-D), rawlog playback observations per second, and the tracker's
// epochs per second with and without its bias states.
// Run: build/tests/bench/bench_multilateration --benchmark_repetitions=5
//      --benchmark_report_aggregates_only=true   (report the medians)
#include <benchmark/benchmark.h>
#include <mrloc/beacons/BeaconTracker.h>
#include <mrloc/beacons/Multilateration.h>
#include <mrloc/common/Rawlog.h>
#include <mrpt/obs/CObservationBeaconRanges.h>
#include <mrpt/random/RandomGenerators.h>

#include <cmath>
#include <filesystem>

#include "BeaconRangesAt.h"

using namespace mrloc;
using Eigen::Vector3d;

namespace {

// Non-coplanar beacons around a 6 x 6 m room, 1 cm range noise, 256 prepared problems.
std::vector<std::vector<beacons::RangeMeasurement>> problems(int nBeacons) {
    const std::vector<Vector3d> all = {{0, 0, 2.5}, {6, 0, 1.5}, {6, 6, 2.5}, {0, 6, 1.2},
                                       {3, 0, 2.2}, {6, 3, 2.0}, {3, 6, 1.8}, {0, 3, 2.4}};
    mrpt::random::CRandomGenerator rng(1);
    std::vector<std::vector<beacons::RangeMeasurement>> out;
    for (int k = 0; k < 256; ++k) {
        const Vector3d x(rng.drawUniform(0.5, 5.5), rng.drawUniform(0.5, 5.5), 0.5);
        std::vector<beacons::RangeMeasurement> m;
        for (int i = 0; i < nBeacons; ++i)
            m.push_back({all[i], (x - all[i]).norm() + rng.drawGaussian1D(0, 0.01), i});
        out.push_back(m);
    }
    return out;
}

void fixes(benchmark::State& state, beacons::Residual residual, bool twoD) {
    const auto p = problems(int(state.range(0)));
    beacons::MultilaterationOptions o;
    o.residual = residual;
    if (twoD) o.knownHeight = 0.5;
    size_t i = 0, failed = 0, iterations = 0;
    for (auto _ : state) {
        const auto f = beacons::multilaterate(p[i++ & 255], o);
        failed += !f.ok();
        iterations += size_t(f.iterations);
        benchmark::DoNotOptimize(f.position);
    }
    if (failed) state.SkipWithError("a fix failed");
    state.SetItemsProcessed(int64_t(state.iterations()));
    state.counters["gn_iterations"] = double(iterations) / double(state.iterations());
    state.counters["fixes_per_s"] =
        benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_Fix3D_Range(benchmark::State& s) { fixes(s, beacons::Residual::Range, false); }
void BM_Fix3D_SquaredRange_Seed001(benchmark::State& s) {
    fixes(s, beacons::Residual::SquaredRange, false);
}
void BM_Fix2D_Range(benchmark::State& s) { fixes(s, beacons::Residual::Range, true); }
BENCHMARK(BM_Fix3D_Range)->Arg(4)->Arg(8);
BENCHMARK(BM_Fix3D_SquaredRange_Seed001)->Arg(4)->Arg(8);
BENCHMARK(BM_Fix2D_Range)->Arg(4)->Arg(8);

// One observation of n ranges with one late echo (a hostile log's size, issue 26): the
// robust fix refits only the most suspect 12 beyond 12 ranges, so time grows as n log n.
void BM_RobustFix2D_OneEcho(benchmark::State& state) {
    const int n = int(state.range(0));
    const Vector3d x(4.3, 7.1, 0.5);
    mrpt::random::CRandomGenerator rng(1);
    std::vector<beacons::RangeMeasurement> m;
    for (int i = 0; i < n; ++i) {  // a ceiling of 10 x 12 m
        const Vector3d b(rng.drawUniform(0, 10), rng.drawUniform(0, 12), 2.5 + 0.1 * (i % 3));
        m.push_back({b, (x - b).norm(), i});
    }
    m[size_t(n) / 2].range += 0.8;
    beacons::MultilaterationOptions o;
    o.knownHeight = 0.5;
    int rejected = -1;
    for (auto _ : state) {
        const auto f = beacons::robustMultilaterate(m, o, 0.001, &rejected);
        benchmark::DoNotOptimize(f.position);
    }
    if (rejected != n / 2) state.SkipWithError("the echo was not rejected");
    state.SetComplexityN(n);
}
BENCHMARK(BM_RobustFix2D_OneEcho)->RangeMultiplier(4)->Range(8, 8192)->Complexity();

// Playback: read a 200,000-observation rawlog (beacon ranges, 4 beacons each), as every
// command does (checked first: the gzip stream, then every entry in an isolated child), and,
// for comparison, unchecked. Wall-clock time: the check runs in another process.
void playback(benchmark::State& state, bool checked) {
    const std::string path =
        (std::filesystem::temp_directory_path() / "mrloc_bench_playback.rawlog").string();
    const size_t n = 200000;
    {
        common::RawlogWriter w(path);
        auto obs = mrpt::obs::CObservationBeaconRanges::Create();
        obs->sensorLabel = "r1.beacons";
        for (int b = 0; b < 4; ++b) {
            mrpt::obs::CObservationBeaconRanges::TMeasurement m;
            m.beaconID = b;
            m.sensedDistance = 2.0f + float(b);
            obs->sensedData.push_back(m);
        }
        for (size_t i = 0; i < n; ++i) {
            obs->timestamp = mrpt::Clock::fromDouble(1e9 + 0.01 * double(i));
            w.write(*obs);
        }
        w.commit();
    }
    for (auto _ : state) {
        auto r = checked ? common::RawlogReader(path)
                         : common::RawlogReader(path, common::RawlogReader::kUnchecked);
        size_t count = 0;
        for (mrpt::obs::CObservation::Ptr o; r.next(o);) ++count;
        if (count != n) state.SkipWithError("wrong count");
    }
    state.SetItemsProcessed(int64_t(state.iterations() * n));
    state.counters["obs_per_s"] =
        benchmark::Counter(double(state.iterations() * n), benchmark::Counter::kIsRate);
    std::filesystem::remove(path);
}
void BM_RawlogPlayback(benchmark::State& state) { playback(state, true); }
void BM_RawlogPlaybackUnchecked(benchmark::State& state) { playback(state, false); }
BENCHMARK(BM_RawlogPlayback)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_RawlogPlaybackUnchecked)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

// The tracker (tests/beacons/test_tracker.cpp's drive): odometry at 20 Hz and four ranges
// per 0.2 s epoch round a 1 m circle, 30 % of them long; one iteration is one epoch (its
// four odometry readings and its ranges). Arg: 1 with the bias states, 0 without.
static void BM_TrackerEpoch(benchmark::State& state) {
    const beacons::BeaconMap map = {
        {1, {0, 0, 2.5}}, {2, {3, 0, 2.5}}, {3, {3, 3, 2.5}}, {4, {0, 3, 2.5}}};
    beacons::TrackerOptions o;
    o.rangeSigma = 0.01;
    o.fix.knownHeight = 0.0;
    o.estimateBias = state.range(0) != 0;
    // 300 epochs precomputed; the tracker runs them again and again
    mrpt::random::CRandomGenerator rng(7);
    mrpt::poses::CPose2D truth(1.5, 0.5, 0), odometry(5, -2, 1.0);
    const mrpt::poses::CPose2D step(0.0125, 0, 0.0125);
    std::vector<std::pair<std::vector<mrpt::poses::CPose2D>, mrpt::obs::CObservationBeaconRanges>>
        epochs;
    for (int k = 0; k < 300; ++k) {
        std::vector<mrpt::poses::CPose2D> odo;
        for (int j = 0; j < 4; ++j)
            truth = truth + step, odometry = odometry + step, odo.push_back(odometry);
        const auto obs = testing_beacons::rangesAt(map, truth, [&](int, double) {
            const double late = rng.drawUniform(0.0, 1.0) < 0.3 ? rng.drawUniform(0.02, 1.0) : 0;
            return rng.drawGaussian1D(0, 0.01) + late;
        });
        epochs.push_back({odo, obs});
    }
    size_t done = 0;
    for (auto _ : state) {
        state.PauseTiming();
        beacons::BeaconTracker tracker(map, o);
        state.ResumeTiming();
        for (size_t k = 0; k < epochs.size(); ++k) {
            for (const auto& p : epochs[k].first) tracker.onOdometry(p);
            benchmark::DoNotOptimize(tracker.onRanges(0.2 * double(k + 1), epochs[k].second));
        }
        done += epochs.size();
    }
    state.counters["epochs_per_s"] = benchmark::Counter(double(done), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_TrackerEpoch)->Arg(1)->Arg(0)->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
