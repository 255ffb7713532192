#pragma once
// The ultrasonic link from a beacon's transmitter to a robot's receiver (section
// [ultrasonic]), and the pan-tilt heads' hardware limits.
//
// Seed 001 section 5.2 names the mechanism and this model follows it: the transmitter's
// beam is narrow, so the signal level at the receiver falls with the off-axis angle and
// with distance; the receiver's tone decoder fires when the envelope of the 40 kHz burst
// crosses its threshold; a weak burst crosses it later (the range reads long) or, within
// the firing time, never (no reception). Levels are in dB above the decoder threshold:
//
//   margin = source_margin - 20 log10(d / 1 m) - absorption (d - 1 m)
//            - 6 dB (2 theta / beam_angle)^2 + fading,          fading ~ N(0, fading_sigma)
//
// (a Gaussian main lobe, 6 dB down at half the beam angle). The envelope rises as
// A (1 - exp(-t / rise_time)); it reaches the threshold at
//
//   delay = -rise_time ln(1 - 10^(-margin / 20))
//
// if that is within firing_time, else the shot is missed. The receiver is calibrated on
// the beam's axis at calibration_distance: that delay is subtracted from every reading.
#include <mrloc/beacons/PanTilt.h>
#include <mrloc/common/KeyTable.h>
#include <mrpt/config/CLoadableOptions.h>

#include <Eigen/Core>
#include <functional>
#include <map>
#include <optional>

namespace mrloc::beacons {

/** The range error a shot's decoder delay adds, over the fading: its mean and spread (m). */
struct DelayMoments {
    double mean = 0;
    double sd = 0;
};

struct UltrasonicOptions : public mrpt::config::CLoadableOptions {
    double speedOfSound = 343;           ///< m/s
    double beamAngle = 50 * M_PI / 180;  ///< full beam width at -6 dB (rad)
    double sourceMarginDb = 23;          ///< level above the threshold at 1 m on the axis (dB)
    double absorptionDbPerM = 1.3;       ///< air absorption at 40 kHz (dB/m)
    double fadingSigmaDb = 1.5;          ///< shot-to-shot level scatter (dB)
    double riseTime = 150e-6;            ///< envelope time constant at the receiver (s)
    double firingTime = 450e-6;          ///< burst length, seed 001 section 5.2 (s)
    double calibrationDistance = 1.0;    ///< on-axis distance of the receiver's calibration (m)
    beacons::PanTiltLimits head;         ///< pan_min, pan_max, tilt_max, slew_rate

    /** Every key of [ultrasonic], declared once (loading, effective.ini, doc/ini.md). */
    static const common::KeyTable<UltrasonicOptions>& keys();

    void loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                            const std::string& section) override;
    void saveToConfigFile(mrpt::config::CConfigFileBase& target,
                          const std::string& section) const override;
};

class UltrasonicLink {
 public:
    explicit UltrasonicLink(UltrasonicOptions options);
    const UltrasonicOptions& options() const { return o_; }

    /** Mean level above the decoder threshold (dB) at `distance` and `offAxis` (rad). */
    double marginDb(double distance, double offAxis) const;
    /** Time from the burst's arrival to the decoder's trigger, or nothing if the envelope
     *  never reaches the threshold within the firing time. */
    std::optional<double> triggerDelay(double marginDb) const;
    /** The range error the trigger delay causes once the calibration is subtracted (m). */
    std::optional<double> rangeBias(double marginDb) const;
    /** The range error the decoder's delay is expected to add to a shot over `distance` at
     *  `offAxis` (m): rangeBias averaged over the fading (Simpson's rule from the detection
     * threshold), the shots too weak to be heard left out; 0 if none would be. What a receiver that
     * knows its hardware (the datasheet's rise time, source level, beam and absorption) subtracts:
     *  [beacons] delay_compensation. */
    double expectedRangeBias(double distance, double offAxis) const {
        return rangeBiasMoments(distance, offAxis).mean;
    }
    /** expectedRangeBias and the standard deviation of rangeBias over the heard shots: the
     *  jitter a weak burst adds ([beacons] jitter_weights). */
    DelayMoments rangeBiasMoments(double distance, double offAxis) const;
    /** The weakest margin that is still detected (dB). */
    double detectionThresholdDb() const { return minMarginDb_; }

 private:
    UltrasonicOptions o_;
    double minMarginDb_;
    double calibrationDelay_;
};

/** The range error a shot from beacon `id` at `beacon` to a receiver at `receiver` is expected
 *  to carry, and its spread (m): TrackerOptions::rangeDelay. */
using RangeDelay = std::function<DelayMoments(int id, const Eigen::Vector3d& beacon,
                                              const Eigen::Vector3d& receiver)>;

/** [beacons] delay_compensation: each shot's expected decoder delay from the hardware's
 *  nominal model (UltrasonicLink::expectedRangeBias), its off-axis angle 0 for a head aimed
 *  at the receiver, or from the head's fixed aim point for a beacon in `fixedAim`. */
RangeDelay decoderDelayModel(const UltrasonicOptions& hardware,
                             std::map<int, Eigen::Vector3d> fixedAim);

}  // namespace mrloc::beacons
