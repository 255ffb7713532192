#include <mrloc/common/KeyTable.h>
#include <mrloc/framesync/FramesyncConfig.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>

#include <algorithm>
#include <sstream>

namespace mrloc::framesync {

namespace {

/** The default rig: side-looking sonars left and right (seed 004 fig. 3) and one ahead. */
std::vector<SonarMount> defaultMounts() {
    using mrpt::poses::CPose3D;
    return {{"left", CPose3D(0, 0.15, 0.3, M_PI / 2, 0, 0)},
            {"right", CPose3D(0, -0.15, 0.3, -M_PI / 2, 0, 0)},
            {"front", CPose3D(0.2, 0, 0.3, 0, 0, 0)}};
}

constexpr const char* kSonarPrefix = "sonar_";

/** sonar_<name> = x y z yaw_deg: every key of the prefix that is not one of the rig's. */
void loadMounts(common::IniSection& s, FramesyncConfig& c) {
    auto& rig = c.rig;
    rig.mounts.clear();
    for (const auto& key : s.keys()) {
        if (key.rfind(kSonarPrefix, 0) != 0) continue;
        static const std::vector<std::string> kRigKeys{"sonar_aperture",  "sonar_min_range",
                                                       "sonar_max_range", "sonar_sigma",
                                                       "sonar_rate",      "sonar_fan_step"};
        if (std::find(kRigKeys.begin(), kRigKeys.end(), key) != kRigKeys.end()) continue;
        const auto v = s.reals(key, {}, 4);
        if (std::abs(v[0]) > 10 || std::abs(v[1]) > 10 || v[2] < 0 || v[2] > 10)
            s.fail(key, "expected x y z yaw_deg on the robot, within 10 m of its centre");
        rig.mounts.push_back(
            {key.substr(6), mrpt::poses::CPose3D(v[0], v[1], v[2], mrpt::DEG2RAD(v[3]), 0, 0)});
    }
    s.allowPrefix(kSonarPrefix);
    if (rig.mounts.empty()) rig.mounts = defaultMounts();
    // sonar ids by name, whatever the INI's order: effective.ini gives the same ids back
    std::sort(rig.mounts.begin(), rig.mounts.end(),
              [](const SonarMount& a, const SonarMount& b) { return a.name < b.name; });
    if (rig.mounts.size() > size_t(FramesyncConfig::kMaxSonars))
        s.fail(kSonarPrefix, mrpt::format("at most %ld sonars", FramesyncConfig::kMaxSonars));
}

void saveMounts(const FramesyncConfig& c, mrpt::config::CConfigFileBase& t,
                const std::string& section) {
    for (const auto& mount : c.rig.mounts)
        t.write(section, kSonarPrefix + mount.name,
                common::keyListText({mount.pose.x(), mount.pose.y(), mount.pose.z()}) + " " +
                    common::keyDegreesText(mount.pose.yaw()));
}

}  // namespace

const common::KeyTable<FramesyncConfig>& FramesyncConfig::keys() {
    using Cfg = FramesyncConfig;
    using OnRedefinition = TeamOptions::OnRedefinition;
    static const auto table =
        common::KeyTable<Cfg>("framesync")
            .flag("sharing", MRLOC_KEY_FIELD(team.sharing),
                  "`false`: every robot keeps its own odometry frame (walls are still found)")
            .custom(
                "priority", "", "",
                "robot names, highest priority of reference first; unlisted robots rank "
                "after, by name. The highest never redefines its frame",
                [](common::IniSection& s, Cfg& c) {
                    std::vector<std::string> order;
                    std::istringstream names(s.text("priority", ""));
                    for (std::string n; names >> n;) order.push_back(n);
                    try {
                        c.team.priority = PriorityOrder(order);
                    } catch (const std::exception&) {
                        s.fail("priority", "each robot once, highest first");
                    }
                },
                [](const Cfg& c) {
                    std::string order;
                    for (const auto& n : c.team.priority.listed())
                        order += (order.empty() ? "" : " ") + n;
                    return order;
                },
                "(by name)")
            .choice("on_redefinition", MRLOC_KEY_FIELD(team.onRedefinition),
                    std::vector<std::pair<std::string, OnRedefinition>>{
                        {"drop", OnRedefinition::Drop}, {"transform", OnRedefinition::Transform}},
                    "what the wall detector does with its ERPs when the frame is redefined: "
                    "`drop` them (paper 004 sec. 5.1) or `transform` them into the new frame")
            .real("erp_baseline", MRLOC_KEY_FIELD(team.detector.baseline), {0.005, 10}, "m",
                  "between the two sensor positions of an ERP pair; the normal's noise is "
                  "about sqrt(2) sonar sd / baseline")
            .real("pair_gap", MRLOC_KEY_FIELD(team.detector.maxPairGap), {"erp_baseline", 100}, "m",
                  "two readings further apart (a gap in the echoes) are not paired")
            .degrees("cone_margin", MRLOC_KEY_FIELD(team.detector.coneMargin), {0, 90},
                     "the wall's normal must lie within the sonar's half cone plus this")
            .degrees("group_angle", MRLOC_KEY_FIELD(team.detector.groupAngle), {0.1, 90},
                     "an ERP joins the current group if its normal is this near the group's")
            .real("group_gap", MRLOC_KEY_FIELD(team.detector.groupGap), {0.001, 100}, "m",
                  "and it lies this near the group's last ERP")
            .integer("min_erps", MRLOC_KEY_FIELD(team.detector.minErps), 2, 100000, "",
                     "ERPs a wall needs (two per pair)")
            .real("min_wall_length", MRLOC_KEY_FIELD(team.detector.minLength), {0, 1000}, "m",
                  "the shortest wall announced")
            .real("wall_length", MRLOC_KEY_FIELD(team.detector.wallLength),
                  {"min_wall_length", 1000}, "m",
                  "a group this long is announced and a new one starts (positive)")
            .real("max_residual", MRLOC_KEY_FIELD(team.detector.maxResidual), {0, 10}, "m",
                  "every ERP must lie this near the fitted line (about 4 sonar sd)")
            .degrees("max_ray_angle", MRLOC_KEY_FIELD(team.detector.maxRayAngle), {0, 90},
                     "every sonar ray must meet the fitted line this near a right angle")
            .degrees("max_bearing", MRLOC_KEY_FIELD(team.manager.match.maxBearing), {0.01, 90},
                     "two walls match if their bearings differ by less (paper 004: 20)")
            .real("max_distance", MRLOC_KEY_FIELD(team.manager.match.maxDistance), {1e-3, 100}, "m",
                  "and the robot's distances to them differ by less (paper 004: 50 cm)")
            .real("min_overlap", MRLOC_KEY_FIELD(team.manager.match.minOverlap), {0, 1000}, "m",
                  "the two segments must share once the frame is redefined (paper 004: they "
                  "\"intersect\", 0)")
            .real("max_age", MRLOC_KEY_FIELD(team.manager.maxAge), {0.1, 1e6}, "s",
                  "a wall stays in a robot's database")
            .choice("matching", MRLOC_KEY_FIELD(team.manager.match.general),
                    std::vector<std::pair<std::string, bool>>{{"local", false}, {"general", true}},
                    "`local`: the paper's sec. 4.3 tests alone (frames that differ by drift); "
                    "`general`: when no wall passes them, paper 004 sec. 3's general transform "
                    "from corners of two walls (frames that differ by any rotation and shift: "
                    "robots started apart, doc/framesync.md \"The general transform\")")
            .integer("general_support", MRLOC_KEY_FIELD(team.manager.match.generalSupport), 2, 1000,
                     "walls", "own walls a general transform must put on the other robot's walls")
            .family("sonar_<name>", "m, deg", "within 10 m, at most 64 sonars",
                    "(simulator) a sonar on every robot: `x y z yaw_deg`; without any, `left` "
                    "`0 0.15 0.3 90`, `right` `0 -0.15 0.3 -90` and `front` `0.2 0 0.3 0`; at "
                    "most 64",
                    loadMounts, saveMounts, "`left`, `right`, `front`")
            .degrees("sonar_aperture", MRLOC_KEY_FIELD(rig.aperture), {0.5, 120},
                     "(simulator) the cone's full width")
            .real("sonar_min_range", MRLOC_KEY_FIELD(rig.minRange), {0, 100}, "m",
                  "(simulator) a reading nearer is 0: no echo")
            .real("sonar_max_range", MRLOC_KEY_FIELD(rig.maxRange), {"sonar_min_range", 100}, "m",
                  "(simulator) a reading further is 0: no echo")
            .real("sonar_sigma", MRLOC_KEY_FIELD(rig.sigma), {0, 1}, "m",
                  "(simulator) Gaussian range noise")
            .real("sonar_rate", MRLOC_KEY_FIELD(rig.rate), {0.1, 1000}, "Hz",
                  "(simulator) every sonar; a whole number of `[scenario] dt` steps")
            .degrees("sonar_fan_step", MRLOC_KEY_FIELD(rig.fanStep), {0.05, 10},
                     "(simulator) between the rays cast over the cone")
            .integer("experiment_seeds", MRLOC_KEY_FIELD(experimentSeeds), 0, kMaxSeeds, "",
                     "the INI's scenario simulated again with seeds `seed`, `seed + 1`, ... (0: "
                     "no experiment)")
            .integer("experiment_sweep_seeds", MRLOC_KEY_FIELD(sweepSeeds), 0, kMaxSeeds, "",
                     "seeds per value of each sweep (0: no sweep)")
            .numbers("experiment_noise", MRLOC_KEY_FIELD(sweepNoise), {0, 1, size_t(kMaxSweep)},
                     "m",
                     "sonar noise sd of the noise sweep; each run sets `erp_baseline` to at least "
                     "20 sd and `max_residual` to at least 4 sd")
            .numbers("experiment_drift", MRLOC_KEY_FIELD(sweepDrift), {0, 100, size_t(kMaxSweep)},
                     "",
                     "factors on every robot's four systematic odometry keys, of the drift "
                     "sweep");
    return table;
}

void FramesyncConfig::loadFromConfigFile(const mrpt::config::CConfigFileBase& src,
                                         const std::string& section) {
    *this = FramesyncConfig{};  // every key absent takes the struct's default: written once
    common::IniSection s(src, section);
    keys().load(s, *this);
    if (!(team.detector.wallLength > 0)) s.fail("wall_length", "must be positive");
    s.finish();
}

void FramesyncConfig::saveToConfigFile(mrpt::config::CConfigFileBase& t,
                                       const std::string& section) const {
    keys().save(*this, t, section);
}

}  // namespace mrloc::framesync
