// Speed of polymap on real scans (doc/polymap.md, "Real scans"): tracing MRPT's grid maps,
// the 360-degree range profile of one position (720 rays: the search's unit of work), the
// hypotheses from a first scan with the heading unknown over the whole map, and one passive
// update. Maps: MRPT's localization_demo simplemap, the map icp-slam builds of the SENA log
// (both traced), and a 100 x 50 m hall with 100 pillars of 20 vertices (n = 2004).
// Run: build/tests/bench/bench_scan_localizer --benchmark_repetitions=5
//      --benchmark_report_aggregates_only=true   (report the medians)
#include <benchmark/benchmark.h>
#include <mrloc/common/Rawlog.h>
#include <mrloc/polymap/GridTrace.h>
#include <mrloc/polymap/ScanLocalizer.h>
#include <mrpt/random/RandomGenerators.h>

#include <map>
#include <memory>

#include "TestPaths.h"

using namespace mrloc;
using common::TPoint2D;

namespace {

const std::string kDemoMap = "/usr/share/mrpt/datasets/localization_demo.simplemap.gz";
const std::string kDemoLog = "/usr/share/mrpt/datasets/localization_demo.rawlog";
const std::string kSenaMap =
    std::string(MRLOC_SOURCE_DIR) + "/data/real/mrpt-references/sena.icp-slam.simplemap";
const std::string kSenaLog =
    "/usr/share/mrpt/datasets/2006-01ENE-21-SENA_Telecom Faculty_one_loop_only.rawlog";

/** The hall: 100 x 50 m, 100 round pillars (20-gons of radius 0.3 m) on a jittered grid. */
std::vector<std::vector<TPoint2D>> pillarHall() {
    mrpt::random::CRandomGenerator rng(4);
    std::vector<std::vector<TPoint2D>> rings{{{0, 0}, {100, 0}, {100, 50}, {0, 50}}};
    for (int i = 0; i < 10; ++i)
        for (int j = 0; j < 10; ++j) {
            const TPoint2D c{5 + 10 * i + rng.drawUniform(-2, 2),
                             3 + 4.5 * j + rng.drawUniform(-1, 1)};
            auto& ring = rings.emplace_back();
            for (int k = 0; k < 20; ++k)
                ring.push_back({c.x + 0.3 * std::cos(2 * M_PI * k / 20),
                                c.y + 0.3 * std::sin(2 * M_PI * k / 20)});
        }
    return rings;
}

struct Case {
    polymap::WallMap map;
    std::vector<polymap::ScanBeamSet> scans;  ///< the log's first scans
};

/** 0: localization_demo, 1: SENA, 2: the pillar hall (scans cast in it, 180 degrees). */
const Case& caseOf(int which) {
    static std::map<int, std::unique_ptr<Case>> cache;
    if (auto it = cache.find(which); it != cache.end()) return *it->second;
    auto c = std::make_unique<Case>();
    if (which == 2) {
        c->map = polymap::wallMapOfRings(pillarHall(), 0.05, 0.15, "pillar hall");
        for (int s = 0; s < 2; ++s) {
            polymap::ScanBeamSet b;
            b.maxRange = 80;
            b.sensor = {0.3, 0, 0};
            const mrpt::math::TPose2D robot{42.0 + 0.2 * s, 21.0, 0.4};
            for (int i = 0; i < 361; ++i) {
                b.angle.push_back(-M_PI / 2 + M_PI * i / 360);
                const TPoint2D at{robot.x + 0.3 * std::cos(robot.phi),
                                  robot.y + 0.3 * std::sin(robot.phi)};
                b.range.push_back(c->map.caster.cast(at, robot.phi + b.angle.back(), 80));
            }
            b.returns = 361;
            c->scans.push_back(b);
        }
    } else {
        polymap::GridTraceOptions o;
        o.resolution = which == 0 ? 0.06 : 0.05;
        const auto grid = polymap::loadGridMap(which == 0 ? kDemoMap : kSenaMap, o);
        c->map = polymap::traceGrid(grid, o, "map");
        common::RawlogReader reader(which == 0 ? kDemoLog : kSenaLog);
        for (mrpt::obs::CObservation::Ptr obs; reader.next(obs) && c->scans.size() < 2;)
            if (const auto s = std::dynamic_pointer_cast<mrpt::obs::CObservation2DRangeScan>(obs))
                c->scans.push_back(polymap::beamSetOf(*s));
    }
    return *cache.emplace(which, std::move(c)).first->second;
}

void BM_TraceGrid(benchmark::State& state) {
    polymap::GridTraceOptions o;
    o.resolution = state.range(0) == 0 ? 0.06 : 0.05;
    const auto grid = polymap::loadGridMap(state.range(0) == 0 ? kDemoMap : kSenaMap, o);
    for (auto _ : state) benchmark::DoNotOptimize(polymap::traceGrid(grid, o, "map"));
}
BENCHMARK(BM_TraceGrid)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_RangeProfile(benchmark::State& state) {
    // 720 rays from one free position: what the first scan's search pays per position
    const auto& c = caseOf(int(state.range(0)));
    mrpt::random::CRandomGenerator rng(2);
    std::vector<TPoint2D> at;
    while (at.size() < 64) {
        const TPoint2D p{rng.drawUniform(c.map.min.x, c.map.max.x),
                         rng.drawUniform(c.map.min.y, c.map.max.y)};
        if (c.map.freeCells.at(p)) at.push_back(p);
    }
    size_t k = 0;
    for (auto _ : state) {
        const TPoint2D& p = at[k++ % at.size()];
        double sum = 0;
        for (int i = 0; i < 720; ++i) sum += c.map.caster.cast(p, 2 * M_PI * i / 720, 80);
        benchmark::DoNotOptimize(sum);
    }
}
BENCHMARK(BM_RangeProfile)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);

void BM_HypothesesFromFirstScan(benchmark::State& state) {
    const auto& c = caseOf(int(state.range(0)));
    polymap::ScanLocalizerOptions o;
    for (auto _ : state) benchmark::DoNotOptimize(polymap::globalHypotheses(c.map, c.scans[0], o));
}
BENCHMARK(BM_HypothesesFromFirstScan)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

void BM_PassiveUpdate(benchmark::State& state) {
    // one later scan with the first scan's hypotheses (at most max_hypotheses) alive
    const auto& c = caseOf(int(state.range(0)));
    polymap::ScanLocalizerOptions o;
    const auto H = polymap::globalHypotheses(c.map, c.scans[0], o);
    state.counters["hypotheses"] = double(H.size());
    for (auto _ : state) {
        polymap::PassiveElimination e(c.map, o, H, 0);
        e.update({0, 0, 0}, 0, c.scans[1]);
        benchmark::DoNotOptimize(e.live().size());
    }
}
BENCHMARK(BM_PassiveUpdate)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
