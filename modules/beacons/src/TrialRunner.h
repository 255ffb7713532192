#pragma once
// The trial physics of the beacon study (BeaconStudy.h), shared by its coverage evaluation
// (BeaconStudy.cpp) and its agents' scheduler (AgentsScheduler.cpp): the beacons' shots
// through the ultrasonic link and the receiver's fix from them, in an empty room.
#include <mrloc/beacons/BeaconStudy.h>

#include <algorithm>
#include <cmath>

namespace mrloc::beacons {

/** The beacons' shots and the receiver's fix for many trials in one room: the link, the
 *  heads and the fix's tracker are built once. */
class TrialRunner {
 public:
    TrialRunner(const StudyRoom& room, const StudyHardware& hw, const StudyMethod& method)
        : room_(room), hw_(hw), method_(method), link_(hw.ultrasonic) {
        for (const auto& [id, b] : room.beacons)
            heads_.emplace(id, PanTiltHead(b, hw.ultrasonic.head));
        TrackerOptions o = hw.tracker;
        o.estimateBias = false;  // a fix alone: no filter state
        o.startPose.reset();
        o.fix.residual = method.residual;
        o.fix.knownHeight = method.threeD ? std::nullopt : std::optional<double>(0.0);
        o.rangeDelay = nullptr;
        o.jitterWeights = method.jitterWeights;
        if (method.delayCompensation)
            o.rangeDelay = decoderDelayModel(
                hw.ultrasonic, room.active ? std::map<int, Eigen::Vector3d>{} : aimsOf(room));
        tracker_.emplace(room.beacons, o);
    }

    /** Where beacon `id`'s head points when the receiver reports `reported`. */
    mrpt::math::TPoint3D aimOf(int id, const mrpt::math::TPoint3D& reported) const {
        if (room_.active) return reported;
        if (const auto a = room_.fixedAim.find(id); a != room_.fixedAim.end())
            return {a->second.x(), a->second.y(), a->second.z()};
        const mrpt::math::TPoint3D& b = room_.beacons.at(id);
        return {b.x, b.y, b.z - 1};  // straight down
    }

    /** The link's mean level of beacon `id`'s burst at `rx` with its head aimed at `aim`. */
    double predictedMargin(int id, const mrpt::math::TPoint3D& aim,
                           const mrpt::math::TPoint3D& rx) const {
        const PanTiltHead& head = heads_.at(id);
        const auto angles = head.aimAt(aim);
        const mrpt::math::TPoint3D b = room_.beacons.at(id);
        return link_.marginDb(std::sqrt((b - rx).sqrNorm()), head.offAxisAngle(angles, rx));
    }

    /** The `k` beacons the link predicts loudest at `reported` (not in `taken`), ascending id. */
    std::vector<int> loudest(const mrpt::math::TPoint3D& reported, size_t k,
                             const std::vector<int>& taken = {}) const {
        std::vector<std::pair<double, int>> level;
        for (const auto& [id, b] : room_.beacons)
            if (std::find(taken.begin(), taken.end(), id) == taken.end())
                level.emplace_back(-predictedMargin(id, aimOf(id, reported), reported), id);
        k = std::min(k, level.size());
        std::partial_sort(level.begin(), level.begin() + long(k), level.end());
        std::vector<int> out;
        for (size_t i = 0; i < k; ++i) out.push_back(level[i].second);
        std::sort(out.begin(), out.end());
        return out;
    }

    ShotRecord shoot(int id, const mrpt::math::TPoint3D& aim, const mrpt::math::TPoint3D& rx,
                     mrpt::random::CRandomGenerator& rng) const {
        const PanTiltHead& head = heads_.at(id);
        return simulateShot(
            link_, hw_.sensors, head, head.aimAt(aim), id, rx, [] { return true; },
            [] { return 0.0; }, rng);  // an empty room: every path in sight
    }

    std::optional<Fix> fix(const mrpt::obs::CObservationBeaconRanges& obs) {
        if (obs.sensedData.empty()) return std::nullopt;
        return tracker_->fixOnly(obs);
    }

    static mrpt::obs::CObservationBeaconRanges::TMeasurement measurement(int id, double range,
                                                                         double height) {
        mrpt::obs::CObservationBeaconRanges::TMeasurement m;
        m.beaconID = id;
        m.sensedDistance = float(range);
        m.sensorLocationOnRobot = mrpt::poses::CPoint3D(0, 0, height);
        return m;
    }

    TrialOutcome trial(const mrpt::math::TPoint2D& at, mrpt::random::CRandomGenerator& rng) {
        const mrpt::math::TPoint3D p0{at.x, at.y, hw_.receiverHeight};
        const double heading = rng.drawUniform(-M_PI, M_PI);
        const mrpt::math::TPoint3D dir{std::cos(heading), std::sin(heading), 0};
        const auto fired = loudest(p0, size_t(std::max(1, hw_.beaconsPerFix)));
        mrpt::obs::CObservationBeaconRanges obs;
        size_t shot = 0;
        mrpt::math::TPoint3D rx = p0;
        for (int round = 0; round < method_.shotsPerBeacon; ++round)
            for (const int id : fired) {
                rx = p0 + dir * (hw_.speed * hw_.shotInterval * double(shot++));
                const auto r = shoot(id, aimOf(id, p0), rx, rng);
                if (r.detected)
                    obs.sensedData.push_back(measurement(id, r.range, hw_.receiverHeight));
            }
        TrialOutcome out;
        if (const auto f = fix(obs)) {
            out.fixed = true;
            out.error = std::hypot(f->position.x() - rx.x, f->position.y() - rx.y);
        }
        return out;
    }

    const UltrasonicLink& link() const { return link_; }

 private:
    static std::map<int, Eigen::Vector3d> aimsOf(const StudyRoom& room) {
        std::map<int, Eigen::Vector3d> out = room.fixedAim;
        for (const auto& [id, b] : room.beacons)
            if (!out.count(id)) out[id] = Eigen::Vector3d(b.x, b.y, b.z - 1);
        return out;
    }

    const StudyRoom& room_;
    const StudyHardware& hw_;
    StudyMethod method_;
    UltrasonicLink link_;
    std::map<int, PanTiltHead> heads_;
    std::optional<BeaconTracker> tracker_;
};

}  // namespace mrloc::beacons
