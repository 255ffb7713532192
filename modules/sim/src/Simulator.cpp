#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/OdometryPath.h>
#include <mrloc/common/Trajectory.h>
#include <mrloc/sim/Sensors.h>
#include <mrloc/sim/Simulator.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace mrloc::sim {

Fleet::Fleet(const std::vector<RobotOptions>& robots)
    : previous_(robots.size()), speed_(robots.size(), 0.0) {
    robots_.reserve(robots.size());
    for (const auto& r : robots) robots_.emplace_back(r);
}

size_t Fleet::indexOf(const std::string& name) const {
    for (size_t i = 0; i < robots_.size(); ++i)
        if (robots_[i].options().name == name) return i;
    throw Error("simulation: there is no robot '" + name + "'");
}

std::vector<mrpt::poses::CPose2D> Fleet::poses() const {
    std::vector<mrpt::poses::CPose2D> out;
    for (const auto& r : robots_) out.push_back(r.pose());
    return out;
}

Simulator::Simulator(ScenarioConfig config)
    : config_(std::move(config)), world_(std::make_shared<const World>(config_.world)) {}

Simulator::Simulator(ScenarioConfig config, std::shared_ptr<const World> world)
    : config_(std::move(config)), world_(std::move(world)) {}

SimulationResult Simulator::run(common::RawlogWriter& out, Payload* payload,
                                common::Progress* progress) {
    return run([&out](const mrpt::obs::CObservation& obs) { out.write(obs); }, payload, progress);
}

SimulationResult Simulator::run(const std::function<void(const mrpt::obs::CObservation&)>& write,
                                Payload* payload, common::Progress* progress) {
    const auto& sc = config_.scenario;
    mrpt::random::CRandomGenerator rng(uint32_t(sc.seed));
    Fleet fleet(config_.robots);
    std::vector<OdometrySensor> odometers;
    std::vector<long> odometryEvery;
    std::vector<common::OdometryPath> odometryPaths(fleet.size());
    odometers.reserve(fleet.size());
    const auto every = [&](double rate) {
        return std::max<long>(1, std::lround(1.0 / (rate * sc.dt)));
    };
    for (size_t i = 0; i < fleet.size(); ++i) {
        odometers.emplace_back(fleet.robot(i).options(), rng, sc.odometryErrorScale);
        odometryEvery.push_back(every(config_.robots[i].odometryRate));
    }
    const long steps = std::lround(sc.duration / sc.dt);
    const long gtEvery = every(sc.groundTruthRate);

    SimulationResult result;
    const std::function<void(const mrpt::obs::CObservation::Ptr&)> emit =
        [&](const mrpt::obs::CObservation::Ptr& obs) {
            write(*obs);
            ++result.observations;
            if (payload) payload->onObservation(obs);
        };
    for (long k = 0; k <= steps; ++k) {
        const double t = double(k) * sc.dt;
        const auto stamp = mrpt::Clock::fromDouble(sc.startTime + t);
        Step step{k, t, sc.dt, sc.startTime, stamp, fleet, *world_, rng, emit};
        if (payload) payload->command(step);
        for (size_t i = 0; i < fleet.size(); ++i) {
            Robot& robot = fleet.robot(i);
            const auto& ro = robot.options();
            fleet.previous_[i] = robot.pose();
            if (k > 0 && !robot.halted()) odometers[i].accumulate(robot.step(sc.dt, rng), rng);
            if (k % odometryEvery[i] == 0) {
                auto odo = odometers[i].read(ro.name + ".odom", stamp);
                odometryPaths[i].add(t, odo->odometry);
                fleet.speed_[i] = odometryPaths[i].speed().value_or(0.0);
                emit(odo);
            }
            if (k % gtEvery == 0)
                result.groundTruth[ro.name].push_back(
                    {mrpt::Clock::toDouble(stamp), mrpt::poses::CPose3D(robot.pose())});
        }
        if (payload) payload->sense(step);
        if (progress) progress->update(size_t(k));
    }
    return result;
}

SimulatedFiles simulateToFiles(const ScenarioConfig& config, const std::string& dir,
                               const common::Log& log, Payload* payload) {
    common::makeDirectories(dir);
    SimulatedFiles files;
    files.rawlog = dir + "/" + config.scenario.name + ".rawlog";
    Simulator sim(config);
    common::RawlogWriter writer(files.rawlog);
    common::Progress progress(
        "simulating", size_t(std::lround(config.scenario.duration / config.scenario.dt)), log);
    const auto result = sim.run(writer, payload, &progress);
    progress.finish();
    files.all.push_back(files.rawlog);
    try {
        for (const auto& [robot, traj] : result.groundTruth) {
            files.all.push_back(common::groundTruthPath(files.rawlog, robot));
            common::saveTum(files.all.back(), traj);
        }
        if (payload)
            for (const auto& f : payload->finish(files.rawlog)) files.all.push_back(f);
        writer.commit();
    } catch (...) {
        for (size_t i = 1; i < files.all.size(); ++i) std::filesystem::remove(files.all[i]);
        throw;
    }
    return files;
}

}  // namespace mrloc::sim
