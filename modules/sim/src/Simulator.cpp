#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/sim/BeaconRanging.h>
#include <mrloc/sim/OmniCamera.h>
#include <mrloc/sim/Simulator.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/obs/CObservationImage.h>
#include <mrpt/obs/CObservationRange.h>
#include <mrpt/random/RandomGenerators.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace mrloc::sim {

namespace {

/** What the simulator keeps per robot besides its kinematics. */
struct RobotState {
    long odometryEvery = 1;  ///< odometry period in steps
    double minEpochGap = 0;  ///< 1 / beacon_rate
    double lastEpoch = -std::numeric_limits<double>::infinity();
    long epochs = 0;
    double speed = 0;  ///< from the last two odometry readings
    std::optional<std::pair<double, mrpt::poses::CPose2D>> previousOdometry;
};

}  // namespace

Simulator::Simulator(ScenarioConfig config) : config_(std::move(config)), world_(config_.world) {}

SimulationResult Simulator::run(common::RawlogWriter& out, SimulationHooks hooks,
                                common::Progress* progress) {
    const auto& sc = config_.scenario;
    mrpt::random::CRandomGenerator rng(uint32_t(sc.seed));
    std::vector<Robot> robots;
    std::vector<OdometrySensor> odometers;
    std::vector<RobotState> state(config_.robots.size());
    robots.reserve(config_.robots.size());
    odometers.reserve(config_.robots.size());
    const auto every = [&](double rate) {
        return std::max<long>(1, std::lround(1.0 / (rate * sc.dt)));
    };
    for (size_t i = 0; i < config_.robots.size(); ++i) {
        robots.emplace_back(config_.robots[i]);
        odometers.emplace_back(robots.back().options());
        state[i].odometryEvery = every(config_.robots[i].odometryRate);
        state[i].minEpochGap = 1.0 / config_.robots[i].beaconRate;
    }
    const auto indexOf = [&](const std::string& name) {
        for (size_t i = 0; i < robots.size(); ++i)
            if (robots[i].options().name == name) return i;
        throw Error("ranging: the controller chose robot '" + name + "', which does not exist");
    };
    BeaconRanging ranging(world_, config_.beacons, config_.sensors, config_.ultrasonic);
    const long steps = std::lround(sc.duration / sc.dt);
    const long gtEvery = every(sc.groundTruthRate);
    const auto& plan = config_.floorPlan;
    const long scanEvery = plan && plan->scanner.rate > 0 ? every(plan->scanner.rate) : 0;
    double channelFree = 0;
    const auto& omni = config_.omni;
    std::unique_ptr<OmniRenderer> renderer;
    if (omni && omni->camera.render) renderer = std::make_unique<OmniRenderer>(omni->camera);
    const auto stopped = [&](const std::string& robot, double t) {
        if (!omni) return false;
        for (const auto& st : omni->stops)
            if (st.robot == robot && t > st.from + 1e-9 && t <= st.to + 1e-9) return true;
        return false;
    };
    const auto snapshotAt = [&](double t) {
        if (!omni) return false;
        for (double ts : omni->snapshotTimes)
            if (std::abs(t - ts) < 0.5 * sc.dt) return true;
        return false;
    };

    SimulationResult result;
    const auto emit = [&](const mrpt::obs::CObservation::Ptr& obs) {
        out.write(*obs);
        ++result.observations;
        if (hooks.onboard) hooks.onboard->process(obs);
    };
    std::vector<mrpt::poses::CPose2D> previousPose(robots.size());
    size_t epochRobot = 0;  // index of the robot the current epoch serves
    const auto fireDue = [&](double t) {
        if (!ranging.inEpoch()) return;
        const size_t i = epochRobot;
        const Robot& robot = robots[i];
        // A shot falls between two steps: the receiver is where the robot was at that time.
        const auto receiverAtTime = [&](double when) {
            const double a = std::clamp(1.0 - (t - when) / sc.dt, 0.0, 1.0);
            const auto& p0 = previousPose[i];
            const auto& p1 = robot.pose();
            const mrpt::poses::CPose2D p(p0.x() + a * (p1.x() - p0.x()),
                                         p0.y() + a * (p1.y() - p0.y()),
                                         p0.phi() + a * mrpt::math::wrapToPi(p1.phi() - p0.phi()));
            return receiverAt(p, robot.options().receiver);
        };
        auto obs = ranging.fireDue(t, receiverAtTime, robot.options().receiver, rng, result.shots);
        if (!obs) return;
        obs->sensorLabel = robot.options().name + ".beacons";
        obs->timestamp = mrpt::Clock::fromDouble(sc.startTime + ranging.lastShotTime());
        emit(obs);
    };
    // What a robot tells the RF beacon: the receiver where its own estimate puts it (its
    // configured start before the first estimate: robots start at a surveyed spot).
    const auto report = [&](size_t i) {
        const Robot& robot = robots[i];
        const auto& ro = robot.options();
        common::RobotReport r;
        r.robot = ro.name;
        r.speed = state[i].speed;
        std::optional<mrpt::poses::CPose3D> est;
        if (hooks.onboard) est = hooks.onboard->latestEstimate(ro.name);
        const mrpt::poses::CPose2D believed =
            est ? mrpt::poses::CPose2D(est->x(), est->y(), est->yaw()) : ro.start;
        r.receiver = receiverAt(believed, ro.receiver);
        return r;
    };

    for (long k = 0; k <= steps; ++k) {
        const double t = double(k) * sc.dt;
        const auto stamp = mrpt::Clock::fromDouble(sc.startTime + t);
        for (size_t i = 0; i < robots.size(); ++i) {
            Robot& robot = robots[i];
            const auto& ro = robot.options();
            previousPose[i] = robot.pose();
            // A robot told to stand still (seed 000: the pair that stops) does not move.
            if (k > 0 && !stopped(ro.name, t)) odometers[i].accumulate(robot.step(sc.dt), rng);
            if (k % state[i].odometryEvery == 0) {
                auto odo = odometers[i].read(ro.name + ".odom", stamp);
                if (state[i].previousOdometry) {
                    const auto& [t0, p0] = *state[i].previousOdometry;
                    state[i].speed =
                        std::hypot(odo->odometry.x() - p0.x(), odo->odometry.y() - p0.y()) /
                        (t - t0);
                }
                state[i].previousOdometry = std::make_pair(t, odo->odometry);
                emit(odo);
            }
            if (plan && (k == 0 || (scanEvery > 0 && k % scanEvery == 0))) {
                auto scan = scanFloorPlan(plan->polygon, robot.pose(), plan->scanner, rng);
                scan->sensorLabel = ro.name + ".scan";
                scan->timestamp = stamp;
                emit(scan);
            }
            if (k % gtEvery == 0)
                result.groundTruth[ro.name].push_back(
                    {mrpt::Clock::toDouble(stamp), mrpt::poses::CPose3D(robot.pose())});
        }
        if (snapshotAt(t)) {  // every omni-directional camera fires at once
            std::vector<mrpt::poses::CPose2D> poses;
            for (const auto& r : robots) poses.push_back(r.pose());
            for (size_t i = 0; i < robots.size(); ++i) {
                const std::string& name = robots[i].options().name;
                mrpt::obs::CObservation::Ptr obs;
                if (renderer) {
                    auto img = mrpt::obs::CObservationImage::Create();
                    img->image = renderer->render(poses, i);
                    img->cameraPose =
                        mrpt::poses::CPose3D(0, 0, omni->camera.cameraHeight, 0, 0, 0);
                    img->sensorLabel = name + ".omni";
                    obs = img;
                } else {
                    obs = senseBearings(poses, i, omni->camera, rng);
                    obs->sensorLabel = name + ".omni_bearings";
                }
                obs->timestamp = stamp;
                emit(obs);
            }
            if (omni->lidar) {  // the conventional method's one measured distance
                const auto& l = *omni->lidar;
                const auto& a = robots[indexOf(l.from)].pose();
                const auto& b = robots[indexOf(l.to)].pose();
                auto range = mrpt::obs::CObservationRange::Create();
                range->sensorLabel = l.from + ".lidar." + l.to;
                range->timestamp = stamp;
                range->minSensorDistance = 0;
                range->maxSensorDistance = 1e3;
                mrpt::obs::CObservationRange::TMeasurement m;
                m.sensorID = 0;
                m.sensedDistance = float(std::hypot(b.x() - a.x(), b.y() - a.y()) +
                                         rng.drawGaussian1D(0, l.sigma));
                range->sensedData.push_back(m);
                emit(range);
            }
        }
        fireDue(t);
        if (hooks.ranging && !ranging.inEpoch() && t >= channelFree - 1e-9) {
            std::vector<common::RobotReport> requests;
            for (size_t i = 0; i < robots.size(); ++i) {
                const long cap = robots[i].options().rangingEpochs;
                if (t - state[i].lastEpoch >= state[i].minEpochGap - 1e-9 &&
                    (cap == 0 || state[i].epochs < cap))
                    requests.push_back(report(i));
            }
            if (!requests.empty())
                if (const auto epoch = hooks.ranging->nextEpoch(t, requests)) {
                    const size_t i = epochRobot = indexOf(epoch->robot);
                    state[i].lastEpoch = t;
                    ++state[i].epochs;
                    channelFree = ranging.begin(t, *epoch);
                    fireDue(t);  // heads already aimed: the first shot leaves now
                }
        }
        if (progress) progress->update(size_t(k));
    }
    return result;
}

std::string simulateToFiles(const ScenarioConfig& config, const std::string& dir, bool quiet,
                            SimulationHooks hooks) {
    common::makeDirectories(dir);
    const std::string path = dir + "/" + config.scenario.name + ".rawlog";
    Simulator sim(config);
    common::RawlogWriter writer(path);
    common::Progress progress(
        "simulating", size_t(std::lround(config.scenario.duration / config.scenario.dt)), quiet);
    const auto result = sim.run(writer, hooks, &progress);
    progress.finish();
    for (const auto& [robot, traj] : result.groundTruth)
        common::saveTum(common::groundTruthPath(path, robot), traj);
    saveShotLog(shotLogPath(path), result.shots);
    writer.commit();
    return path;
}

}  // namespace mrloc::sim
