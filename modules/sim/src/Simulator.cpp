#include <mrloc/common/AtomicFile.h>
#include <mrloc/sim/Simulator.h>
#include <mrpt/random/RandomGenerators.h>

#include <cmath>

namespace mrloc::sim {

Simulator::Simulator(ScenarioConfig config) : config_(std::move(config)), world_(config_.world) {}

SimulationResult Simulator::run(common::RawlogWriter& out, common::Progress* progress) {
    const auto& sc = config_.scenario;
    mrpt::random::CRandomGenerator rng(uint32_t(sc.seed));
    std::vector<Robot> robots;
    std::vector<OdometrySensor> odometers;
    robots.reserve(config_.robots.size());
    odometers.reserve(config_.robots.size());
    for (const auto& r : config_.robots) {
        robots.emplace_back(r);
        odometers.emplace_back(robots.back().options());
    }
    const BeaconRanger ranger(world_, config_.beacons, config_.sensors);
    const auto every = [&](double rate) {
        return std::max<long>(1, std::lround(1.0 / (rate * sc.dt)));
    };
    const long steps = std::lround(sc.duration / sc.dt);
    const long gtEvery = every(sc.groundTruthRate);
    std::vector<long> odometryEvery, beaconEvery;  // sensor periods in steps, per robot
    for (const auto& r : robots) {
        odometryEvery.push_back(every(r.options().odometryRate));
        beaconEvery.push_back(every(r.options().beaconRate));
    }

    SimulationResult result;
    for (long k = 0; k <= steps; ++k) {
        const double t = double(k) * sc.dt;
        const auto stamp = mrpt::Clock::fromDouble(sc.startTime + t);
        for (size_t i = 0; i < robots.size(); ++i) {
            Robot& robot = robots[i];
            const auto& ro = robot.options();
            if (k > 0) odometers[i].accumulate(robot.step(sc.dt), rng);
            if (k % odometryEvery[i] == 0) {
                out.write(*odometers[i].read(ro.name + ".odom", stamp));
                ++result.observations;
            }
            if (k % beaconEvery[i] == 0) {
                out.write(
                    *ranger.read(ro.name + ".beacons", stamp, robot.pose(), ro.receiver, rng));
                ++result.observations;
            }
            if (k % gtEvery == 0)
                result.groundTruth[ro.name].push_back(
                    {mrpt::Clock::toDouble(stamp), mrpt::poses::CPose3D(robot.pose())});
        }
        if (progress) progress->update(size_t(k));
    }
    return result;
}

std::string simulateToFiles(const ScenarioConfig& config, const std::string& dir, bool quiet) {
    common::makeDirectories(dir);
    const std::string path = dir + "/" + config.scenario.name + ".rawlog";
    Simulator sim(config);
    common::RawlogWriter writer(path);
    common::Progress progress(
        "simulating", size_t(std::lround(config.scenario.duration / config.scenario.dt)), quiet);
    const auto result = sim.run(writer, &progress);
    progress.finish();
    for (const auto& [robot, traj] : result.groundTruth)
        common::saveTum(common::groundTruthPath(path, robot), traj);
    writer.commit();
    return path;
}

}  // namespace mrloc::sim
