#include <mrloc/framesync/FramesyncExperiment.h>
#include <mrloc/framesync/FramesyncLocalizer.h>
#include <mrloc/framesync/FramesyncPayload.h>
#include <mrloc/sim/Simulator.h>

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>

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
                                      const FramesyncConfig& config) {
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
    std::atomic<size_t> next{0};
    std::exception_ptr failure;
    std::mutex failureLock;
    auto worker = [&] {
        for (size_t k; (k = next++) < jobs.size();) {
            try {
                const Job& j = jobs[k];
                out.runs[k] =
                    simulateRun(scenario, config, world, slices, j.seed, j.sigma, j.drift);
                out.runs[k].kind = j.kind;
                out.runs[k].value = j.value;
            } catch (...) {
                std::lock_guard<std::mutex> lock(failureLock);
                if (!failure) failure = std::current_exception();
            }
        }
    };
    const size_t threads = std::clamp<size_t>(std::thread::hardware_concurrency(), 1, 8);
    std::vector<std::thread> pool;
    for (size_t t = 1; t < threads; ++t) pool.emplace_back(worker);
    worker();
    for (auto& t : pool) t.join();
    if (failure) std::rethrow_exception(failure);
    return out;
}

std::vector<std::string> framesyncExperiment(const method::ExperimentInput& in) {
    const auto& config = dynamic_cast<const FramesyncLocalizer&>(in.localizer).config();
    if (!in.ini.sectionExists("scenario")) return {};  // a log recorded elsewhere: no scenario
    if (config.experimentSeeds == 0 &&
        (config.sweepSeeds == 0 || (config.sweepNoise.empty() && config.sweepDrift.empty())))
        return {};
    const auto file = runExperiment(sim::ScenarioConfig::load(in.ini), config);
    file.write(in.outDir);
    return {FramesyncExperimentFile::path(in.outDir)};
}

}  // namespace mrloc::framesync
