#include <mrloc/beacons/BeaconRanging.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/KeyTable.h>

#include <algorithm>
#include <cmath>

namespace mrloc::beacons {

using mrpt::math::TPoint3D;

namespace {
// A reflected echo (no line of sight) loses this much at the wall, on top of its longer path.
constexpr double kReflectionLossDb = 3.0;
}  // namespace

const common::KeyTable<SensorOptions>& SensorOptions::keys() {
    using Opt = SensorOptions;
    static const auto table =
        common::KeyTable<Opt>("sensors")
            .real("range_sigma", MRLOC_KEY_FIELD(rangeSigma), {0, 10}, "m",
                  "Gaussian TOF range noise")
            .real("range_max", MRLOC_KEY_FIELD(rangeMax), {0.01, 1000}, "m", "no range beyond")
            .real("range_dropout", MRLOC_KEY_FIELD(dropout), {0, 1}, "",
                  "probability a line-of-sight range is missed")
            .real("range_outlier_probability", MRLOC_KEY_FIELD(outlierProbability), {0, 1}, "",
                  "probability a range reads long (late trigger)")
            .real("range_outlier_min", MRLOC_KEY_FIELD(outlierMin), {0, 100}, "m",
                  "such a range is long by U(`range_outlier_min`, `range_outlier_max`); the "
                  "short ones pass any gate")
            .real("range_outlier_max", MRLOC_KEY_FIELD(outlierMax), {0.1, 100}, "m",
                  "at least `range_outlier_min`")
            .real("range_bias_sigma", MRLOC_KEY_FIELD(biasSigma), {0, 10}, "m",
                  "each beacon's own range offset, drawn once per run (a UWB antenna delay); 0: "
                  "none drawn, so other logs keep their random stream")
            .real("range_bias_drift", MRLOC_KEY_FIELD(biasDrift), {0, 10}, "m/sqrt(s)",
                  "that offset's random walk; 0: none drawn")
            .choice("nlos", MRLOC_KEY_FIELD(nlosReflect),
                    std::vector<std::pair<std::string, bool>>{{"reflect", true}, {"drop", false}},
                    "blocked path: `reflect` (range long by U(`range_outlier_min`, "
                    "`range_outlier_max`), 3 dB reflection loss) or `drop`");
    return table;
}

void SensorOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& src,
                                       const std::string& section) {
    *this = SensorOptions{};  // every key absent takes the struct's default: written once
    common::IniSection s(src, section);
    keys().load(s, *this);
    if (outlierMax < outlierMin)
        s.fail("range_outlier_max",
               "must be at least range_outlier_min (" + std::to_string(outlierMin) + ")");
    s.finish();
}

void SensorOptions::saveToConfigFile(mrpt::config::CConfigFileBase& t,
                                     const std::string& section) const {
    keys().save(*this, t, section);
}

BeaconRanging::BeaconRanging(const sim::World& world, const BeaconMap& beacons,
                             SensorOptions sensors, UltrasonicOptions ultrasonic)
    : world_(world), beacons_(beacons), sensors_(sensors), link_(ultrasonic) {
    for (const auto& [id, p] : beacons_)
        heads_.emplace(id, Head{PanTiltHead(p, ultrasonic.head), {}});
}

double BeaconRanging::begin(double t, const RangingEpoch& epoch) {
    if (inEpoch_) throw Error("ranging: an epoch began before the previous one ended");
    if (epoch.beacons.empty() || epoch.beacons.size() != epoch.aimPoints.size() ||
        !(epoch.shotInterval > 0))
        throw Error("ranging: an epoch for robot '" + epoch.robot +
                    "' needs one aim point per beacon, at least one beacon and a "
                    "positive shot interval");
    double slew = 0;
    for (size_t j = 0; j < epoch.beacons.size(); ++j) {
        const auto it = heads_.find(epoch.beacons[j]);
        if (it == heads_.end())
            throw Error("ranging: beacon " + std::to_string(epoch.beacons[j]) + " of section '" +
                        epoch.section + "' is not in the beacon map");
        Head& h = it->second;
        const auto target = h.head.aimAt(epoch.aimPoints[j], h.angles.pan);
        slew = std::max(slew, h.head.slewTime(h.angles, target));
        h.angles = target;  // no shot is fired before every head has arrived
    }
    epoch_ = epoch;
    inEpoch_ = true;
    firstShot_ = t + slew;
    fired_ = 0;
    obs_ = mrpt::obs::CObservationBeaconRanges::Create();
    obs_->minSensorDistance = 0;
    obs_->maxSensorDistance = float(sensors_.rangeMax);
    obs_->stdError = float(sensors_.rangeSigma);
    return firstShot_ + double(epoch.beacons.size()) * epoch.shotInterval;
}

