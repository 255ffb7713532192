// Simulated ultrasonic shots per second in closed loop: config/beacons_multi_robot.ini (four
// robots, two sections, active heads, priority scheduling, the on-board tracker running),
// rawlog writing included. Issue 3's benchmark.
#include <benchmark/benchmark.h>
#include <mrloc/beacons/BeaconPayload.h>
#include <mrloc/beacons/BeaconsMethod.h>
#include <mrloc/sim/Simulator.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "TestPaths.h"

using namespace mrloc;

namespace {
std::string iniText() {
    std::ifstream in(std::string(MRLOC_SOURCE_DIR) + "/config/beacons_multi_robot.ini");
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}
}  // namespace

static void BM_MultiRobotShots(benchmark::State& state) {
    mrpt::config::CConfigFileMemory ini(iniText());
    ini.write("scenario", "duration", "20");
    const auto cfg = beacons::loadScenario(ini).config;
    const std::string path =
        (std::filesystem::temp_directory_path() / "mrloc_bench_ranging.rawlog").string();
    size_t shots = 0;
    for (auto _ : state) {
        auto scenario = beacons::loadScenario(ini);  // a fresh on-board part each run
        common::RawlogWriter out(path);
        sim::Simulator simulator(cfg);
        const auto r = simulator.run(out, scenario.payload.get());
        shots += dynamic_cast<const beacons::BeaconPayload&>(*scenario.payload).shots().size();
        benchmark::DoNotOptimize(r.observations);
    }
    state.counters["shots_per_s"] = benchmark::Counter(double(shots), benchmark::Counter::kIsRate);
    state.counters["shots_per_run"] = double(shots) / double(state.iterations());
    state.counters["sim_s_per_s"] =  // simulated time per wall-clock second
        benchmark::Counter(cfg.scenario.duration * double(state.iterations()),
                           benchmark::Counter::kIsRate);
    std::filesystem::remove(path);
}
BENCHMARK(BM_MultiRobotShots)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
