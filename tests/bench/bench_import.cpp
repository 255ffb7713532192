// Speed of `mrloc import`: records (input lines or bag messages) converted per second, file to
// rawlog, on every format's real or test input:
//   BM_Import/librsf      libRSF's Labyrinth (466 lines)
//   BM_Import/sonar-text  the Udacity log (826 lines in two files)
//   BM_Import/carmen      a CARMEN log of 2,000 lines written here (ODOM, FLASER of 181
//                         beams, SONAR of 16)
//   BM_Import/rosbag      tests/data/rosbag/tiny.bag (23 messages; the child process's fork
//                         dominates)
//   BM_Import/mrclam      MRCLAM dataset 6's robot 1 (113,000 lines; skipped without
//                         ../shared/data/mrclam-ds6)
// Run: build/tests/bench/bench_import --benchmark_repetitions=5
//      --benchmark_report_aggregates_only=true   (report the medians)
#include <benchmark/benchmark.h>
#include <mrloc/logimport/Format.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "TestPaths.h"

namespace {

namespace li = mrloc::logimport;
namespace fs = std::filesystem;

const std::string kSource = MRLOC_SOURCE_DIR;

struct Case {
    std::string format;
    std::vector<std::string> inputs, options;
    size_t records;
};

std::string carmenLog() {
    const std::string path = fs::temp_directory_path() / "bench_import.clf";
    std::ofstream out(path);
    for (int k = 0; k < 2000; ++k) {
        const double t = 100 + 0.05 * k;
        if (k % 3 == 0) {
            out << "ODOM " << 0.01 * k << " 0 0 0.2 0 0 " << t << " h " << t << "\n";
        } else if (k % 3 == 1) {
            out << "FLASER 181";
            for (int i = 0; i < 181; ++i) out << " " << 2 + std::sin(0.1 * i + k);
            out << " 0 0 0 0 0 0 " << t << " h " << t << "\n";
        } else {
            out << "SONAR 0.26 16";
            for (int i = 0; i < 16; ++i) out << " " << 1 + 0.1 * i;
            for (int i = 0; i < 16; ++i) out << " 0.1 0 " << 0.39 * i;
            out << " " << t << " h " << t << "\n";
        }
    }
    return path;
}

void BM_Import(benchmark::State& state, const Case& c) {
    li::FormatRegistry registry;
    li::registerAllFormats(registry);
    for (const auto& in : c.inputs)
        if (!fs::exists(in)) return state.SkipWithError(("absent: " + in).c_str());
    const std::string out = fs::temp_directory_path() / "bench_import.rawlog";
    for (auto _ : state) li::runImport(registry.get(c.format), c.inputs, c.options, out);
    state.counters["records_per_s"] =
        benchmark::Counter(double(c.records), benchmark::Counter::kIsIterationInvariantRate);
}

const std::string kReal = kSource + "/data/real";
const std::string kMrclam = kSource + "/../shared/data/mrclam-ds6";

BENCHMARK_CAPTURE(BM_Import, librsf,
                  Case{"librsf",
                       {kReal + "/librsf-indoor-uwb/Indoor_UWB_Input.txt",
                        kReal + "/librsf-indoor-uwb/Indoor_UWB_GT.txt"},
                       {"wheel_base_scale=2", "swap_wheels=yes"},
                       466 + 233})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_Import, sonar_text,
                  Case{"sonar-text",
                       {kReal + "/udacity-sonar/measurement.txt",
                        kReal + "/udacity-sonar/poses.txt"},
                       {"bearings=-90,-37.5,-22.5,-7.5,7.5,22.5,37.5,90"},
                       826})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_Import, carmen, Case{"carmen", {carmenLog()}, {}, 2000})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_Import, rosbag,
                  Case{"rosbag", {kSource + "/tests/data/rosbag/tiny.bag"}, {}, 23})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_Import, mrclam_robot1,
                  Case{"mrclam", {kMrclam}, {"robots=1"}, 61785 + 1942 + 49241})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
