#include <mrloc/common/Error.h>
#include <mrloc/common/Names.h>
#include <mrloc/formation/DeadReckoning.h>
#include <mrloc/formation/FormationFiles.h>
#include <mrloc/formation/FormationLocalizer.h>
#include <mrloc/formation/FormationPayload.h>
#include <mrpt/obs/CObservationComment.h>
#include <mrpt/obs/CObservationOdometry.h>

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
    if (firstSighting)  // the start: where the strip puts it
        estimates_[team_->options().names[*robot]].push_back(
            {t, pose3(team_->believed()[*robot], team_->believedHeading(*robot))});
    if (team_->moves().size() > before) {
        const size_t r = team_->moves().back().move.robot;
        estimates_[team_->options().names[r]].push_back(
            {t, pose3(team_->believed()[r], team_->believedHeading(r))});
    }
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
