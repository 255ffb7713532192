#include <mrloc/common/ParallelFor.h>
#include <mrloc/common/Progress.h>
#include <mrloc/common/Seeds.h>
#include <mrloc/formation/AlgorithmOne.h>
#include <mrloc/formation/FormationExperiment.h>
#include <mrloc/formation/FormationLocalizer.h>
#include <mrloc/formation/PixelMarch.h>
#include <mrloc/formation/Routes.h>
#include <mrpt/core/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>

namespace mrloc::formation {

namespace {

// The purposes whose draws common::seedOf separates under the experiment's seed (Table 1's
// runs are seeds experiment_seed + r instead, so that a batch over seeds gives them)
constexpr const char* kPixelTableDraws = "formation pixel table";
constexpr const char* kFig15Draws = "formation fig. 15 and fig. 11";

/** A dead-reckoning curve point every this many seconds (fig. 14). */
constexpr double kCurveStep = 5;

/** Algorithm 1 from pixels starts from a 3 x 3 x 3 grid around the vertex (any
 *  camera_starts > 0). */
constexpr size_t kCameraGridStarts = 27;

/** Marches per Monte Carlo run: every route at every speed (Table 1, fig. 14), then N = 4 ..
 *  experiment_robots_max on the first route (fig. 15). */
size_t marchesPerRun(const FormationConfig& c) {
    return c.experimentRoutes.size() * c.experimentSpeeds.size() +
           (c.experimentRobotsMax >= 4 ? c.experimentRobotsMax - 3 : 0);
}

/** One pixel march and the dead-reckoned drive beside it. */
struct PixelJob {
    size_t route = 0, speed = 0, run = 0;
    PixelMarchResult march;
    double deadReckoning = 0;
};

/** Table 1 from pixels: pixel_runs pixel marches per route and speed, on every core. Each
 *  worker thread renders with its own camera (an EGL context is current on one thread) and
 *  each march draws from its own generator, the stream of its place in the table under the
 *  experiment's seed (common/Seeds.h): the same file whatever the thread count. */
std::vector<FormationExperimentFile::PixelRow> pixelTable(const FormationConfig& c,
                                                          const common::Log& log,
                                                          std::vector<double>& lateral,
                                                          std::vector<double>& longitudinal) {
    std::vector<PixelJob> jobs;
    for (size_t r = 0; r < c.experimentRoutes.size(); ++r)
        for (size_t w = 0; w < c.experimentSpeeds.size(); ++w)
            for (size_t run = 0; run < c.pixelRuns; ++run) jobs.push_back({r, w, run, {}, 0});
    std::vector<std::vector<TPoint2D>> routes;
    for (const auto& name : c.experimentRoutes) routes.push_back(route(name));
    std::atomic<size_t> done{0};
    common::Progress progress("formation pixel experiment", jobs.size(), log);
    common::parallelForWorkers(
        jobs.size(),
        [&] {
            // a camera per thread: its EGL context is current on the thread that made it
            auto camera = std::make_shared<sim::PinholeCamera>(
                renderIntrinsics(pixelMarchOptions(c, c.wheelSpeed)));
            return [&, camera](size_t k) {
                auto& j = jobs[k];
                mrpt::random::CRandomGenerator rng(common::streamSeed(
                    common::seedOf(c.experimentSeed.value, kPixelTableDraws), k));
                const double w = c.experimentSpeeds[j.speed];
                j.march = pixelMarch(c.robots, routes[j.route], {}, pixelMarchOptions(c, w),
                                     *camera, rng);
                j.deadReckoning =
                    deadReckon(routes[j.route], c.wheelRadius, w, c.deadReckoning, rng)
                        .back()
                        .error;
                ++done;
            };
        },
        [&] { progress.update(done); });  // the calling thread draws the bar
    std::vector<FormationExperimentFile::PixelRow> rows;
    for (size_t r = 0; r < c.experimentRoutes.size(); ++r)
        for (size_t w = 0; w < c.experimentSpeeds.size(); ++w) {
            FormationExperimentFile::PixelRow row;
            row.route = c.experimentRoutes[r];
            row.wheelSpeed = c.experimentSpeeds[w];
            std::vector<double> errors;
            for (const auto& j : jobs) {
                if (j.route != r || j.speed != w) continue;
                const auto& m = j.march;
                ++row.runs;
                row.arrived += m.march.arrived ? 1 : 0;
                errors.push_back(m.march.finalError());
                row.deadReckoning += j.deadReckoning;
                row.lostMoves += double(m.lostMoves);
                row.frames += double(m.frames);
                row.rotation += m.rotation.empty() ? 0 : std::abs(m.rotation.back());
                lateral.insert(lateral.end(), m.lateral.begin(), m.lateral.end());
                longitudinal.insert(longitudinal.end(), m.longitudinal.begin(),
                                    m.longitudinal.end());
            }
            const double n = double(row.runs);
            for (const double e : errors)
                row.formation += e / n, row.formationMax = std::max(row.formationMax, e);
            for (const double e : errors)
                row.formationSd += (e - row.formation) * (e - row.formation) / n;
            row.formationSd = std::sqrt(row.formationSd);
            row.deadReckoning /= n, row.lostMoves /= n, row.frames /= n, row.rotation /= n;
            rows.push_back(row);
        }
    return rows;
}

MarchOptions marchOptions(const FormationConfig& c) {
    MarchOptions o;
    o.formation = c.formation;
    o.wheelRadius = c.wheelRadius;
    o.maxMoves = c.maxMoves;
    o.carry = c.carry;
    return o;
}

/** One march of Table 1 and the dead-reckoned drive beside it. */
struct TableMarch {
    MarchResult march;
    std::vector<ErrorSample> deadReckoning;
};

/** One Monte Carlo run of Table 1 (and fig. 14): every route at every speed, in that
 *  order, drawn from a generator of its own seeded with `seed`. Run r of the experiment is
 *  seed experiment_seed + r, so that `mrloc batch` over those seeds gives Table 1. */
std::vector<TableMarch> tableRun(const FormationConfig& c, unsigned long seed) {
    mrpt::random::CRandomGenerator rng{static_cast<uint32_t>(seed)};
    MarchOptions o = marchOptions(c);
    std::vector<TableMarch> out;
    for (const auto& name : c.experimentRoutes) {
        const auto waypoints = route(name);
        for (const double w : c.experimentSpeeds) {
            o.wheelSpeed = w;
            TableMarch t;
            t.march = march(c.robots, waypoints, {}, o, c.vertexErrors, rng);
            t.deadReckoning = deadReckon(waypoints, c.wheelRadius, w, c.deadReckoning, rng);
            out.push_back(std::move(t));
        }
    }
    return out;
}

}  // namespace

common::Headline formationTrial(const method::TrialOf<FormationLocalizer>& in) {
    const auto& c = in.localizer.config();
    const auto run = tableRun(c, in.scenario.scenario.seed);
    common::Headline h;
    h.status = "Table 1, one run";
    size_t k = 0;
    for (const auto& name : c.experimentRoutes)
        for (const double w : c.experimentSpeeds) {
            const auto& t = run[k++];
            const std::string where = name + mrpt::format(" at %g rad/s", w);
            h.reached = h.reached && t.march.arrived;
            h.figures.push_back({where + ": formation", t.march.finalError(), "m", "", "", false});
            h.figures.push_back(
                {where + ": dead reckoning", t.deadReckoning.back().error, "m", "", "", true});
        }
    if (!h.reached) h.status = "Table 1, one run: a march did not arrive";
    return h;
}

FormationExperimentFile runFormationExperiment(const FormationConfig& c, const common::Log& log) {
    FormationExperimentFile f;
    if (c.pixelRuns > 0) {
        std::vector<double> lateral, longitudinal;
        f.pixel = pixelTable(c, log, lateral, longitudinal);
        const auto [lm, ls] = absMoments(lateral);
        const auto [om, os] = absMoments(longitudinal);
        f.steps.push_back({"pixel_march", lm, ls, om, os, lateral.size()});
    }
    if (c.runs == 0) return f;
    common::Progress progress("formation experiment", c.runs * marchesPerRun(c), log);
    size_t marches = 0;
    // Table 1's runs, each from its own seed (formationTrial's), summed as they come (a run
    // is dropped once summed: memory stays that of one run); then the rest from one
    // generator of the experiment's seed
    struct Cell {
        FormationExperimentFile::TableRow row;
        std::vector<double> moveError, moveTime, drError;
    };
    std::vector<Cell> cells;  // route x speed, tableRun's order
    for (const auto& name : c.experimentRoutes)
        for (const double w : c.experimentSpeeds)
            cells.push_back({FormationExperimentFile::TableRow{name, w, c.runs}, {}, {}, {}});
    const size_t every = size_t(std::lround(kCurveStep / c.deadReckoning.dt));
    for (size_t run = 0; run < c.runs; ++run) {
        const auto marchesOfRun = tableRun(c, c.experimentSeed.value + run);
        for (size_t k = 0; k < cells.size(); ++k) {
            auto& [row, moveError, moveTime, drError] = cells[k];
            const auto& m = marchesOfRun[k].march;
            const auto& d = marchesOfRun[k].deadReckoning;
            row.formation += m.finalError() / double(c.runs);
            row.deadReckoning += d.back().error / double(c.runs);
            row.moves = m.moves.size();
            row.formationTime = m.moves.empty() ? 0 : m.moves.back().time;
            row.deadReckoningTime = d.back().time;
            moveError.resize(m.moves.size()), moveTime.resize(m.moves.size());
            for (size_t i = 0; i < m.moves.size(); ++i) {
                moveError[i] += m.moves[i].error() / double(c.runs);
                moveTime[i] = m.moves[i].time;
            }
            drError.resize((d.size() - 1) / every + 1);
            for (size_t i = 0; i * every < d.size(); ++i)
                drError[i] += d[i * every].error / double(c.runs);
        }
        progress.update(marches += cells.size());
    }
    for (const auto& [row, moveError, moveTime, drError] : cells) {
        f.table.push_back(row);
        for (size_t i = 0; i < moveError.size(); ++i)
            f.curves.push_back({row.route, "formation", row.wheelSpeed, moveTime[i], moveError[i]});
        for (size_t i = 0; i < drError.size(); ++i)
            f.curves.push_back(
                {row.route, "dr", row.wheelSpeed, double(i) * kCurveStep, drError[i]});
    }
    mrpt::random::CRandomGenerator rng(common::drawSeed(c.experimentSeed.value, kFig15Draws));
    MarchOptions o = marchOptions(c);
    std::vector<double> lateral, longitudinal;  // the model's per-step errors, as drawn
    // fig. 15: the first route at the first speed, N = 4 .. max
    o.wheelSpeed = c.experimentSpeeds.front();
    const auto waypoints = route(c.experimentRoutes.front());
    for (size_t n = 4; n <= c.experimentRobotsMax; ++n) {
        FormationExperimentFile::RobotsRow row{n, c.runs};
        for (size_t run = 0; run < c.runs; ++run, progress.update(++marches))
            row.error +=
                march(n, waypoints, {}, o, c.vertexErrors, rng).finalError() / double(c.runs);
        f.robots.push_back(row);
    }
    // fig. 11: the paper's moments (60 lab runs), the model's draws, and the camera path
    f.steps.push_back({"paper", paper::kLateralMean, paper::kLateralSd, paper::kLongitudinalMean,
                       paper::kLongitudinalSd, paper::kFig11Runs});
    for (size_t k = 0; k < 100 * c.runs; ++k) {
        lateral.push_back(drawAxisError(c.vertexErrors.lateralMean, c.vertexErrors.lateralSd, rng));
        longitudinal.push_back(
            drawAxisError(c.vertexErrors.longitudinalMean, c.vertexErrors.longitudinalSd, rng));
    }
    const auto [lm, ls] = absMoments(lateral);
    const auto [om, os] = absMoments(longitudinal);
    f.steps.push_back({"model", lm, ls, om, os, lateral.size()});
    if (c.cameraStarts > 0) {  // the building step of fig. 3g from a 3 x 3 x 3 grid of starts
        MarkerOptions markers;
        const auto step = buildingStep(c.formation.side, markers);
        // the pixel mode's camera, through its camera model
        const CameraModel lens(c.cameraIntrinsics(), c.lens);
        sim::PinholeCamera camera(lens.renderIntrinsics());
        AlgorithmOneOptions ao;
        ao.side = c.formation.side;
        ao.pixelTolerance = c.pixelTolerance;
        ao.lateral = c.lateral;
        ao.noise = c.maneuverNoise;
        ao.together = c.together;
        std::vector<double> lat, lon;
        const auto& ideal = step.vertex;
        for (const double dx : {-0.15, 0.0, 0.15})
            for (const double depth : {-0.2, 0.0, 0.2})
                for (const double heading : {-10.0, 0.0, 10.0}) {
                    const mrpt::poses::CPose2D start(ideal.x() + dx, ideal.y() - depth,
                                                     ideal.phi() + heading * M_PI / 180);
                    const auto r = runAlgorithmOne(*step.scene, step.beacons, start, camera,
                                                   markers, ao, rng, &lens);
                    lat.push_back(r.end.x() - ideal.x());  // along the base
                    lon.push_back(r.end.y() - ideal.y());  // across it
                }
        const auto [cm, cs] = absMoments(lat);
        const auto [cn, cns] = absMoments(lon);
        f.steps.push_back({"camera", cm, cs, cn, cns, lat.size()});
    }
    return f;
}

std::vector<std::string> formationExperiment(const method::ExperimentOf<FormationLocalizer>& in) {
    const auto& loc = in.localizer;
    if (loc.config().runs == 0 && loc.config().pixelRuns == 0) return {};
    // the configuration read [scenario] seed, which --seed sets: in.seed is already in it
    runFormationExperiment(loc.config(), in.log).write(in.outDir);
    return {FormationExperimentFile::path(in.outDir)};
}

}  // namespace mrloc::formation
