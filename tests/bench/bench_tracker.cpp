// Speed of the beacon tracker on single sightings (issue 54): EKF updates per second with a
// range and a bearing to one landmark at a time, with 4 and 15 landmarks in the map (the bias
// state grows with them), over 3 layouts; and the particle start-up's sightings per second
// until it converges.
// Run: build/tests/bench/bench_tracker --benchmark_repetitions=5
//      --benchmark_report_aggregates_only=true   (report the medians)
#include <benchmark/benchmark.h>
#include <mrloc/beacons/BeaconTracker.h>
#include <mrpt/random/RandomGenerators.h>

#include <cmath>

using namespace mrloc;

namespace {

/** `n` landmarks scattered over a 10 x 10 m arena, layout `seed`. */
beacons::BeaconMap layout(int n, int seed) {
    mrpt::random::CRandomGenerator rng{uint32_t(seed)};
    beacons::BeaconMap map;
    for (int i = 0; i < n; ++i) {
        const double x = rng.drawUniform(0, 10), y = rng.drawUniform(0, 10);
        map[i + 1] = mrpt::math::TPoint3D(x, y, 0);
    }
    return map;
}

/** The robot on a circle of 3 m about the arena's centre at `t` s (0.3 m/s). */
mrpt::poses::CPose2D onCircle(double t) {
    const double a = 0.1 * t;
    return {5 + 3 * std::cos(a), 5 + 3 * std::sin(a), a + M_PI / 2};
}

std::vector<beacons::BeaconTracker::Sighting> sightingOf(const beacons::BeaconMap& map, int id,
                                                         const mrpt::poses::CPose2D& p,
                                                         mrpt::random::CRandomGenerator& rng) {
    const auto& b = map.at(id);
    beacons::BeaconTracker::Sighting s;
    s.beacon = {b.x, b.y, b.z};
    s.sensorOnRobot = {0, 0, 0};
    s.range = std::hypot(b.x - p.x(), b.y - p.y()) + rng.drawGaussian1D(0, 0.05);
    s.bearing = std::atan2(b.y - p.y(), b.x - p.x()) - p.phi() + rng.drawGaussian1D(0, 0.01);
    s.rangeSigma = 0.05;
    s.bearingSigma = 0.01;
    s.beaconId = id;
    return {s};
}

void BM_TrackerSighting(benchmark::State& state) {
    const int n = int(state.range(0));
    size_t updates = 0;
    for (auto _ : state) {
        state.PauseTiming();
        mrpt::random::CRandomGenerator rng(7);
        std::vector<beacons::BeaconTracker> trackers;
        std::vector<beacons::BeaconMap> maps;
        beacons::TrackerOptions o;
        o.rangeSigma = 0.05;
        o.bearingSigma = 0.01;
        o.startPose = onCircle(0);
        for (int seed = 1; seed <= 3; ++seed) {
            maps.push_back(layout(n, seed));
            trackers.emplace_back(maps.back(), o);
        }
        state.ResumeTiming();
        // 1,000 steps of 0.1 s per layout: an odometry reading and a sighting each
        for (size_t k = 0; k < trackers.size(); ++k)
            for (int step = 0; step < 1000; ++step) {
                const double t = 0.1 * step;
                const auto p = onCircle(t);
                trackers[k].onOdometry(p);
                trackers[k].onSightings(t, sightingOf(maps[k], 1 + step % n, p, rng));
                ++updates;
            }
    }
    state.SetItemsProcessed(int64_t(updates));
}
BENCHMARK(BM_TrackerSighting)->Arg(4)->Arg(15)->Unit(benchmark::kMillisecond);

void BM_ParticleStartUntilConverged(benchmark::State& state) {
    const int n = int(state.range(0));
    size_t sightings = 0, started = 0;
    for (auto _ : state) {
        for (int seed = 1; seed <= 3; ++seed) {
            mrpt::random::CRandomGenerator rng{uint32_t(seed)};
            const auto map = layout(n, seed);
            beacons::TrackerOptions o;
            o.rangeSigma = 0.05;
            o.bearingSigma = 0.01;
            beacons::BeaconTracker tracker(map, o);
            for (int step = 0; step < 600 && !tracker.initialized(); ++step) {
                const double t = 0.1 * step;
                const auto p = onCircle(t);
                tracker.onOdometry(p);
                tracker.onSightings(t, sightingOf(map, 1 + step % n, p, rng));
                ++sightings;
            }
            started += tracker.initialized();
        }
    }
    state.SetItemsProcessed(int64_t(sightings));
    state.counters["started_share"] = double(started) / double(3 * state.iterations());
}
BENCHMARK(BM_ParticleStartUntilConverged)->Arg(4)->Arg(15)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
