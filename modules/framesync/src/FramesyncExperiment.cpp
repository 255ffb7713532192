#include <mrloc/common/ParallelFor.h>
#include <mrloc/common/Progress.h>
#include <mrloc/framesync/FramesyncExperiment.h>
#include <mrloc/framesync/FramesyncLocalizer.h>
#include <mrloc/framesync/FramesyncPayload.h>
#include <mrloc/sim/Simulator.h>
#include <mrpt/core/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>

namespace mrloc::framesync {

ExperimentRun simulateRun(const sim::ScenarioConfig& scenario, const FramesyncConfig& config,
                          const std::shared_ptr<const sim::World>& world,
                          const std::shared_ptr<const FloorSlices>& slices, unsigned long seed,
                          double sigma, double drift) {
    sim::ScenarioConfig sc = scenario;
    sc.scenario.seed = seed;
    for (auto& r : sc.robots) {
        r.odometryScaleError *= drift, r.odometryScaleErrorSigma *= drift;
        r.odometryHeadingDrift *= drift, r.odometryHeadingDriftSigma *= drift;
    }
    FramesyncConfig c = config;
    // a noisier sonar is set up to match, as a user would from its datasheet: ERP pairs
    // further apart (the normal's noise is about sqrt(2) sd / baseline) and a looser bound
    // on the residuals (4 sd)
    auto& d = c.team.detector;
    d.baseline = std::max(config.team.detector.baseline, 20 * sigma);
    d.maxPairGap = std::max(d.maxPairGap, 5 * d.baseline);
    d.maxResidual = std::max(config.team.detector.maxResidual, 4 * sigma);
    c.rig.sigma = sigma;
    FramesyncPayload payload(c, sc.scenario.dt, slices);
    sim::Simulator simulator(sc, world);
    const auto result = simulator.run([](const mrpt::obs::CObservation&) {}, &payload);
    const auto& team = payload.team();
    ExperimentRun run;
    run.seed = seed;
    std::tie(run.sharedError, run.odometryError) =
        meanPairErrors(endFigures(team.estimates(), team.odometry(), result.groundTruth));
    for (const auto& [name, node] : team.robots()) run.walls += node->walls().size();
    run.redefinitions = team.events().size();
    return run;
}

FramesyncExperimentFile runExperiment(const sim::ScenarioConfig& scenario,
                                      const FramesyncConfig& config, const common::Log& log) {
    struct Job {
        std::string kind;
        double value, sigma, drift;
        unsigned long seed;
    };
    std::vector<Job> jobs;
    const unsigned long first = scenario.scenario.seed;
    for (size_t i = 0; i < config.experimentSeeds; ++i)
        jobs.push_back({"paper", config.rig.sigma, config.rig.sigma, 1.0, first + i});
    for (const double sigma : config.sweepNoise)
        for (size_t i = 0; i < config.sweepSeeds; ++i)
            jobs.push_back({"noise", sigma, sigma, 1.0, first + i});
    for (const double drift : config.sweepDrift)
        for (size_t i = 0; i < config.sweepSeeds; ++i)
            jobs.push_back({"drift", drift, config.rig.sigma, drift, first + i});
    const auto world = std::make_shared<const sim::World>(scenario.world);
    const auto slices = sliceWorld(*world, config.rig);
    FramesyncExperimentFile out;
    out.runs.resize(jobs.size());
    std::atomic<size_t> done{0};
    common::Progress progress("framesync experiment", jobs.size(), log);
    // the calling thread draws the bar between its runs (Progress is not shared)
    common::parallelFor(
        jobs.size(),
        [&](size_t k) {
            const Job& j = jobs[k];
            out.runs[k] = simulateRun(scenario, config, world, slices, j.seed, j.sigma, j.drift);
            out.runs[k].kind = j.kind;
            out.runs[k].value = j.value;
            ++done;
        },
        [&] { progress.update(done); });
    return out;
}

common::Headline framesyncTrial(const method::TrialOf<FramesyncLocalizer>& in) {
    const auto& config = in.localizer.config();
    // a batch job's trials share the world and its slices, as the experiment's runs do
    const auto world = sim::sharedWorld(in.scenario.world);
    const auto run = simulateRun(in.scenario, config, world, sharedSlices(world, config.rig),
                                 in.scenario.scenario.seed, config.rig.sigma, 1.0);
    common::Headline h;
    h.reached = !config.team.sharing || run.redefinitions > 0;
    h.status = !config.team.sharing ? "frames kept apart ([framesync] sharing = false)"
               : h.reached          ? "one frame shared"
                                    : "no frame shared";
    // the names of the run's headline (FramesyncMethod.cpp), whose first two are these
    const auto value = [](double v) {
        return std::isfinite(v) ? std::optional<double>(v) : std::nullopt;
    };
    h.figures.push_back(
        {"end discrepancy, shared frame", value(run.sharedError), "m", "", "", false});
    h.figures.push_back({"own odometry", value(run.odometryError), "m", "", "", true});
    h.figures.push_back({"walls", double(run.walls), "", "", "", false});
    h.figures.push_back({"redefinitions", double(run.redefinitions), "", "", "", false});
    return h;
}

std::vector<method::WorkItem> framesyncWork(const FramesyncLocalizer& localizer,
                                            const sim::ScenarioConfig* scenario) {
    if (!scenario) return {};
    const auto& c = localizer.config();
    // Measured (doc/errors.md, "Work"): the corridor's 2 robots over 10,000 s of log (1e6
    // steps) simulate in 9.1 s, 4.5 us per robot and step, sonars and on-board team included.
    constexpr double kSecondsPerRobotStep = 5e-6;
    const double robotSteps = scenario->scenario.duration / scenario->scenario.dt *
                              double(std::max<size_t>(1, scenario->robots.size()));
    std::vector<method::WorkItem> out;
    method::WorkItem sonars;
    sonars.what = "the sonars' simulation";
    sonars.keys = "[scenario] duration / dt x robots";
    sonars.seconds = robotSteps * kSecondsPerRobotStep;
    sonars.simulation = true;
    out.push_back(sonars);
    const double runs = double(c.experimentSeeds) +
                        double(c.sweepSeeds) * double(c.sweepNoise.size() + c.sweepDrift.size());
    if (runs > 0) {
        method::WorkItem e;
        e.what = mrpt::format("the experiment's %.0f simulated runs", runs);
        e.keys =
            "[framesync] experiment_seeds + experiment_sweep_seeds x (experiment_noise + "
            "experiment_drift values), each [scenario] duration / dt x robots";
        e.seconds = runs * robotSteps * kSecondsPerRobotStep;
        e.parallel = true;  // runExperiment's pool
        out.push_back(e);
    }
    return out;
}

std::vector<std::string> framesyncExperiment(const method::ExperimentOf<FramesyncLocalizer>& in) {
    const auto& config = in.localizer.config();
    if (!in.scenario) return {};  // a log recorded elsewhere: no scenario to simulate again
    if (config.experimentSeeds == 0 &&
        (config.sweepSeeds == 0 || (config.sweepNoise.empty() && config.sweepDrift.empty())))
        return {};
    const auto file = runExperiment(*in.scenario, config, in.log);
    file.write(in.outDir);
    return {FramesyncExperimentFile::path(in.outDir)};
}

}  // namespace mrloc::framesync
