#include <mrloc/common/Progress.h>
#include <mrloc/formation/AlgorithmOne.h>
#include <mrloc/formation/FormationExperiment.h>
#include <mrloc/formation/FormationLocalizer.h>
#include <mrloc/formation/Routes.h>
#include <mrpt/core/format.h>

#include <cmath>

namespace mrloc::formation {

namespace {

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

}  // namespace

FormationExperimentFile runFormationExperiment(const FormationConfig& c, bool quiet) {
    FormationExperimentFile f;
    if (c.runs == 0) return f;
    common::Progress progress("formation experiment", c.runs * marchesPerRun(c), quiet);
    size_t marches = 0;
    mrpt::random::CRandomGenerator rng(uint32_t(c.experimentSeed));
    MarchOptions o;
    o.formation = c.formation;
    o.wheelRadius = c.wheelRadius;
    o.maxMoves = c.maxMoves;
    o.carry = c.carry;
    std::vector<double> lateral, longitudinal;  // the model's per-step errors, as drawn
    for (const auto& name : c.experimentRoutes) {
        const auto waypoints = route(name);
        for (const double w : c.experimentSpeeds) {
            o.wheelSpeed = w;
            FormationExperimentFile::TableRow row{name, w, c.runs};
            std::vector<double> moveError, drError;
            std::vector<double> moveTime;
            for (size_t run = 0; run < c.runs; ++run) {
                const auto m = march(c.robots, waypoints, {}, o, c.vertexErrors, rng);
                const auto d = deadReckon(waypoints, c.wheelRadius, w, c.deadReckoning, rng);
                progress.update(++marches);
                row.formation += m.finalError() / double(c.runs);
                row.deadReckoning += d.back().error / double(c.runs);
                row.moves = m.moves.size();
                row.formationTime = m.moves.empty() ? 0 : m.moves.back().time;
                row.deadReckoningTime = d.back().time;
                moveError.resize(m.moves.size()), moveTime.resize(m.moves.size());
                for (size_t k = 0; k < m.moves.size(); ++k) {
                    moveError[k] += m.moves[k].error() / double(c.runs);
                    moveTime[k] = m.moves[k].time;
                }
                const size_t every = size_t(std::lround(kCurveStep / c.deadReckoning.dt));
                drError.resize((d.size() - 1) / every + 1);
                for (size_t k = 0; k * every < d.size(); ++k)
                    drError[k] += d[k * every].error / double(c.runs);
            }
            f.table.push_back(row);
            for (size_t k = 0; k < moveError.size(); ++k)
                f.curves.push_back({name, "formation", w, moveTime[k], moveError[k]});
            for (size_t k = 0; k < drError.size(); ++k)
                f.curves.push_back({name, "dr", w, double(k) * kCurveStep, drError[k]});
        }
    }
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
        sim::PinholeCamera camera(cameraIntrinsics(c.cameraFocal));
        AlgorithmOneOptions ao;
        ao.side = c.formation.side;
        ao.pixelTolerance = c.pixelTolerance;
        ao.lateral = c.lateral;
        ao.noise = c.maneuverNoise;
        std::vector<double> lat, lon;
        const auto& ideal = step.vertex;
        for (const double dx : {-0.15, 0.0, 0.15})
            for (const double depth : {-0.2, 0.0, 0.2})
                for (const double heading : {-10.0, 0.0, 10.0}) {
                    const mrpt::poses::CPose2D start(ideal.x() + dx, ideal.y() - depth,
                                                     ideal.phi() + heading * M_PI / 180);
                    const auto r =
                        runAlgorithmOne(*step.scene, step.beacons, start, camera, markers, ao, rng);
                    lat.push_back(r.end.x() - ideal.x());  // along the base
                    lon.push_back(r.end.y() - ideal.y());  // across it
                }
        const auto [cm, cs] = absMoments(lat);
        const auto [cn, cns] = absMoments(lon);
        f.steps.push_back({"camera", cm, cs, cn, cns, lat.size()});
    }
    return f;
}

std::vector<method::WorkItem> formationWork(const FormationLocalizer& localizer,
                                            const sim::ScenarioConfig* scenario) {
    const auto& c = localizer.config();
    // Measured (doc/errors.md, "Work"): about 1 ms per error-model march of 4 robots along
    // the many-turns route (113 m), dead reckoning included, growing about as N; 0.17 s per
    // camera start (Algorithm 1 on rendered frames); the pixel mode's simulation 150 us per
    // robot and step (formation_pixel.ini: 6,000 steps, 5 robots, 4.4 s).
    constexpr double kSecondsPerMarchMetre = 1e-3 / 113, kSecondsPerCameraStart = 0.17;
    constexpr double kPixelSecondsPerRobotStep = 1.5e-4;
    const auto length = [](const std::string& name) {
        const auto w = route(name);
        double m = 0;
        for (size_t i = 1; i < w.size(); ++i) m += (w[i] - w[i - 1]).norm();
        return m;
    };
    std::vector<method::WorkItem> out;
    if (scenario && c.mode == FormationConfig::Mode::Pixel) {
        method::WorkItem w;
        w.what = "the pixel mode's rendered frames";
        w.keys = "[formation] mode = pixel, [scenario] duration / dt x robots";
        w.seconds = scenario->scenario.duration / scenario->scenario.dt * double(c.robots + 1) *
                    kPixelSecondsPerRobotStep;
        w.simulation = true;
        out.push_back(w);
    }
    if (c.runs == 0) return out;
    double marchMetres = 0;  // Table 1 and fig. 14, then fig. 15 on the first route
    for (const auto& name : c.experimentRoutes)
        marchMetres += double(c.experimentSpeeds.size()) * length(name) * double(c.robots) / 4;
    for (size_t n = 4; n <= c.experimentRobotsMax; ++n)
        marchMetres += length(c.experimentRoutes.front()) * double(n) / 4;
    method::WorkItem e;
    e.what = mrpt::format("the experiment's %zu x %zu marches", c.runs, marchesPerRun(c));
    e.keys =
        "[formation] runs x (experiment_routes x experiment_speeds + "
        "experiment_robots_max - 3)";
    e.seconds = double(c.runs) * marchMetres * kSecondsPerMarchMetre +
                (c.cameraStarts > 0 ? double(kCameraGridStarts) * kSecondsPerCameraStart : 0);
    out.push_back(e);
    return out;
}

std::vector<std::string> formationExperiment(const method::ExperimentOf<FormationLocalizer>& in) {
    const auto& loc = in.localizer;
    if (loc.config().runs == 0) return {};
    FormationConfig config = loc.config();
    if (!config.experimentSeedGiven) config.experimentSeed = in.seed;
    runFormationExperiment(config, in.quiet).write(in.outDir);
    return {FormationExperimentFile::path(in.outDir)};
}

}  // namespace mrloc::formation
