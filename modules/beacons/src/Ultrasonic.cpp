#include <mrloc/beacons/Ultrasonic.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/IniSection.h>
#include <mrpt/core/bits_math.h>

#include <cmath>

namespace mrloc::beacons {

void UltrasonicOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& src,
                                           const std::string& section) {
    *this = UltrasonicOptions{};  // every key absent takes the struct's default: written once
    common::IniSection s(src, section);
    speedOfSound = s.real("speed_of_sound", speedOfSound, 100, 2000);
    const double beamDeg = s.real("beam_angle", 50, 0, 360);
    if (!(beamDeg > 0)) s.fail("beam_angle", "must be greater than 0 degrees");
    beamAngle = mrpt::DEG2RAD(beamDeg);
    sourceMarginDb = s.real("source_margin_db", sourceMarginDb, -100, 200);
    absorptionDbPerM = s.real("absorption_db_per_m", absorptionDbPerM, 0, 100);
    fadingSigmaDb = s.real("fading_sigma_db", fadingSigmaDb, 0, 50);
    riseTime = s.real("rise_time", riseTime, 1e-9, 1);
    firingTime = s.real("firing_time", firingTime, 1e-9, 1);
    calibrationDistance = s.real("calibration_distance", calibrationDistance, 0.01, 100);
    head.panMin = mrpt::DEG2RAD(s.real("pan_min", -180, -360, 360));
    head.panMax = mrpt::DEG2RAD(s.real("pan_max", 180, -360, 360));
    if (head.panMax <= head.panMin) s.fail("pan_max", "must be greater than pan_min");
    head.tiltMax = mrpt::DEG2RAD(s.real("tilt_max", 90, 0, 180));
    head.slewRate = mrpt::DEG2RAD(s.real("slew_rate", mrpt::RAD2DEG(head.slewRate), 1e-3, 1e5));
    s.finish();
}

void UltrasonicOptions::saveToConfigFile(mrpt::config::CConfigFileBase& t,
                                         const std::string& section) const {
    t.write(section, "speed_of_sound", speedOfSound);
    t.write(section, "beam_angle", mrpt::RAD2DEG(beamAngle));
    t.write(section, "source_margin_db", sourceMarginDb);
    t.write(section, "absorption_db_per_m", absorptionDbPerM);
    t.write(section, "fading_sigma_db", fadingSigmaDb);
    t.write(section, "rise_time", riseTime);
    t.write(section, "firing_time", firingTime);
    t.write(section, "calibration_distance", calibrationDistance);
    t.write(section, "pan_min", mrpt::RAD2DEG(head.panMin));
    t.write(section, "pan_max", mrpt::RAD2DEG(head.panMax));
    t.write(section, "tilt_max", mrpt::RAD2DEG(head.tiltMax));
    t.write(section, "slew_rate", mrpt::RAD2DEG(head.slewRate));
}

UltrasonicLink::UltrasonicLink(UltrasonicOptions options) : o_(options) {
    // The envelope peaks at the end of the burst: A (1 - exp(-firing_time / rise_time)).
    minMarginDb_ = -20 * std::log10(1 - std::exp(-o_.firingTime / o_.riseTime));
    const auto cal = triggerDelay(marginDb(o_.calibrationDistance, 0));
    if (!cal)
        throw Error(
            "[ultrasonic]: the receiver cannot even hear a beacon on the axis at "
            "calibration_distance; raise source_margin_db or shorten the distance");
    calibrationDelay_ = *cal;
}

double UltrasonicLink::marginDb(double distance, double offAxis) const {
    const double d = std::max(distance, 1e-3);
    const double lobe = 2 * offAxis / o_.beamAngle;
    return o_.sourceMarginDb - 20 * std::log10(d) - o_.absorptionDbPerM * (d - 1) - 6 * lobe * lobe;
}

std::optional<double> UltrasonicLink::triggerDelay(double margin) const {
    if (margin <= minMarginDb_) return std::nullopt;
    return -o_.riseTime * std::log1p(-std::pow(10, -margin / 20));
}

std::optional<double> UltrasonicLink::rangeBias(double margin) const {
    const auto d = triggerDelay(margin);
    if (!d) return std::nullopt;
    return o_.speedOfSound * (*d - calibrationDelay_);
}

DelayMoments UltrasonicLink::rangeBiasMoments(double distance, double offAxis) const {
    // E[bias(margin + F) | heard] and its second moment, F ~ N(0, fading_sigma): Simpson's
    // rule over the levels that are heard, from the detection threshold (the bias is steep
    // there) to 5 sigma up
    const double mean = marginDb(distance, offAxis), sigma = o_.fadingSigmaDb;
    if (!(sigma > 0)) return {rangeBias(mean).value_or(0.0), 0.0};
    const double lo = std::max(-5.0, (minMarginDb_ - mean) / sigma) + 1e-9, hi = 5.0;
    if (!(lo < hi)) return {};
    constexpr int kIntervals = 200;  // even, for Simpson
    const double h = (hi - lo) / kIntervals;
    double sum = 0, sum2 = 0, weight = 0;
    for (int k = 0; k <= kIntervals; ++k) {
        const double z = lo + h * k;
        const double w = (k == 0 || k == kIntervals ? 1 : k % 2 ? 4 : 2) * std::exp(-0.5 * z * z);
        const double b = rangeBias(mean + sigma * z).value_or(0.0);
        sum += w * b;
        sum2 += w * b * b;
        weight += w;
    }
    const double m = sum / weight;
    return {m, std::sqrt(std::max(0.0, sum2 / weight - m * m))};
}

RangeDelay decoderDelayModel(const UltrasonicOptions& hardware,
                             std::map<int, Eigen::Vector3d> fixedAim) {
    const auto link = std::make_shared<const UltrasonicLink>(hardware);
    return [link, aimOf = std::move(fixedAim)](int id, const Eigen::Vector3d& beacon,
                                               const Eigen::Vector3d& receiver) {
        const Eigen::Vector3d toReceiver = receiver - beacon;
        double offAxis = 0;
        if (const auto aim = aimOf.find(id); aim != aimOf.end()) {
            const Eigen::Vector3d axis = aim->second - beacon;
            offAxis = std::atan2(axis.cross(toReceiver).norm(), axis.dot(toReceiver));
        }
        return link->rangeBiasMoments(toReceiver.norm(), offAxis);
    };
}

}  // namespace mrloc::beacons
