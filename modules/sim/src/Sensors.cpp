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

}  // namespace mrloc::sim