double BeaconRanging::beaconBias(int id, double t, mrpt::random::CRandomGenerator& rng) {
    // drawn only when asked for, so logs without beacon biases keep their random stream
    auto it = bias_.find(id);
    if (it == bias_.end()) {
        const double b0 = sensors_.biasSigma > 0 ? rng.drawGaussian1D(0, sensors_.biasSigma) : 0;
        it = bias_.emplace(id, std::make_pair(b0, t)).first;
    }
    auto& [bias, since] = it->second;
    if (sensors_.biasDrift > 0 && t > since)
        bias += rng.drawGaussian1D(0, sensors_.biasDrift * std::sqrt(t - since));
    since = t;
    return bias;
}

ShotRecord simulateShot(const UltrasonicLink& link, const SensorOptions& sensors,
                        const PanTiltHead& head, const PanTiltAngles& angles, int id,
                        const TPoint3D& rx, const std::function<bool()>& lineOfSight,
                        const std::function<double()>& beaconBias,
                        mrpt::random::CRandomGenerator& rng) {
    const TPoint3D b = head.base();
    ShotRecord r;
    r.beacon = id;
    r.pan = angles.pan;
    r.tilt = angles.tilt;
    r.offAxis = head.offAxisAngle(angles, rx);
    r.distance = std::sqrt((b - rx).sqrNorm());
    // Every draw is made whatever the branch, so one shot's fate never shifts the random
    // stream of the others.
    const double fading = rng.drawGaussian1D(0, link.options().fadingSigmaDb);
    const double noise = rng.drawGaussian1D(0, sensors.rangeSigma);
    const double u = rng.drawUniform(0.0, 1.0), v = rng.drawUniform(0.0, 1.0);
    const double extra = rng.drawUniform(sensors.outlierMin, sensors.outlierMax);
    const double bias = sensors.biasSigma > 0 || sensors.biasDrift > 0 ? beaconBias() : 0.0;

    r.lineOfSight = lineOfSight();
    double path = r.distance;
    double loss = 0;
    if (!r.lineOfSight) {
        if (!sensors.nlosReflect) return r;
        path += extra;  // the first echo arrives by a longer, reflected path
        loss = kReflectionLossDb;
    }
    r.marginDb = link.marginDb(path, r.offAxis) + fading - loss;
    if (r.distance > sensors.rangeMax) return r;
    const auto late = link.rangeBias(r.marginDb);  // late trigger of a weak burst
    if (!late) return r;
    if (r.lineOfSight && u < sensors.dropout) return r;
    if (r.lineOfSight && v < sensors.outlierProbability) path += extra;
    r.detected = true;
    r.range = std::max(0.0, path + *late + bias + noise);
    return r;
}

ShotRecord BeaconRanging::shoot(int id, const TPoint3D& rx, double t,
                                mrpt::random::CRandomGenerator& rng) {
    const Head& h = heads_.at(id);
    const TPoint3D b = beacons_.at(id);
    return simulateShot(
        link_, sensors_, h.head, h.angles, id, rx, [&] { return world_.lineOfSight(b, rx); },
        [&] { return beaconBias(id, t, rng); }, rng);
}

mrpt::obs::CObservationBeaconRanges::Ptr BeaconRanging::fireDue(
    double t, const std::function<TPoint3D(double)>& receiverAt, const TPoint3D& onRobot,
    mrpt::random::CRandomGenerator& rng, ShotLog& log) {
    if (!inEpoch_) return nullptr;
    const double interval = epoch_.shotInterval;
    const size_t n = epoch_.beacons.size();
    while (fired_ < n && firstShot_ + double(fired_) * interval <= t + 1e-9) {
        const double when = firstShot_ + double(fired_) * interval;
        ShotRecord r = shoot(epoch_.beacons[fired_], receiverAt(when), when, rng);
        r.start = lastShot_ = when;
        r.end = r.start + interval;
        r.robot = epoch_.robot;
        r.section = epoch_.section;
        if (r.detected) {
            mrpt::obs::CObservationBeaconRanges::TMeasurement m;
            m.beaconID = r.beacon;
            m.sensedDistance = float(r.range);
            m.sensorLocationOnRobot = mrpt::poses::CPoint3D(onRobot);
            obs_->sensedData.push_back(m);
        }
        log.push_back(std::move(r));
        ++fired_;
    }
    if (fired_ < n) return nullptr;
    inEpoch_ = false;
    return std::move(obs_);
}

}  // namespace mrloc::beacons
