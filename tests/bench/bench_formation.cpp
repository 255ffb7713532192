// Speed of seed 003's Monte Carlo in the error-model mode (the target: 100 runs x 2 routes x
// 2 wheel speeds, formation and dead reckoning each, in under 2 s), of rendering and searching
// a frame at several resolutions, of whole pixel marches over both routes and several seeds,
// and of the pixel experiment (Table 1 from pixels).
// Run: build/tests/bench/bench_formation --benchmark_repetitions=5
//      --benchmark_report_aggregates_only=true   (report the medians)
#include <benchmark/benchmark.h>
#include <mrloc/formation/AlgorithmOne.h>
#include <mrloc/formation/FormationExperiment.h>
#include <mrloc/formation/March.h>
#include <mrloc/formation/Markers.h>
#include <mrloc/formation/PixelMarch.h>
#include <mrloc/formation/Routes.h>
#include <mrloc/sim/PinholeCamera.h>

#include <cmath>

using namespace mrloc;

namespace {

/** One iteration: the whole Table 1 experiment, 400 formation marches and 400 dead-reckoned
 *  drives. */
void BM_TableOneMonteCarlo(benchmark::State& state) {
    const auto manyTurns = formation::route("many_turns"), patrol = formation::route("patrol");
    mrpt::random::CRandomGenerator rng(1);
    size_t moves = 0;
    for (auto _ : state)
        for (const auto* route : {&manyTurns, &patrol})
            for (const double w : {5.8, 2.9})
                for (int run = 0; run < 100; ++run) {
                    formation::MarchOptions o;
                    o.wheelSpeed = w;
                    moves += formation::march(4, *route, {}, o, {}, rng).moves.size();
                    benchmark::DoNotOptimize(
                        formation::deadReckon(*route, o.wheelRadius, w, {}, rng).back().error);
                }
    state.counters["runs/s"] =
        benchmark::Counter(800.0 * double(state.iterations()), benchmark::Counter::kIsRate);
    state.counters["moves per march"] = double(moves) / (400.0 * double(state.iterations()));
}

/** The work estimate's costs (formationWork, doc/errors.md "Work"): an error-model march per
 *  move, for N robots and a triangle side; dead reckoning per step, at two wheel speeds (its
 *  steps are the route over speed x period). */
void BM_ErrorModelMarch(benchmark::State& state) {
    const auto route = formation::route(state.range(2) ? "patrol" : "many_turns");
    formation::MarchOptions o;
    o.formation.side = double(state.range(1)) / 10;
    mrpt::random::CRandomGenerator rng(1);
    size_t moves = 0;
    for (auto _ : state) moves += formation::march(size_t(state.range(0)), route, {}, o, {}, rng).moves.size();
    state.counters["moves"] = double(moves) / double(state.iterations());
    state.counters["us per move"] = benchmark::Counter(
        double(moves) * 1e-6, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_DeadReckonSteps(benchmark::State& state) {
    const auto route = formation::route(state.range(1) ? "patrol" : "many_turns");
    const double w = double(state.range(0)) / 10;
    mrpt::random::CRandomGenerator rng(1);
    size_t steps = 0;
    for (auto _ : state) steps += formation::deadReckon(route, 0.035, w, {}, rng).size() - 1;
    state.counters["steps"] = double(steps) / double(state.iterations());
    state.counters["ns per step"] = benchmark::Counter(
        double(steps) * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

/** The camera path's perception per frame: the rear camera (1280 x 720) renders three beacon
 *  robots with their tags, and ArUco finds them (seed 003 fig. 3g). */
void BM_RenderAndDetect(benchmark::State& state) {
    formation::MarkerOptions o;
    const auto step = formation::buildingStep(1.5, o);
    const double scale = double(state.range(1)) / 1280;
    auto k = formation::cameraIntrinsics(485);
    k.ncols = uint32_t(state.range(1)), k.nrows = uint32_t(std::lround(720 * scale));
    k.setIntrinsicParamsFromValues(485 * scale, 485 * scale, k.ncols / 2.0, k.nrows / 2.0);
    sim::PinholeCamera camera(k);
    const auto pose =
        sim::cameraPoseLooking({step.vertex.x(), step.vertex.y(), o.tagHeight}, M_PI / 2);
    // 0: none, 1: ArUco, 2: AprilTag 3 (decimation 2), 3: AprilTag 3 at full resolution (the
    // simulator's pixel mode)
    const int detector = int(state.range(0));
    size_t tags = 0;
    for (auto _ : state) {
        const auto picture = camera.render(*step.scene, pose);
        if (detector == 1) tags += formation::detectMarkersArUco(picture).size();
        if (detector == 2) tags += formation::detectMarkers(picture).size();
        if (detector == 3) tags += formation::detectMarkers(picture, 1).size();
    }
    state.counters["frames/s"] =
        benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
    state.counters["tags per frame"] = double(tags) / double(state.iterations());
    const char* labels[] = {"render only", "render + ArUco", "render + AprilTag 3",
                            "render + AprilTag 3, full resolution"};
    state.SetLabel(labels[detector]);
}

/** The camera path's control loop: Algorithm 1 from 0.15 m aside, 0.2 m short and 10 degrees
 *  off, each frame rendered, searched and acted on (render + detect + control). */
void BM_AlgorithmOne(benchmark::State& state) {
    formation::MarkerOptions markers;
    const auto step = formation::buildingStep(1.5, markers);
    sim::PinholeCamera camera(formation::cameraIntrinsics(485));
    mrpt::random::CRandomGenerator rng(1);
    const mrpt::poses::CPose2D start(step.vertex.x() + 0.15, step.vertex.y() + 0.2,
                                     step.vertex.phi() + 10 * M_PI / 180);
    int frames = 0;
    for (auto _ : state)
        frames +=
            formation::runAlgorithmOne(*step.scene, step.beacons, start, camera, markers, {}, rng)
                .frames;
    state.counters["frames/s"] = benchmark::Counter(double(frames), benchmark::Counter::kIsRate);
    state.counters["frames per run"] = double(frames) / double(state.iterations());
}

/** A camera of the pixel mode's field of view (f = 485 px at 1280 x 720) at `width` px. */
mrpt::img::TCamera scaledCamera(long width, long rows = 0) {
    const double scale = double(width) / 1280;
    auto k = formation::cameraIntrinsics(485);
    k.ncols = uint32_t(width), k.nrows = uint32_t(rows > 0 ? rows : std::lround(720 * scale));
    k.setIntrinsicParamsFromValues(485 * scale, 485 * scale, k.ncols / 2.0, k.nrows / 2.0);
    return k;
}

/** A whole pixel march (4 robots) along a route of seed 003: every frame rendered, searched
 *  and decided on. Args: route (0 many turns, 1 patrol), camera width (px), seed, corrections
 *  together (1) or one per frame (0), rows (0: 16:9), lateral rule (0 midpoint, 1 the
 *  paper's; optional). Counters: the formation's |rotation| after 50, 100 and 150 moves. */
void BM_PixelMarch(benchmark::State& state) {
    const auto route = formation::route(state.range(0) == 0 ? "many_turns" : "patrol");
    formation::PixelMarchOptions o;
    o.camera.intrinsics = scaledCamera(state.range(1), state.range(4));
    o.camera.algorithmOne.lateral = state.range(5) == 1
                                        ? formation::AlgorithmOneOptions::Lateral::Paper
                                        : formation::AlgorithmOneOptions::Lateral::Midpoint;
    o.camera.algorithmOne.together = state.range(3) != 0;
    const size_t robots = size_t(state.range(6));
    o.camera.latticeFit = state.range(7) != 0;
    sim::PinholeCamera camera(formation::renderIntrinsics(o));
    size_t frames = 0, moves = 0, lost = 0;
    double error = 0, rotation = 0;
    for (auto _ : state) {
        mrpt::random::CRandomGenerator rng(uint32_t(state.range(2)));
        const auto r = formation::pixelMarch(robots, route, {}, o, camera, rng);
        frames += r.frames, moves += r.march.moves.size(), lost += r.lostMoves;
        error = r.march.finalError();
        rotation = r.rotation.empty() ? 0 : r.rotation.back() * 180 / M_PI;
        for (const size_t at : {50, 100, 150})
            state.counters["rot" + std::to_string(at) + " deg"] =
                r.rotation.size() >= at ? std::abs(r.rotation[at - 1]) * 180 / M_PI : NAN;
    }
    const double n = double(state.iterations());
    state.counters["frames/s"] = benchmark::Counter(double(frames), benchmark::Counter::kIsRate);
    state.counters["frames"] = double(frames) / n;
    state.counters["moves"] = double(moves) / n;
    state.counters["lost"] = double(lost) / n;
    state.counters["error m"] = error;
    state.counters["rotation deg"] = rotation;
}

}  // namespace

/** The pixel experiment (Table 1 from pixels) with pixel_runs = 2: 8 marches (both routes,
 *  both speeds) on every core, dead reckoning beside each. */
void BM_PixelExperiment(benchmark::State& state) {
    formation::FormationConfig c;
    c.runs = 0, c.cameraStarts = 0, c.pixelRuns = 2;
    size_t rows = 0;
    for (auto _ : state) rows += formation::runFormationExperiment(c).pixel.size();
    state.counters["marches"] = 8;
    state.counters["rows"] = double(rows) / double(state.iterations());
}

// Args: route (0 many turns, 1 patrol), width (px), seed, corrections together (1) or one
// per frame (0), rows (0: 16:9), lateral rule (0 midpoint, 1 the paper's), robots, lattice
// fit (1) or Algorithm 1 alone (0)
BENCHMARK(BM_PixelMarch)
    ->ArgsProduct({{0, 1}, {640}, {1, 2, 3}, {1}, {200}, {0}, {4}, {1}})
    ->ArgsProduct({{0}, {640}, {1, 2, 3}, {0}, {200}, {0}, {4}, {1}})
    ->ArgsProduct({{0}, {640}, {1, 2, 3}, {1}, {200}, {1}, {4}, {1}})
    ->ArgsProduct({{0}, {960}, {1, 2, 3}, {1}, {300}, {0}, {4}, {1}})
    ->ArgsProduct({{0}, {1280}, {1, 2, 3}, {1}, {400}, {0}, {4}, {1}})
    ->ArgsProduct({{0}, {640}, {1, 2, 3}, {1}, {200}, {0}, {6, 8}, {0, 1}})
    ->ArgsProduct({{0}, {960}, {1, 2, 3}, {1}, {300}, {0}, {8}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);
BENCHMARK(BM_PixelExperiment)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK(BM_AlgorithmOne)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_RenderAndDetect)
    ->Args({0, 1280})
    ->Args({1, 1280})
    ->Args({2, 1280})
    ->Args({3, 1280})
    ->Args({0, 640})
    ->Args({3, 640})
    ->Args({0, 960})
    ->Args({3, 960})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_TableOneMonteCarlo)->Unit(benchmark::kMillisecond);
// robots, side in dm, route (0 many turns, 1 patrol); wheel speed in 0.1 rad/s, route
BENCHMARK(BM_ErrorModelMarch)
    ->ArgsProduct({{4, 6, 8, 10, 16, 24, 32, 50}, {15}, {0, 1}})
    ->ArgsProduct({{4}, {5, 30}, {0, 1}})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DeadReckonSteps)->ArgsProduct({{58, 29, 1}, {0, 1}})->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
