// common::evaluate of a 10^6-pose truth against a 10^5-pose estimate (issue 53: well under a
// second), over three shapes of estimate: one that covers the whole truth, one with a gap in
// every 100 s (a tracker that loses its ranges), and one that starts halfway (a tracker that
// starts late). Each with the three alignments, since SE(2) adds a pass over the pairs.
#include <benchmark/benchmark.h>
#include <mrloc/common/Evaluation.h>

#include <cmath>

using namespace mrloc::common;

namespace {

constexpr size_t kTruthPoses = 1000000;  // 1,000 s at 1 kHz
constexpr size_t kEstimatePoses = 100000;

/** A robot on a 20 m circle at 1 m/s, sampled every `dt` s from t0, with a small wobble that
 *  makes every error differ. */
Trajectory circle(size_t n, double dt, double wobble) {
    Trajectory t;
    t.reserve(n);
    for (size_t k = 0; k < n; ++k) {
        const double time = 1.7e9 + double(k) * dt, a = double(k) * dt / 20.0;
        const double w = wobble * std::sin(0.37 * double(k) * dt);
        t.push_back({time, mrpt::poses::CPose3D(20 * std::cos(a) + w, 20 * std::sin(a) - w, 0,
                                                a + M_PI / 2 + 0.1 * w, 0, 0)});
    }
    return t;
}

enum Shape { kWhole = 0, kGaps = 1, kLateStart = 2 };

Trajectory estimateOf(Shape shape) {
    auto e = circle(kEstimatePoses, 0.01, 0.05);  // every 10 ms over the same 1,000 s
    Trajectory out;
    out.reserve(e.size());
    for (const auto& p : e) {
        const double s = p.t - 1.7e9;
        if (shape == kGaps && std::fmod(s, 100.0) > 90.0) continue;  // 10 s lost in every 100
        if (shape == kLateStart && s < 500.0) continue;
        out.push_back(p);
    }
    return out;
}

void BM_Evaluate(benchmark::State& state) {
    static const Trajectory truth = circle(kTruthPoses, 0.001, 0.0);
    const auto estimate = estimateOf(Shape(state.range(0)));
    EvaluationOptions o;
    o.align = Alignment(state.range(1));
    for (auto _ : state) {
        auto e = evaluate(estimate, truth, o);
        benchmark::DoNotOptimize(e.translation.rmse);
    }
    state.SetLabel(std::string(state.range(0) == kWhole  ? "whole"
                               : state.range(0) == kGaps ? "gaps"
                                                         : "late start") +
                   ", align " + alignmentName(o.align));
}

}  // namespace

BENCHMARK(BM_Evaluate)
    ->ArgsProduct({{kWhole, kGaps, kLateStart},
                   {int(Alignment::None), int(Alignment::SE2), int(Alignment::Origin)}})
    ->Unit(benchmark::kMillisecond)
    ->Repetitions(3)
    ->ReportAggregatesOnly(true);

BENCHMARK_MAIN();
