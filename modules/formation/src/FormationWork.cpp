// The formation run's work (method/Work.h, doc/errors.md "Work"), from every key that
// multiplies it. The costs were measured once on the 2-core CI machine (Release build) by
// tests/bench/bench_formation (BM_ErrorModelMarch, BM_DeadReckonSteps, BM_PixelMarch) and
// by mrloc runs of formation_pixel.ini; tests/apps/test_work.cpp varies each key named here
// and checks that the estimate grows.
#include <mrloc/formation/FormationExperiment.h>
#include <mrloc/formation/Routes.h>
#include <mrpt/core/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace mrloc::formation {

namespace {

/** Seconds per error-model move with n robots, on one core: the route planner weighs every
 *  robot's candidate vertices against the others, about n^4 (BM_ErrorModelMarch: 0.53 us at
 *  4 robots, 24 us at 10, 4.5 ms at 32, 26 ms at 50). Interpolated log-log between the
 *  measured sizes, extrapolated beyond by the end slopes. */
double secondsPerMove(double n) {
    static constexpr std::array<std::pair<double, double>, 8> kMeasured{{{4, 0.53e-6},
                                                                         {6, 1.2e-6},
                                                                         {8, 6.6e-6},
                                                                         {10, 24e-6},
                                                                         {16, 164e-6},
                                                                         {24, 1.16e-3},
                                                                         {32, 4.5e-3},
                                                                         {50, 25.9e-3}}};
    size_t i = 1;
    while (i + 1 < kMeasured.size() && n > kMeasured[i].first) ++i;
    const auto [n0, s0] = kMeasured[i - 1];
    const auto [n1, s1] = kMeasured[i];
    const double slope = std::log(s1 / s0) / std::log(n1 / n0);
    return s0 * std::pow(std::max(n, 1.0) / n0, slope);
}

/** Moves of one march: one robot moves a triangle's half side at a time (153 moves on the
 *  many-turns route's 113 m at 1.5 m, 477 at 0.5 m, 178 with 10 robots), taken as 1.2 x
 *  the route over half a side. */
double movesPerMarch(double routeMetres, double side) { return 1.2 * routeMetres / (side / 2); }

/** Dead reckoning is stepped at its period along the whole route: 77 ns a step for the
 *  drive (BM_DeadReckonSteps, 5,559 to 322,428 steps), 110 ns in the experiment with its
 *  curves summed (experiment_speeds = 0.01: 100 runs of 6.3 million steps in about 70 s);
 *  16 bytes a step held (the error curve). */
constexpr double kSecondsPerDeadReckoningStep = 110e-9, kBytesPerDeadReckoningStep = 16;

double deadReckoningSteps(double routeMetres, const FormationConfig& c, double wheelSpeed) {
    return routeMetres / (c.wheelRadius * wheelSpeed * c.deadReckoning.dt);
}

/** Algorithm 1 from rendered frames, per start of fig. 3g's 3 x 3 x 3 grid. */
constexpr double kSecondsPerCameraStart = 0.17;
constexpr double kCameraGridStarts = 27;

/** A pixel march (the pixel experiment): 7.2 s on one core for 4 robots on a route with the
 *  640 x 200 camera (pixel_runs = 2: 8 marches in 29 s on 2 cores), its frames growing
 *  with the pixels and the robots and its moves with the route over the side. */
constexpr double kSecondsPerPixelMarch = 7.2, kReferencePixels = 640.0 * 200.0;

/** A pixel of the camera: 180 ps per robot and step to render and search, 27 bytes held
 *  (render target, image, grey copy and the tag detector's buffers; 647 MB at 4096 x 4096
 *  against 210 MB at 640 x 200). */
constexpr double kPixelSeconds = 1.8e-10, kPixelBytes = 27;

double routeMetres(const std::string& name) {
    const auto w = route(name);
    double m = 0;
    for (size_t i = 1; i < w.size(); ++i) m += (w[i] - w[i - 1]).norm();
    return m;
}

}  // namespace

