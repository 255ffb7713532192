// Speed of seed 004's on-board system: sonar readings processed per second. The issue's
// target: at least 1,000,000 per second per core, far beyond any sonar ring.
//   BM_WallDetector   one sonar's readings along the corridor (ERP pairs, groups, line fits)
//   BM_OnBoardTeam    the whole on-board system of the corridor's two robots on its log:
//                     odometry, every sonar's wall detector, announcements over the bus,
//                     matching and redefinitions (single thread)
//   BM_SonarSimulator the simulator's sonar model (a fan of rays in the OctoMap's slice)
// Run: build/tests/bench/bench_framesync --benchmark_repetitions=5
//      --benchmark_report_aggregates_only=true   (report the medians)
#include <benchmark/benchmark.h>
#include <mrloc/framesync/FramesyncConfig.h>
#include <mrloc/framesync/FramesyncPayload.h>
#include <mrloc/framesync/Team.h>
#include <mrloc/sim/Simulator.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CObservationRange.h>

#include "TestPaths.h"

using namespace mrloc;
using namespace mrloc::framesync;

namespace {

/** The corridor's log (config/framesync_corridor.ini, seed 1), kept in memory. */
struct CorridorLog {
    FramesyncConfig config;
    std::vector<mrpt::obs::CObservation::Ptr> log;
    size_t readings = 0;
    CorridorLog() {
        mrpt::config::CConfigFile ini(std::string(MRLOC_SOURCE_DIR) +
                                      "/config/framesync_corridor.ini");
        config.loadFromConfigFile(ini, "framesync");
        const auto scenario = sim::ScenarioConfig::load(ini);
        FramesyncPayload payload(config, scenario.scenario.dt);
        sim::Simulator simulator(scenario);
        simulator.run(
            [&](const mrpt::obs::CObservation& o) {
                log.push_back(
                    std::dynamic_pointer_cast<mrpt::obs::CObservation>(o.duplicateGetSmartPtr()));
                if (auto r = dynamic_cast<const mrpt::obs::CObservationRange*>(&o))
                    readings += r->sensedData.size();
            },
            &payload);
    }
};

const CorridorLog& corridor() {
    static const CorridorLog c;
    return c;
}

void BM_WallDetector(benchmark::State& state) {
    // the real robot's left sonar, in its odometry frame
    const auto& c = corridor();
    std::vector<SonarReading> readings;
    mrpt::poses::CPose2D odometry;
    for (const auto& o : c.log) {
        if (o->sensorLabel == "real.odom")
            odometry = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(o)->odometry;
        if (o->sensorLabel != "real.sonar") continue;
        for (const auto& m : std::dynamic_pointer_cast<mrpt::obs::CObservationRange>(o)->sensedData)
            if (std::abs(m.sensorPose.yaw - M_PI / 2) < 1e-6)  // the left sonar
                readings.push_back({0,
                                    odometry + mrpt::poses::CPose2D(m.sensorPose.x, m.sensorPose.y,
                                                                    m.sensorPose.yaw),
                                    m.sensedDistance, m.sensedDistance > 0});
    }
    size_t walls = 0;
    for (auto _ : state) {
        WallDetector d(c.config.team.detector);
        for (const auto& r : readings) walls += d.add(r).has_value();
    }
    state.counters["readings/s"] = benchmark::Counter(
        double(readings.size()) * double(state.iterations()), benchmark::Counter::kIsRate);
    state.counters["walls per pass"] = double(walls) / double(state.iterations());
}

void BM_OnBoardTeam(benchmark::State& state) {
    const auto& c = corridor();
    size_t events = 0;
    for (auto _ : state) {
        FrameTeam team(c.config.team);
        for (const auto& o : c.log) team.process(o);
        events += team.events().size();
    }
    state.counters["readings/s"] = benchmark::Counter(
        double(c.readings) * double(state.iterations()), benchmark::Counter::kIsRate);
    state.counters["redefinitions per pass"] = double(events) / double(state.iterations());
}

void BM_SonarSimulator(benchmark::State& state) {
    const auto& c = corridor();
    mrpt::config::CConfigFile ini(std::string(MRLOC_SOURCE_DIR) + "/config/framesync_corridor.ini");
    const sim::World world(sim::ScenarioConfig::load(ini).world);
    const FloorSlice slice(world, 0.3);
    size_t n = 0;
    double sum = 0;
    for (auto _ : state)
        for (double x = 1; x < 22; x += 0.03, ++n)
            if (auto e = nearestEcho(slice, mrpt::poses::CPose2D(x, 1.1, M_PI / 2), c.config.rig))
                sum += *e;
    benchmark::DoNotOptimize(sum);
    state.counters["readings/s"] = benchmark::Counter(double(n), benchmark::Counter::kIsRate);
}

}  // namespace

BENCHMARK(BM_WallDetector)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OnBoardTeam)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SonarSimulator)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
