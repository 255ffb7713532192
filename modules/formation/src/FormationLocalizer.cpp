#include <mrloc/common/Error.h>
#include <mrloc/common/Names.h>
#include <mrloc/formation/DeadReckoning.h>
#include <mrloc/formation/FormationFiles.h>
#include <mrloc/formation/FormationLocalizer.h>
#include <mrloc/formation/FormationPayload.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/obs/CObservationComment.h>
#include <mrpt/obs/CObservationOdometry.h>

#include <algorithm>
#include <cmath>

namespace mrloc::formation {

namespace {

mrpt::poses::CPose3D pose3(const TPoint2D& p, double heading) {
    return mrpt::poses::CPose3D(p.x, p.y, 0, heading, 0, 0);
}

const char* stateName(Team::State s) {
    switch (s) {
        case Team::State::Waiting:
            return "waiting";
        case Team::State::Moving:
            return "moving";
        case Team::State::Arrived:
            return "arrived";
        case Team::State::Stuck:
            return "stuck";
    }
    return "?";
}

}  // namespace

void FormationLocalizer::configure(const mrpt::config::CConfigFileBase& ini) {
    config_.loadFromConfigFile(ini, "formation");
    team_.emplace(teamOptions(config_));
    estimates_.clear();
    track_.clear();
    moveStart_.clear();
    moveFrom_.clear();
    lastReading_.clear();
    lastArrival_ = lastTime_ = -1;
    deadReckoned_.reset();
    cameraLostMoves_ = 0;
}

void FormationLocalizer::saveConfig(mrpt::config::CConfigFileBase& target) const {
    config_.saveToConfigFile(target, "formation");
}

void FormationLocalizer::process(const mrpt::obs::CObservation::Ptr& obs) {
    const double t = mrpt::Clock::toDouble(obs->timestamp);
    if (const auto c = std::dynamic_pointer_cast<mrpt::obs::CObservationComment>(obs);
        c && isLostBeaconsText(c->text))
        ++cameraLostMoves_;
    if (obs->sensorLabel == kDeadReckoningLabel) {
        const auto odo = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(obs);
        if (!odo || !odo->hasVelocities)
            throw Error("formation: " + obs->sensorLabel +
                        " must be a CObservationOdometry with velocities (sensed speed)");
        const double heading = odo->odometry.phi(), speed = odo->velocityLocal.vx;
        // the dead-reckoning robot's own integration (DeadReckoner::advance), from its start
        deadReckoned_ = deadReckoned_ ? DeadReckoner::advance(*deadReckoned_, heading, speed,
                                                              config_.deadReckoning.dt)
                                      : config_.worldRoute().front();
        estimates_[kDeadReckoningRobot].push_back({t, pose3(*deadReckoned_, heading)});
        track_[kDeadReckoningRobot].push_back(estimates_[kDeadReckoningRobot].back());
        lastTime_ = std::max(lastTime_, t);
        return;
    }
    {  // what observationUse counts: the team's kinds of observation, and whose they are
        const auto comment = std::dynamic_pointer_cast<mrpt::obs::CObservationComment>(obs);
        const auto [name, sensor] =
            common::parseSensorLabel(comment ? arrivedLabel(comment->text) : obs->sensorLabel);
        if (sensor == "obstacles" || sensor == "arrived") {
            ++teamSeen_;
            teamUsed_ += team_->indexOf(name).has_value();
        }
    }
    const size_t before = team_->moves().size();
    const auto robot = [&]() -> std::optional<size_t> {
        const auto dot = obs->sensorLabel.rfind('.');
        return dot == std::string::npos ? std::nullopt
                                        : team_->indexOf(obs->sensorLabel.substr(0, dot));
    }();
    const bool firstSighting =
        robot && !estimates_.count(team_->options().names[*robot]) &&
        obs->sensorLabel.size() > 10 &&
        obs->sensorLabel.compare(obs->sensorLabel.size() - 10, 10, ".obstacles") == 0;
    team_->observe(obs);
    lastTime_ = std::max(lastTime_, t);
    noteMotion(obs, t);
    if (firstSighting) {  // the start: where the strip puts it
        const std::string& name = team_->options().names[*robot];
        estimates_[name].push_back(
            {t, pose3(team_->believed()[*robot], team_->believedHeading(*robot))});
        track_[name].push_back(estimates_[name].back());
        lastArrival_ = std::max(lastArrival_, t);
    }
    if (team_->moves().size() > before) {
        const size_t r = team_->moves().back().move.robot;
        const std::string& name = team_->options().names[r];
        auto& track = track_[name];
        // it stood where it was until its odometry first moved (else, one robot moving at a
        // time in seed 003 Algorithm 2, until the team's previous arrival), and moved from there
        const auto started = moveStart_.find(name);
        const double from = started != moveStart_.end() ? started->second : lastArrival_;
        if (!track.empty() && from > track.back().t && from < t)
            track.push_back({from, track.back().pose});
        moveStart_.erase(name);
        estimates_[name].push_back({t, pose3(team_->believed()[r], team_->believedHeading(r))});
        // the vertex replaces the odometry's pose of the same instant
        if (!track.empty() && track.back().t >= t - 1e-6) track.pop_back();
        track.push_back(estimates_[name].back());
        lastArrival_ = t;
    }
}

void FormationLocalizer::noteMotion(const mrpt::obs::CObservation::Ptr& obs, double t) {
    const auto odo = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(obs);
    const auto [name, sensor] = common::parseSensorLabel(obs->sensorLabel);
    if (!odo || sensor != "odom" || !team_->indexOf(name)) return;
    // at rest: the odometry does not change between two readings (to 1e-6 m and rad; its
    // noise grows with the motion, none while the robot stands)
    constexpr double kAtRest = 1e-6;
    const auto last = lastReading_.find(name);
    const bool moving =
        last != lastReading_.end() &&
        (std::abs(odo->odometry.x() - last->second.pose.x()) > kAtRest ||
         std::abs(odo->odometry.y() - last->second.pose.y()) > kAtRest ||
         std::abs(mrpt::math::wrapToPi(odo->odometry.phi() - last->second.pose.phi())) > kAtRest);
    auto& track = track_[name];
    if (track.empty()) {  // not seen yet: the team places it at its first scan
        lastReading_[name] = {t, odo->odometry, moving};
        return;
    }
    if (moving && !moveStart_.count(name)) {
        // the move begins: from the held estimate, at the reading before
        moveStart_[name] = last->second.t;
        moveFrom_[name] = {mrpt::poses::CPose2D(track.back().pose), last->second.pose};
    }
    // at rest the robot is where the team placed it; during a move it knows only its
    // odometry (seed 003 places it again at the vertex): the held pose moved by the
    // odometry since the move began
    const auto from = moveFrom_.find(name);
    const mrpt::poses::CPose3D now =
        moveStart_.count(name) && from != moveFrom_.end()
            ? mrpt::poses::CPose3D(from->second.first + (odo->odometry - from->second.second))
            : track.back().pose;
    if (t > track.back().t + 1e-6) track.push_back({t, now});
    lastReading_[name] = {t, odo->odometry, moving};
}

common::Trajectories FormationLocalizer::estimates() const {
    common::Trajectories out = track_;
    // after its last arrival a robot stands still: it would have reported another
    for (auto& [name, track] : out)
        if (name != kDeadReckoningRobot && !track.empty() && lastTime_ > track.back().t)
            track.push_back({lastTime_, track.back().pose});
    return out;
}

common::ObservationUse FormationLocalizer::observationUse() const {
    common::ObservationUse use;
    use.kind = "team scans and arrival messages (<robot>.obstacles, <robot>.arrived)";
    use.seen = teamSeen_;
    use.used = teamUsed_;
    use.unmatched.push_back({"from robots not in [formation] names", teamSeen_ - teamUsed_});
    return use;
}

nlohmann::json FormationLocalizer::methodMetrics() const {
    nlohmann::json j;
    j["moves"] = team_->moves().size();
    j["state"] = stateName(team_->state());
    j["obstacle_cells"] = team_->obstacles().size();
    j["camera_lost_moves"] = cameraLostMoves_;  // pixel mode: finished by the belief
    j["dead_reckoning_readings"] =
        estimates_.count(kDeadReckoningRobot) ? estimates_.at(kDeadReckoningRobot).size() : 0;
    return j;
}

nlohmann::json FormationLocalizer::truthMetrics(const common::Trajectories& truth) const {
    const auto run = FormationRunFile::fromRun(*team_, estimates_, truth);
    nlohmann::json j;
    if (!run.moves.empty() && std::isfinite(run.moves.back().error()))
        j["final_error_m"] = run.moves.back().error();  // seed 003 Table 1: the last mover
    if (std::isfinite(run.deadReckoningFinalError))
        j["dead_reckoning_final_error_m"] = run.deadReckoningFinalError;
    double sum = 0;
    size_t n = 0;
    for (const auto& m : run.moves)
        if (std::isfinite(m.error())) sum += m.error(), ++n;
    if (n) j["mean_vertex_error_m"] = sum / double(n);
    return j;
}

void FormationLocalizer::writeOutputs(const std::string& outDir,
                                      const common::Trajectories& truth) const {
    FormationRunFile::fromRun(*team_, estimates_, truth).write(outDir);
}

}  // namespace mrloc::formation
