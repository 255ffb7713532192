#include <mrloc/beacons/BeaconLocalizer.h>
#include <mrloc/beacons/Ultrasonic.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/IniSection.h>
#include <mrloc/common/Rawlog.h>
#include <mrloc/common/Trajectory.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/system/datetime.h>

#include <cmath>

namespace mrloc::beacons {

void BeaconLocalizer::configure(const mrpt::config::CConfigFileBase& ini) {
    options_.loadFromConfigFile(ini, "beacons");
    study_.load(ini, "beacons_study");
    if (study_.enabled) {  // the study simulates the run's hardware again
        studyUltrasonic_.loadFromConfigFile(ini, "ultrasonic");
        studySensors_.loadFromConfigFile(ini, "sensors");
    }
}

void BeaconLocalizer::saveConfig(mrpt::config::CConfigFileBase& target) const {
    options_.saveToConfigFile(target, "beacons");
    study_.save(target, "beacons_study");
}

BeaconTracker& BeaconLocalizer::trackerOf(const std::string& robot) {
    auto it = trackers_.find(robot);
    if (it == trackers_.end())
        it = trackers_.emplace(robot, BeaconTracker(options_.map, options_.tracker)).first;
    return it->second;
}

void BeaconLocalizer::process(const mrpt::obs::CObservation::Ptr& obs) {
    const std::string robot = common::robotOfLabel(obs->sensorLabel);
    const double t = common::stampSeconds(obs->timestamp);
    firstSeen_.emplace(robot, t);
    if (auto odo = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(obs)) {
        BeaconTracker& tracker = trackerOf(robot);
        tracker.onOdometry(odo->odometry);
        auto& path = odometry_[robot];
        path.add(t, odo->odometry);
        spacing_[robot].sinceLast += path.lastStep();
        // between sightings the estimate is the odometry's prediction, at its rate, with its
        // growing covariance: a gap in the ranges is never a hole in the output
        if (options_.mode == BeaconOptions::Mode::Tracker && tracker.initialized())
            addEstimate(robot, t, tracker, /*measured=*/false);
        return;
    }
    if (auto camera = std::dynamic_pointer_cast<mrpt::obs::CObservationBearingRange>(obs)) {
        if (options_.mode == BeaconOptions::Mode::Tracker) sighted(robot, t, *camera);
        return;
    }
    auto ranges = std::dynamic_pointer_cast<mrpt::obs::CObservationBeaconRanges>(obs);
    if (!ranges) return;
    if (options_.mode == BeaconOptions::Mode::Fixes) {
        // ranges read one at a time make a fix from the window (windowed): each fix is then
        // the window's newest beacons, moved to the newest reading by the odometry
        const size_t windowBefore = windowEpochs_;
        const auto epoch = windowed(robot, t, *ranges);
        if (!epoch) return;
        const TrackerStats before = trackerOf(robot).stats();
        fixOnly(robot, t, *epoch);
        if (windowEpochs_ != windowBefore)
            countWindowed(before, trackerOf(robot).stats(), ranges->sensedData.size());
        return;
    }
    BeaconTracker& tracker = trackerOf(robot);
    // The filter is at the last odometry reading, up to one reading period before the
    // epoch's stamp: carried to the stamp at the last step's twist, the estimate is the
    // pose at its time (at 0.3 m/s and 20 Hz, up to 15 mm along the path otherwise).
    if (const auto path = odometry_.find(robot); path != odometry_.end())
        if (const auto atStamp = path->second.extrapolate(t)) tracker.onOdometry(*atStamp);
    // not started: each range also goes to the particle start-up, which starts the filter
    // from ranges read one at a time (ParticleStart.h); this observation is then spent
    if (!tracker.initialized()) {
        std::vector<BeaconTracker::Sighting> seen;
        for (const auto& m : ranges->sensedData) {
            const auto b = options_.map.find(m.beaconID);
            if (b == options_.map.end() || !std::isfinite(m.sensedDistance) ||
                m.sensedDistance <= 0)
                continue;
            const auto& s = m.sensorLocationOnRobot;
            BeaconTracker::Sighting v;
            v.beacon = {b->second.x, b->second.y, b->second.z};
            v.sensorOnRobot = {s.x(), s.y(), s.z()};
            v.range = m.sensedDistance;
            v.rangeSigma = options_.tracker.rangeSigma;
            v.beaconId = m.beaconID;
            seen.push_back(v);
        }
        if (tracker.feedStart(t, seen)) {
            addEstimate(robot, t, tracker, /*measured=*/true);
            return;
        }
    }
    const size_t windowBefore = windowEpochs_;
    const auto epoch = windowed(robot, t, *ranges);
    if (!epoch) return;
    const TrackerStats before = tracker.stats();
    const auto pose = tracker.onRanges(t, *epoch);
    if (windowEpochs_ != windowBefore)
        countWindowed(before, tracker.stats(), ranges->sensedData.size());
    if (pose) {
        if (tracker.initialized()) return addEstimate(robot, t, tracker, /*measured=*/true);
        // before the filter starts: a bootstrap fix, no covariance kept
        addEstimate(robot, t, mrpt::poses::CPose3D(*pose), std::nullopt, /*measured=*/true);
    }
}

void BeaconLocalizer::sighted(const std::string& robot, double t,
                              const mrpt::obs::CObservationBearingRange& camera) {
    ++sightingObservations_;
    BeaconTracker& tracker = trackerOf(robot);
    if (const auto path = odometry_.find(robot); path != odometry_.end())
        if (const auto atStamp = path->second.extrapolate(t)) tracker.onOdometry(*atStamp);
    const auto& sensor = camera.sensorLocationOnRobot;
    std::vector<BeaconTracker::Sighting> seen;
    for (const auto& m : camera.sensedData) {
        const auto b = options_.map.find(m.landmarkID);
        if (b == options_.map.end()) {
            ++sightingsNotInMap_;  // another robot, or a landmark the map lacks
            continue;
        }
        BeaconTracker::Sighting v;
        v.beacon = {b->second.x, b->second.y, b->second.z};
        v.sensorOnRobot = {sensor.x(), sensor.y(), sensor.z()};
        v.sensorYaw = sensor.yaw();
        v.beaconId = m.landmarkID;
        v.rangeSigma = options_.tracker.rangeSigma;
        v.bearingSigma = options_.tracker.bearingSigma;
        if (options_.sightings != BeaconOptions::Sightings::Bearing && std::isfinite(m.range) &&
            m.range > 0)
            v.range = m.range;
        if (options_.sightings != BeaconOptions::Sightings::Range && std::isfinite(m.yaw))
            v.bearing = m.yaw;
        if (v.range || v.bearing) seen.push_back(v);
    }
    if (seen.empty()) return;
    if (tracker.onSightings(t, seen)) addEstimate(robot, t, tracker, /*measured=*/true);
}

void BeaconLocalizer::countWindowed(const TrackerStats& before, const TrackerStats& after,
                                    size_t newRanges) {
    // a window's ranges go to the tracker in several epochs: each is counted once, as used
    // when the epoch its own observation completed was used
    windowCount_.fedReceived += after.rangesReceived - before.rangesReceived;
    windowCount_.fedUsed += after.rangesUsed - before.rangesUsed;
    if (after.rangesUsed > before.rangesUsed) windowCount_.used += newRanges;
}

namespace {
/** Ranges the tracker's fixes take at least (BeaconTracker::fixFrom): 2-D with the height
 *  known, and 3-D with the mirror solution resolved (seed 001's three beacons) */
constexpr size_t kFewestForFix = 3;
}  // namespace

std::optional<mrpt::obs::CObservationBeaconRanges> BeaconLocalizer::windowed(
    const std::string& robot, double t, const mrpt::obs::CObservationBeaconRanges& obs) {
    if (options_.rangeWindow <= 0) return compensateMotion(robot, obs);
    BeaconTracker& tracker = trackerOf(robot);
    // the odometry at the range's time; a log without odometry stands still (the window's
    // span bounds what that costs)
    std::optional<mrpt::poses::CPose2D> atStamp;
    if (const auto path = odometry_.find(robot); path != odometry_.end())
        atStamp = path->second.extrapolate(t);
    const mrpt::poses::CPose2D odo = atStamp.value_or(mrpt::poses::CPose2D());
    RangeWindow& window = windows_[robot];
    window.add(t, obs, odo, options_.map);
    // only an observation too short for any fix goes to the window; seed 001's fixes are one
    // per epoch, and an epoch that lost a beacon gives none (Table 4's reception): there only
    // a log whose observations never held enough ranges for a fix (UWB's one range at a time)
    // makes its fixes from the window
    const bool fixes = options_.mode == BeaconOptions::Mode::Fixes;
    size_t& most = mostRanges_[robot];
    most = std::max(most, obs.sensedData.size());
    const bool tooShort = obs.sensedData.size() < kFewestForFix;
    if (!tooShort || (tracker.initialized() && !fixes) || (fixes && most >= kFewestForFix))
        return compensateMotion(robot, obs);
    windowCount_.seen += obs.sensedData.size();
    // a fix with two ranges to spare, as the start-up wants; fewer when the map has fewer
    const size_t unknowns = options_.threeD ? 3 : 2;
    const size_t needed = std::max(kFewestForFix, std::min(options_.map.size(), unknowns + 2));
    auto epoch = window.epoch(t, odo, options_.map, needed, options_.rangeWindow);
    if (!epoch) return std::nullopt;
    epoch->sensorLabel = obs.sensorLabel;
    epoch->stdError = obs.stdError;
    ++windowEpochs_;
    return epoch;
}

mrpt::obs::CObservationBeaconRanges BeaconLocalizer::compensateMotion(
    const std::string& robot, const mrpt::obs::CObservationBeaconRanges& obs) {
    mrpt::obs::CObservationBeaconRanges out = obs;
    const BeaconTracker& tracker = trackerOf(robot);
    const auto path = odometry_.find(robot);
    if (!tracker.initialized() || path == odometry_.end() || !path->second.forwardSpeed())
        return out;
    const double speed = *path->second.forwardSpeed();
    // The beacons fire one after another and the epoch is stamped at its last shot: a
    // range fired `age` earlier was read `age * v` back along the path. To first order it
    // grows by (u . v) age over that time, u the unit vector from beacon to receiver.
    const auto& mean = tracker.pdf().mean;
    const double vx = speed * std::cos(mean.phi()), vy = speed * std::sin(mean.phi());
    for (auto& m : out.sensedData) {
        const auto b = options_.map.find(m.beaconID);
        if (b == options_.map.end()) continue;
        const auto rx = mean.composePoint(
            mrpt::math::TPoint2D(m.sensorLocationOnRobot.x(), m.sensorLocationOnRobot.y()));
        const double dx = rx.x - b->second.x, dy = rx.y - b->second.y,
                     dz = m.sensorLocationOnRobot.z() - b->second.z;
        const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
        if (d < 1e-9) continue;
        m.sensedDistance += float((dx * vx + dy * vy) / d * options_.system.shotAge(m.beaconID));
    }
    return out;
}

void BeaconLocalizer::addEstimate(const std::string& robot, double t, const BeaconTracker& tracker,
                                  bool measured) {
    addEstimate(robot, t, mrpt::poses::CPose3D(tracker.pdf().mean), tracker.pdf().cov, measured);
}

void BeaconLocalizer::addEstimate(const std::string& robot, double t,
                                  const mrpt::poses::CPose3D& pose,
                                  const std::optional<mrpt::math::CMatrixDouble33>& cov,
                                  bool measured) {
    auto& traj = estimates_[robot];
    auto& covariances = covariances_[robot];
    // an epoch stamped before the last odometry reading updates the filter there: the pose
    // is the one at that reading's time, already written, which it replaces
    if (!traj.empty()) t = std::max(t, traj.back().t);
    // how far apart the estimates from measurements are (the bridged ones between them not)
    auto& sp = spacing_[robot];
    if (measured) {
        if (sp.lastMeasured) {
            sp.maxDistance = std::max(sp.maxDistance, sp.sinceLast);
            sp.sumDistance += sp.sinceLast;
            sp.maxTime = std::max(sp.maxTime, t - *sp.lastMeasured);
            ++sp.gaps;
        }
        sp.sinceLast = 0;
        sp.lastMeasured = t;
    }
    common::StampedCovariance c{t, {}};
    c.cov.fill(NAN);
    if (cov) c.cov = *cov;
    // one estimate per time stamp: an odometry reading at a sighting's stamp, the later wins
    if (!traj.empty() && traj.back().t == t) {
        traj.back().pose = pose;
        covariances.back() = c;
        return;
    }
    traj.push_back({t, pose});
    covariances.push_back(c);
}

std::optional<mrpt::poses::CPose3D> BeaconLocalizer::latestEstimate(
    const std::string& robot) const {
    const auto it = estimates_.find(robot);
    if (it == estimates_.end() || it->second.empty()) return std::nullopt;
    return it->second.back().pose;
}

void BeaconLocalizer::fixOnly(const std::string& robot, double t,
                              const mrpt::obs::CObservationBeaconRanges& obs) {
    const auto f = trackerOf(robot).fixOnly(obs);
    if (!f) return;
    // The fix locates the receiver; the robot's reference is sensor z below it.
    const double sensorZ = obs.sensedData.front().sensorLocationOnRobot.z();
    const double z = options_.threeD ? f->position.z() - sensorZ : 0.0;
    const auto odometry = odometry_.find(robot);
    const double heading = odometry == odometry_.end() ? 0.0 : odometry->second.last()->phi();
    mrpt::math::CMatrixDouble33 cov;
    cov.fill(NAN);  // the heading is odometry's: the fix says nothing of it
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) cov(i, j) = f->covariance(i, j);
    addEstimate(robot, t, mrpt::poses::CPose3D(f->position.x(), f->position.y(), z, heading, 0, 0),
                cov, /*measured=*/true);
}

