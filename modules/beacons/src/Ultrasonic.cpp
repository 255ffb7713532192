#include <mrloc/beacons/Ultrasonic.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/KeyTable.h>
#include <mrpt/core/bits_math.h>

#include <cmath>

namespace mrloc::beacons {

const common::KeyTable<UltrasonicOptions>& UltrasonicOptions::keys() {
    using Opt = UltrasonicOptions;
    static const auto table =
        common::KeyTable<Opt>("ultrasonic")
            .real("speed_of_sound", MRLOC_KEY_FIELD(speedOfSound), {100, 2000}, "m/s",
                  "the burst's speed")
            .degrees("beam_angle", MRLOC_KEY_FIELD(beamAngle), {0, 360},
                     "full beam width at -6 dB (> 0)")
            .real("source_margin_db", MRLOC_KEY_FIELD(sourceMarginDb), {-100, 200}, "dB",
                  "level above the tone decoder's threshold at 1 m on the axis")
            .real("absorption_db_per_m", MRLOC_KEY_FIELD(absorptionDbPerM), {0, 100}, "dB/m",
                  "air absorption at 40 kHz")
            .real("fading_sigma_db", MRLOC_KEY_FIELD(fadingSigmaDb), {0, 50}, "dB",
                  "shot-to-shot level scatter")
            .real("rise_time", MRLOC_KEY_FIELD(riseTime), {1e-9, 1}, "s",
                  "envelope time constant at the receiver")
            .real("firing_time", MRLOC_KEY_FIELD(firingTime), {1e-9, 1}, "s",
                  "burst length (paper 001 section 5.2)")
            .real("calibration_distance", MRLOC_KEY_FIELD(calibrationDistance), {0.01, 100}, "m",
                  "the receiver's delay on the axis at this distance is subtracted")
            .degrees("pan_min", MRLOC_KEY_FIELD(head.panMin), {-360, 360},
                     "pan limit; a full turn or more between the two rotates continuously")
            .degrees("pan_max", MRLOC_KEY_FIELD(head.panMax), {-360, 360},
                     "the other pan limit, greater than `pan_min`")
            .degrees("tilt_max", MRLOC_KEY_FIELD(head.tiltMax), {0, 180},
                     "tilt limit from straight down")
            .degrees("slew_rate", MRLOC_KEY_FIELD(head.slewRate), {1e-3, 1e5},
                     "each joint, per second");
    return table;
}

void UltrasonicOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& src,
                                           const std::string& section) {
    *this = UltrasonicOptions{};  // every key absent takes the struct's default: written once
    common::IniSection s(src, section);
    keys().load(s, *this);
    if (!(beamAngle > 0)) s.fail("beam_angle", "must be greater than 0 degrees");
    if (head.panMax <= head.panMin) s.fail("pan_max", "must be greater than pan_min");
    s.finish();
}

void UltrasonicOptions::saveToConfigFile(mrpt::config::CConfigFileBase& t,
                                         const std::string& section) const {
    keys().save(*this, t, section);
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
