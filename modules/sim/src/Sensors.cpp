#include <mrloc/common/IniSection.h>
#include <mrloc/sim/Sensors.h>

#include <cmath>

namespace mrloc::sim {

void SensorOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& src,
                                       const std::string& section) {
    common::IniSection s(src, section);
    rangeSigma = s.real("range_sigma", 0.01, 0, 10);
    rangeMax = s.real("range_max", 10, 0.01, 1000);
    dropout = s.real("range_dropout", 0.02, 0, 1);
    outlierProbability = s.real("range_outlier_probability", 0.01, 0, 1);
    outlierMax = s.real("range_outlier_max", 1.0, 0.1, 100);
    nlosReflect = s.choice("nlos", "reflect", {"reflect", "drop"}) == "reflect";
    s.finish();
}

void SensorOptions::saveToConfigFile(mrpt::config::CConfigFileBase& t,
                                     const std::string& section) const {
    t.write(section, "range_sigma", rangeSigma);
    t.write(section, "range_max", rangeMax);
    t.write(section, "range_dropout", dropout);
    t.write(section, "range_outlier_probability", outlierProbability);
    t.write(section, "range_outlier_max", outlierMax);
    t.write(section, "nlos", nlosReflect ? "reflect" : "drop");
}

OdometrySensor::OdometrySensor(const RobotOptions& robot) : robot_(robot), odometry_(robot.start) {}

void OdometrySensor::accumulate(const mrpt::poses::CPose2D& d,
                                mrpt::random::CRandomGenerator& rng) {
    const double dist = std::hypot(d.x(), d.y());
    const double sxy = robot_.odometrySigmaXY * dist;
    const double sphi =
        robot_.odometrySigmaPhi * std::abs(d.phi()) + robot_.odometrySigmaPhiPerMetre * dist;
    const double ex = rng.drawGaussian1D(0, sxy), ey = rng.drawGaussian1D(0, sxy);
    const double ephi = rng.drawGaussian1D(0, sphi);
    odometry_ = odometry_ + mrpt::poses::CPose2D(d.x() + ex, d.y() + ey, d.phi() + ephi);
}

mrpt::obs::CObservationOdometry::Ptr OdometrySensor::read(const std::string& label,
                                                          mrpt::Clock::time_point t) const {
    auto o = mrpt::obs::CObservationOdometry::Create();
    o->sensorLabel = label;
    o->timestamp = t;
    o->odometry = odometry_;
    return o;
}

BeaconRanger::BeaconRanger(const World& world, const common::BeaconMap& beacons,
                           SensorOptions options)
    : world_(world), beacons_(beacons), o_(options) {}

mrpt::obs::CObservationBeaconRanges::Ptr BeaconRanger::read(
    const std::string& label, mrpt::Clock::time_point t, const mrpt::poses::CPose2D& pose,
    const mrpt::math::TPoint3D& receiver, mrpt::random::CRandomGenerator& rng) const {
    auto obs = mrpt::obs::CObservationBeaconRanges::Create();
    obs->sensorLabel = label;
    obs->timestamp = t;
    obs->minSensorDistance = 0;
    obs->maxSensorDistance = float(o_.rangeMax);
    obs->stdError = float(o_.rangeSigma);
    const double c = std::cos(pose.phi()), s = std::sin(pose.phi());
    const mrpt::math::TPoint3D rx(pose.x() + c * receiver.x - s * receiver.y,
                                  pose.y() + s * receiver.x + c * receiver.y, receiver.z);
    for (const auto& [id, b] : beacons_) {
        const double d = std::sqrt((b - rx).sqrNorm());
        // Every draw is made whatever the branch, so one beacon's fate never shifts the
        // random stream of the others.
        const double noise = rng.drawGaussian1D(0, o_.rangeSigma);
        const double u = rng.drawUniform(0.0, 1.0), v = rng.drawUniform(0.0, 1.0);
        const double extra = rng.drawUniform(0.1, o_.outlierMax);
        if (d > o_.rangeMax) continue;
        double range;
        if (!world_.lineOfSight(b, rx)) {
            if (!o_.nlosReflect) continue;
            range = d + extra;  // the first echo arrives by a longer, reflected path
        } else if (u < o_.dropout) {
            continue;
        } else if (v < o_.outlierProbability) {
            range = d + extra;
        } else {
            range = d + noise;
        }
        mrpt::obs::CObservationBeaconRanges::TMeasurement m;
        m.beaconID = id;
        m.sensedDistance = float(std::max(0.0, range));
        m.sensorLocationOnRobot = mrpt::poses::CPoint3D(receiver);
        obs->sensedData.push_back(m);
    }
    return obs;
}

}  // namespace mrloc::sim