common::ObservationUse BeaconLocalizer::observationUse() const {
    TrackerStats total;
    for (const auto& [robot, tr] : trackers_) total += tr.stats();
    common::ObservationUse use;
    use.kind = "beacon ranges (CObservationBeaconRanges)";
    use.seen = total.rangesReceived - windowCount_.fedReceived + windowCount_.seen;
    use.used = total.rangesUsed - windowCount_.fedUsed + windowCount_.used;
    use.unmatched.push_back({"ranges from beacons not in the map", total.rangesUnknownBeacon});
    if (sightingObservations_ > 0) {
        // a camera's sightings: each range and each bearing counted as one measurement
        use.kind += " and camera sightings (CObservationBearingRange: ranges and bearings)";
        use.seen += total.bearingsReceived + sightingsNotInMap_;
        use.used += total.bearingsUsed;
        use.unmatched.push_back(
            {"sightings of ids not in the map (other robots, unmapped landmarks)",
             sightingsNotInMap_});
    }
    if (total.fixFailures > 0)  // counted in epochs: the ranges of an epoch fail together
        use.unmatched.push_back(
            {"epochs whose multilateration failed (do the map's beacon positions fit this log?)",
             total.fixFailures});
    return use;
}

nlohmann::json BeaconLocalizer::methodMetrics() const {
    nlohmann::json j;
    TrackerStats total;
    for (const auto& [robot, tr] : trackers_) total += tr.stats();
    j["mode"] = options_.mode == BeaconOptions::Mode::Tracker ? "tracker" : "fixes";
    j["beacons"] = options_.map.size();
    j["epochs"] = total.epochs;
    j["ranges_received"] = total.rangesReceived;
    j["ranges_used"] = total.rangesUsed;
    j["ranges_gated"] = total.rangesGated;
    j["ranges_unknown_beacon"] = total.rangesUnknownBeacon;
    // multilateration fixes (seed 001 eqs. 4-10): in fixes mode one per estimate, in tracker
    // mode those that start or restart the filter; the estimates are per robot below
    j["multilateration_fixes"] = total.fixes;
    j["fix_failures"] = total.fixFailures;
    j["mirror_resolved"] = total.mirrorResolved;
    j["window_epochs"] = windowEpochs_;
    j["filter_resets"] = total.resets;
    j["offsets_reopened"] = total.offsetsReopened;  // a beacon kept failing the gate
    j["particle_starts"] = total.particleStarts;    // starts and re-starts from the particles
    j["bearings_received"] = total.bearingsReceived;
    j["bearings_used"] = total.bearingsUsed;
    j["bearings_gated"] = total.bearingsGated;
    j["sightings_not_in_map"] = sightingsNotInMap_;  // other robots, or landmarks not mapped
    for (const auto& [robot, sp] : spacing_) {
        auto& r = j["robots"][robot];
        r["estimates"] = estimates_.count(robot) ? estimates_.at(robot).size() : 0;
        r["max_distance_between_fixes_m"] = sp.maxDistance;
        r["mean_distance_between_fixes_m"] = sp.gaps ? sp.sumDistance / double(sp.gaps) : 0.0;
        r["max_time_between_fixes_s"] = sp.maxTime;
        // from the robot's first observation to its first estimate (null: none)
        const auto e = estimates_.find(robot);
        r["time_to_first_estimate_s"] =
            e == estimates_.end() || e->second.empty() || !firstSeen_.count(robot)
                ? nlohmann::json()
                : nlohmann::json(e->second.front().t - firstSeen_.at(robot));
    }
    // the range biases each robot's tracker estimated, as they stand at the end of the log
    for (const auto& [robot, tr] : trackers_) {
        const auto offsets = tr.rangeOffsets();
        if (offsets.empty() || !tr.initialized()) continue;
        auto& r = j["robots"][robot];
        for (const auto& [id, offset] : offsets) r["range_offsets_m"][std::to_string(id)] = offset;
        r["range_scale"] = tr.rangeScale();
    }
    // The rawlog holds the ranges heard, not the shots fired (a section fires only its own
    // beacons): the mean heard per epoch. The reception rate of the shots fired needs the
    // simulator's shot log; the report shows it.
    if (total.epochs > 0)
        j["ranges_per_epoch"] = double(total.rangesReceived) / double(total.epochs);
    return j;
}

namespace {
BeaconLocalizer configured(const mrpt::config::CConfigFileBase& ini) {
    BeaconLocalizer l;
    l.configure(ini);
    return l;
}
}  // namespace

OnboardBeacons::OnboardBeacons(const mrpt::config::CConfigFileBase& ini)
    : localizer(configured(ini)), rfBeacon(localizer.options().system) {}

}  // namespace mrloc::beacons