std::vector<method::WorkItem> formationWork(const FormationLocalizer& localizer,
                                            const sim::ScenarioConfig* scenario) {
    const auto& c = localizer.config();
    const double robots = double(c.robots), side = c.formation.side;
    const double pixels = double(c.cameraWidth) * double(c.cameraRows);
    std::vector<method::WorkItem> out;
    if (scenario && c.mode == FormationConfig::Mode::Pixel) {
        // Measured on formation_pixel.ini (6,000 steps x 5 robots): simulation 1.0 s at
        // 640 x 200, 3.6 s at 2560 x 800, 21.5 s at 4096 x 1024, 46 s at 4096 x 2048, 93 s
        // and 647 MB at 4096 x 4096; taken as 150 us per robot and step (the 640 x 200
        // camera's 34 us with a margin for routes that turn more) and kPixelSeconds per
        // pixel (the largest cameras'; 45 ps at 2560 x 800 and below)
        method::WorkItem w;
        w.what = "the pixel mode's rendered frames";
        w.keys =
            "[formation] mode = pixel, camera_width x camera_rows, robots, x [scenario] "
            "duration / dt";
        const double robotSteps =
            scenario->scenario.duration / scenario->scenario.dt * (robots + 1);
        w.seconds = robotSteps * (150e-6 + kPixelSeconds * pixels);
        w.memory = kPixelBytes * pixels;
        w.simulation = true;
        out.push_back(w);
    }
    if (c.pixelRuns > 0) {
        double seconds = 0, memory = 0;
        for (const auto& name : c.experimentRoutes) {
            const double metres = routeMetres(name);
            const double moves = movesPerMarch(metres, side);
            for (const double speed : c.experimentSpeeds) {
                const double steps = deadReckoningSteps(metres, c, speed);
                seconds += kSecondsPerPixelMarch * (moves / movesPerMarch(metres, 1.5)) *
                               std::max(1.0, pixels / kReferencePixels) * robots / 4 +
                           moves * secondsPerMove(robots) + steps * kSecondsPerDeadReckoningStep;
                memory = std::max(memory, steps * kBytesPerDeadReckoningStep);
            }
        }
        method::WorkItem p;
        p.what = mrpt::format("the pixel experiment's %zu marches",
                              c.pixelRuns * c.experimentRoutes.size() * c.experimentSpeeds.size());
        p.keys =
            "[formation] pixel_runs x experiment_routes x experiment_speeds, camera_width x "
            "camera_rows, robots, side";
        p.seconds = double(c.pixelRuns) * seconds;
        p.memory = memory + kPixelBytes * pixels;
        p.parallel = true;  // pixelTable's pool
        out.push_back(p);
    }
    if (c.runs == 0) return out;
    // Table 1 and fig. 14: every route at every speed, a march of `robots` and a
    // dead-reckoned drive; fig. 15: the first route, N = 4 .. experiment_robots_max
    double seconds = 0, memory = 0;
    for (const auto& name : c.experimentRoutes) {
        const double metres = routeMetres(name);
        for (const double speed : c.experimentSpeeds) {
            const double steps = deadReckoningSteps(metres, c, speed);
            seconds += movesPerMarch(metres, side) * secondsPerMove(robots) +
                       steps * kSecondsPerDeadReckoningStep;
            memory = std::max(memory, steps * kBytesPerDeadReckoningStep);
        }
    }
    const double firstRoute = routeMetres(c.experimentRoutes.front());
    for (size_t n = 4; n <= c.experimentRobotsMax; ++n)
        seconds += movesPerMarch(firstRoute, side) * secondsPerMove(double(n));
    const size_t marches = c.experimentRoutes.size() * c.experimentSpeeds.size() +
                           (c.experimentRobotsMax >= 4 ? c.experimentRobotsMax - 3 : 0);
    method::WorkItem e;
    e.what = mrpt::format("the experiment's %zu x %zu marches", c.runs, marches);
    e.keys =
        "[formation] runs x (experiment_routes x experiment_speeds + experiment_robots_max - "
        "3), robots, side, wheel_radius x experiment_speeds x dr_period; camera_starts";
    e.seconds = double(c.runs) * seconds +
                (c.cameraStarts > 0 ? kCameraGridStarts * kSecondsPerCameraStart : 0);
    // fig. 11's model draws: 100 per run, lateral and longitudinal
    e.memory = memory + double(c.runs) * 100 * 2 * sizeof(double);
    out.push_back(e);
    return out;
}

}  // namespace mrloc::formation
