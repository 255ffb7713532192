#include <mrloc/beacons/BeaconLocalizer.h>
#include <mrloc/beacons/Ultrasonic.h>
#include <mrloc/common/KeyTable.h>
#include <mrloc/common/MrptKeys.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>

namespace mrloc::beacons {

namespace {

using O = BeaconOptions;
using common::IniSection;

/** MRPT's range-only INIs give the range noise in their landmarks map's likelihood options:
 *  honoured when [beacons] range_sigma is not given (effective.ini says so). */
void loadRangeSigma(IniSection& s, O& o) {
    const auto& src = s.config();
    const auto& key = common::mrpt_ini::kBeaconRangesStd;
    o.rangeSigmaFrom.clear();
    if (!s.has("range_sigma") && src.keyExists(key.section, key.name)) {
        IniSection mrpt(src, key.section);  // MRPT's section: its other keys are its own
        o.tracker.rangeSigma = mrpt.real(key.name, o.tracker.rangeSigma, 1e-6, 10);
        o.rangeSigmaFrom = std::string("[") + key.section + "] " + key.name;
    } else {
        o.tracker.rangeSigma = s.real("range_sigma", o.tracker.rangeSigma, 1e-6, 10);
    }
}

/** [beacons] start, else MRPT's [OdometryEstimation] odometry_X/Y/PHI. */
void loadStart(IniSection& s, O& o) {
    namespace k = common::mrpt_ini;
    const auto& src = s.config();
    o.startFrom.clear();
    o.tracker.startPose.reset();
    if (s.has("start")) {
        const auto v = s.reals("start", {}, 3);
        o.tracker.startPose = mrpt::poses::CPose2D(v[0], v[1], mrpt::DEG2RAD(v[2]));
    } else if (src.keyExists(k::kOdometryX.section, k::kOdometryX.name) &&
               src.keyExists(k::kOdometryY.section, k::kOdometryY.name)) {
        IniSection mrpt(src, k::kOdometryX.section);  // MRPT's section
        o.tracker.startPose = mrpt::poses::CPose2D(
            mrpt.requireReal(k::kOdometryX.name), mrpt.requireReal(k::kOdometryY.name),
            mrpt::DEG2RAD(mrpt.real(k::kOdometryPhi.name, 0, -360, 360)));
        o.startFrom = std::string("[") + k::kOdometryX.section + "] odometry_X/Y/PHI";
    }
}

/** paper_reception_<id> = % per robot (paper 001 Tables 3/4, for the report). */
void loadPaperReception(IniSection& s, O& o) {
    o.paperReception.clear();
    for (const auto& [id, key] : s.numberedKeys("paper_reception_")) {
        const auto rates = s.reals(key, {});
        for (double r : rates)
            if (r < 0 || r > 100) s.fail(key, "rates are percentages, 0 to 100");
        o.paperReception[id] = rates;
    }
}

/** The heads' tone-decoder delay the fixes subtract (delay_compensation): the hardware as
 *  [ultrasonic] describes it; each head points at the robot (active) or at its section's aim
 *  point (fixed). */
void setRangeDelay(const mrpt::config::CConfigFileBase& src, O& o) {
    o.tracker.rangeDelay = nullptr;
    if (!o.delayCompensation) return;
    UltrasonicOptions hardware;
    hardware.loadFromConfigFile(src, "ultrasonic");
    std::map<int, Eigen::Vector3d> aimOf;
    if (!o.system.activeAiming)
        for (const auto& section : o.system.sections.sections())
            for (int id : section.beacons)
                aimOf[id] = {section.aim.x, section.aim.y, section.aim.z};
    o.tracker.rangeDelay = decoderDelayModel(hardware, std::move(aimOf));
}

}  // namespace

const common::KeyTable<BeaconOptions>& BeaconOptions::keys() {
    using Mode = BeaconOptions::Mode;
    using Sightings = BeaconOptions::Sightings;
    static const auto table =
        common::KeyTable<O>("beacons")
            .choice("mode", MRLOC_KEY_FIELD(mode),
                    std::vector<std::pair<std::string, Mode>>{{"tracker", Mode::Tracker},
                                                              {"fixes", Mode::Fixes}},
                    "`tracker` (EKF: odometry + gated ranges) or `fixes` (paper 001: one fix "
                    "per epoch)")
            .choice("dimension", MRLOC_KEY_FIELD(threeD),
                    std::vector<std::pair<std::string, bool>>{{"2d", false}, {"3d", true}},
                    "`2d`: receiver height known (from the observation's sensor pose); `3d`: x, "
                    "y, z")
            .choice("residual", MRLOC_KEY_FIELD(tracker.fix.residual),
                    std::vector<std::pair<std::string, Residual>>{
                        {"range", Residual::Range}, {"squared", Residual::SquaredRange}},
                    "`range` or `squared` (paper 001 eq. 6)")
            .choice("mirror", MRLOC_KEY_FIELD(tracker.fix.mirror),
                    std::vector<std::pair<std::string, MirrorRule>>{
                        {"below", MirrorRule::Below},
                        {"above", MirrorRule::Above},
                        {"nearest", MirrorRule::NearestToHint}},
                    "coplanar beacons: keep the solution below, above or nearest the last "
                    "estimate")
            .integer("max_iterations", MRLOC_KEY_FIELD(tracker.fix.maxIterations), 1, 1000, "",
                     "Gauss-Newton iterations")
            .flag("delay_compensation", MRLOC_KEY_FIELD(delayCompensation),
                  "`mode = fixes`: each range less the delay the tone decoder is expected to add "
                  "to its shot ([ultrasonic]'s nominal link: level from distance and the head's "
                  "off-axis angle, averaged over the fading), from where the fix puts the "
                  "receiver, refit twice. Heads aimed at the robot count as on the axis; fixed "
                  "heads' angle is from their section's aim point")
            .flag("jitter_weights", MRLOC_KEY_FIELD(tracker.jitterWeights),
                  "with `delay_compensation`: the refits weight each range by the jitter its "
                  "shot is expected to carry, sd^2 = (range_sigma^2 + the delay's spread over "
                  "the fading^2) / the beacon's shots in the epoch: a weak burst's range counts "
                  "less")
            .real("max_gdop", MRLOC_KEY_FIELD(tracker.fix.maxGdop), {1, common::IniSection::kInf},
                  "", "fixes with a larger GDOP are rejected as ill-conditioned")
            .family("start", "m m deg", "",
                    "`x y phi_deg`: the robot's pose where the log starts; the filter starts there "
                    "instead of from two fixes (a single-robot log). Without the key, MRPT's "
                    "`[OdometryEstimation] odometry_X/Y/PHI` if the INI has it (effective.ini says "
                    "so)",
                    loadStart,
                    [](const O& o, mrpt::config::CConfigFileBase& t, const std::string& sec) {
                        const auto& p = o.tracker.startPose;
                        if (!p) return;
                        t.write(sec, "start",
                                common::keyListText({p->x(), p->y()}) + " " +
                                    common::keyDegreesText(p->phi()),
                                -1, -1,
                                o.startFrom.empty() ? std::string() : "from MRPT's " + o.startFrom);
                    })
            .family(
                "range_sigma", "m", "1e-6 .. 10",
                "range noise assumed by the filter; without the key, MRPT's "
                "`[MetricMap_landmarksMap_00_likelihoodOpts] beaconRangesStd` if the INI has it "
                "(effective.ini says so in a comment)",
                loadRangeSigma,
                [](const O& o, mrpt::config::CConfigFileBase& t, const std::string& sec) {
                    t.write(sec, "range_sigma", common::keyValueText(o.tracker.rangeSigma), -1, -1,
                            o.rangeSigmaFrom.empty() ? std::string()
                                                     : "from MRPT's " + o.rangeSigmaFrom);
                },
                common::keyNumberText(TrackerOptions{}.rangeSigma))
            .real("bearing_sigma", MRLOC_KEY_FIELD(tracker.bearingSigma), {1e-6, 3}, "rad",
                  "a camera's bearing noise to a landmark (CObservationBearingRange), for the "
                  "tracker and its start-up")
            .choice(
                "sightings", MRLOC_KEY_FIELD(sightings),
                std::vector<std::pair<std::string, Sightings>>{{"range_bearing", Sightings::Both},
                                                               {"range", Sightings::Range},
                                                               {"bearing", Sightings::Bearing}},
                "what the tracker takes of a camera's sightings of the map's landmarks "
                "(CObservationBearingRange, ids through the beacon map; other ids, other "
                "robots, are counted and left out): `range_bearing`, `range` or `bearing`")
            .real("gate_probability", MRLOC_KEY_FIELD(tracker.gateProbability), {0.5, 1.0 - 1e-12},
                  "", "chi-square(1) gate on each range (and bearing) innovation")
            .choice("robust_loss", MRLOC_KEY_FIELD(tracker.robustLoss),
                    std::vector<std::pair<std::string, TrackerOptions::RobustLoss>>{
                        {"huber", TrackerOptions::RobustLoss::Huber},
                        {"mixture", TrackerOptions::RobustLoss::Mixture}},
                    "after the gate: `huber` (`huber_k`) or `mixture`, a Gaussian and a uniform "
                    "of share `outlier_share` (each measurement weighed by its probability of "
                    "being no gross error)")
            .real("outlier_share", MRLOC_KEY_FIELD(tracker.outlierShare), {0, 0.99}, "",
                  "`robust_loss = mixture`: the prior share of gross errors")
            .real("huber_k", MRLOC_KEY_FIELD(tracker.huberK), {0, 100}, "sigma",
                  "Huber's loss: a range or bearing that passed the gate with an innovation "
                  "beyond this many sigmas counts as if its variance were larger (its pull "
                  "capped at k sigmas' worth); `0`: the plain EKF update")
            .real("odometry_sigma_xy", MRLOC_KEY_FIELD(tracker.odomSigmaPerMetre), {0, 10}, "m/m",
                  "filter's odometry noise per reading, per metre of its increment")
            .real("odometry_sigma_phi", MRLOC_KEY_FIELD(tracker.odomSigmaPhiPerRad), {0, 10},
                  "rad/rad", "per radian turned")
            .real("odometry_sigma_phi_per_m", MRLOC_KEY_FIELD(tracker.odomSigmaPhiPerMetre),
                  {0, 10}, "rad/m", "per metre")
            .real("odometry_walk_xy", MRLOC_KEY_FIELD(tracker.odomWalkXY), {0, 10}, "m/sqrt(m)",
                  "the odometry's random walk along the path: its sd after 1 m whatever the "
                  "reading rate (the per-reading terms above add up to less as the rate grows); "
                  "`0` (the default) for mrloc's simulated logs, whose noise is per reading; "
                  "`mrloc import` writes 0.05 for a real log")
            .real("odometry_walk_phi", MRLOC_KEY_FIELD(tracker.odomWalkPhiPerRad), {0, 10},
                  "rad/sqrt(rad)", "heading's random walk, sd after 1 rad turned (import: 0.05)")
            .real("odometry_walk_phi_per_m", MRLOC_KEY_FIELD(tracker.odomWalkPhiPerMetre), {0, 10},
                  "rad/sqrt(m)", "heading's random walk, sd after 1 m travelled (import: 0.02)")
            .real("random_walk_sigma", MRLOC_KEY_FIELD(tracker.randomWalkSigma), {0, 100},
                  "m/sqrt(s)", "prediction when the rawlog has no odometry")
            .real("bootstrap_baseline", MRLOC_KEY_FIELD(tracker.bootstrapBaseline), {0.01, 100},
                  "m",
                  "the start-up fixes must span this (along the odometry's path) before they "
                  "give the start pose and heading")
            .real("range_window", MRLOC_KEY_FIELD(rangeWindow), {0, 60}, "s",
                  "ranges read one at a time (an observation too short for a fix: a UWB tag "
                  "ranging one anchor per exchange, a camera seeing a landmark or two) are "
                  "gathered over this span into one epoch of the beacons a fix with two to "
                  "spare needs, each moved to the newest reading's pose by the odometry between "
                  "them, until the tracker has started; in `fixes` mode, observations of one "
                  "range each make their fixes this way (doc/beacons.md, \"Ranges one at a "
                  "time\"); `0`: never")
            .integer("reset_after", MRLOC_KEY_FIELD(tracker.resetAfter), 1, 100000, "",
                     "epochs in a row lost (every range rejected, or a consistent fix with two "
                     "ranges to spare outside the filter's covariance) before starting again "
                     "from fixes")
            .flag("estimate_bias", MRLOC_KEY_FIELD(tracker.estimateBias),
                  "estimate each beacon's range offset and a common range scale online (`r = "
                  "(1 + scale) d + offset`); `false`: ranges are taken as unbiased")
            .real("bias_sigma", MRLOC_KEY_FIELD(tracker.biasSigma), {0, 10}, "m",
                  "prior sd of the offset common to every beacon (one link hardware)")
            .real("bias_spread", MRLOC_KEY_FIELD(tracker.biasSpread), {0, 10}, "m",
                  "prior sd of each beacon's own offset about the common one (UWB anchors with "
                  "their own antenna delays: a few cm)")
            .real("bias_drift", MRLOC_KEY_FIELD(tracker.biasDrift), {0, 10}, "m/sqrt(s)",
                  "random walk of each offset")
            .real("scale_sigma", MRLOC_KEY_FIELD(tracker.scaleSigma), {0, 1}, "",
                  "prior sd of the common scale (a speed of sound 1 % off: 3.4 m/s, about 6 K); "
                  "`0`: no scale state")
            // the RF beacon's side: aiming, scheduling and sections
            .choice("aiming", MRLOC_KEY_FIELD(system.activeAiming),
                    std::vector<std::pair<std::string, bool>>{{"active", true}, {"fixed", false}},
                    "`active`: heads turn to the robot's reported receiver before each epoch; "
                    "`fixed`: they point at the section's aim point")
            .choice(
                "scheduling", MRLOC_KEY_FIELD(system.scheduling),
                std::vector<std::pair<std::string, Scheduling>>{
                    {"priority", Scheduling::Priority}, {"round_robin", Scheduling::RoundRobin}},
                "`priority` (slots in proportion to speed) or `round_robin`")
            .real("min_speed", MRLOC_KEY_FIELD(system.minSpeed), {1e-6, 100}, "m/s",
                  "the priority's floor, so standing robots are still served")
            .real("handover_margin", MRLOC_KEY_FIELD(system.handoverMargin), {0, 1000}, "m",
                  "a neighbouring section's table is sent this close to its boundary (0: no "
                  "handover)")
            .real("registration_time", MRLOC_KEY_FIELD(system.registrationTime), {0, 1000}, "s",
                  "to receive a section's beacon table")
            .real("shot_interval", MRLOC_KEY_FIELD(system.shotInterval), {1e-4, 10}, "s",
                  "between two beacons' shots in an epoch (flight time + echoes dying out)")
            .integer("beacons_per_epoch", MRLOC_KEY_FIELD(system.beaconsPerEpoch), 0, 1000, "",
                     "the section's beacons fired per epoch, in turn from where the robot's "
                     "last epoch stopped (a radio beacon ranged one at a time: `1`); `0`: all")
            .integer("shots_per_beacon", MRLOC_KEY_FIELD(system.shotsPerBeacon), 1, 10, "",
                     "rounds of the section's beacons in one epoch: each beacon fires this many "
                     "times and a fix (`mode = fixes`) takes each beacon's mean range; the "
                     "tracker takes every shot")
            // read after the beacon map, in loadFromConfigFile: a section names its beacons
            .family(
                "section_<name>", "m", "",
                "`xmin ymin xmax ymax`; `section_<name>_beacons`: its beacon ids, the RF "
                "beacon first (the firing order), required; `section_<name>_aim`: where "
                "fixed heads point, `x y z` (the rectangle's centre, z = 0)",
                nullptr,
                [](const O& o, mrpt::config::CConfigFileBase& t,
                   const std::string& sec) { saveSections(o.system.sections, t, sec); },
                "(one section, `all`)")
            .family(
                "beacon_<id>", "m", "",
                "beacon position `x y z`. If no such key is given, MRPT's "
                "`[MetricMap_landmarksMap_00_creationOpts]` (`nBeacons`, `beacon_001_ID`, "
                "`beacon_001_x/y/z`, ...) is read",
                [](IniSection& s, O& o) { o.map = loadBeaconMap(s.config(), s); },
                [](const O& o, mrpt::config::CConfigFileBase& t, const std::string& sec) {
                    saveBeaconKeys(o.map, t, sec);
                },
                "(required)")
            .family("paper_reception_<id>", "%", "0 .. 100",
                    "paper 001's reception rate of beacon `<id>`, one per robot of `[scenario] "
                    "robots`, set beside the run's in the report",
                    loadPaperReception,
                    [](const O& o, mrpt::config::CConfigFileBase& t, const std::string& sec) {
                        for (const auto& [id, rates] : o.paperReception) {
                            std::string v;
                            for (double r : rates)
                                v += (v.empty() ? "" : " ") + common::keyValueText(r);
                            t.write(sec, "paper_reception_" + std::to_string(id), v);
                        }
                    });
    return table;
}

void BeaconOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& src,
                                       const std::string& section) {
    *this = BeaconOptions{};  // every key absent takes the struct's default: written once
    IniSection s(src, section);
    keys().load(s, *this);
    tracker.fix.knownHeight = threeD ? std::nullopt : std::optional<double>(0.0);  // per epoch
    system.sections = readSections(s, map);
    if (tracker.jitterWeights && !delayCompensation)
        s.fail("jitter_weights",
               "needs delay_compensation = true (the same link model predicts both)");
    setRangeDelay(src, *this);
    s.finish();
}

void BeaconOptions::saveToConfigFile(mrpt::config::CConfigFileBase& t,
                                     const std::string& section) const {
    keys().save(*this, t, section);
}

}  // namespace mrloc::beacons
