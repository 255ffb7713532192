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
//   BM_ImportRosbagTopics/N  a bag of N topics, one message each (half Odometry, half
//                         String, left out): the time order is merged in O(M log C), and
//                         rosbag::View was quadratic in topics (written by Debian's
//                         python3-rosbag; skipped without it)
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

/** A bag of `topics` topics, one message each, written once per size. */
std::string topicsBag(long topics) {
    const std::string path =
        fs::temp_directory_path() / ("bench_import_topics" + std::to_string(topics) + ".bag");
    if (fs::exists(path)) return path;
    const std::string script = fs::temp_directory_path() / "bench_import_topics.py";
    std::ofstream(script) << "import sys, rosbag, rospy\n"
                             "from nav_msgs.msg import Odometry\n"
                             "from std_msgs.msg import String\n"
                             "with rosbag.Bag(sys.argv[2], 'w') as bag:\n"
                             "    for k in range(int(sys.argv[1])):\n"
                             "        t = rospy.Time.from_sec(1000 + 0.001 * k)\n"
                             "        if k % 2:\n"
                             "            bag.write('/s%d' % k, String(data='x'), t)\n"
                             "            continue\n"
                             "        o = Odometry()\n"
                             "        o.header.stamp, o.pose.pose.orientation.w = t, 1.0\n"
                             "        bag.write('/odom%d' % k, o, t)\n";
    const std::string tmp = path + ".tmp.bag";
    if (std::system(("/usr/bin/python3 " + script + " " + std::to_string(topics) + " " + tmp +
                     " 2>/dev/null")
                        .c_str()) != 0)
        return "";
    fs::rename(tmp, path);
    return path;
}

void BM_ImportRosbagTopics(benchmark::State& state) {
    const std::string bag = topicsBag(state.range(0));
    if (bag.empty()) return state.SkipWithError("Debian's python3-rosbag is not installed");
    li::FormatRegistry registry;
    li::registerAllFormats(registry);
    const std::string out = fs::temp_directory_path() / "bench_import_topics.rawlog";
    for (auto _ : state) li::runImport(registry.get("rosbag"), {bag}, {}, out);
    state.counters["topics_per_s"] =
        benchmark::Counter(double(state.range(0)), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_ImportRosbagTopics)
    ->Arg(2500)
    ->Arg(10000)
    ->Arg(40000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
