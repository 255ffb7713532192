#include <mrloc/common/IniSection.h>
#include <mrloc/framesync/FramesyncConfig.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>

#include <algorithm>
#include <sstream>

namespace mrloc::framesync {

namespace {

std::string join(const std::vector<double>& xs) {
    std::string out;
    for (const double x : xs) out += (out.empty() ? "" : " ") + mrpt::format("%.17g", x);
    return out;
}

std::vector<double> sweep(common::IniSection& s, const std::string& key, std::vector<double> def,
                          double lo, double hi) {
    const auto v = s.reals(key, std::move(def));
    if (v.size() > size_t(FramesyncConfig::kMaxSweep))
        s.fail(key, mrpt::format("at most %ld values", FramesyncConfig::kMaxSweep));
    for (const double x : v)
        if (!(x >= lo && x <= hi)) s.fail(key, mrpt::format("every value in [%g, %g]", lo, hi));
    return v;
}

/** The default rig: side-looking sonars left and right (seed 004 fig. 3) and one ahead. */
std::vector<SonarMount> defaultMounts() {
    using mrpt::poses::CPose3D;
    return {{"left", CPose3D(0, 0.15, 0.3, M_PI / 2, 0, 0)},
            {"right", CPose3D(0, -0.15, 0.3, -M_PI / 2, 0, 0)},
            {"front", CPose3D(0.2, 0, 0.3, 0, 0, 0)}};
}

}  // namespace

void FramesyncConfig::loadFromConfigFile(const mrpt::config::CConfigFileBase& src,
                                         const std::string& section) {
    *this = FramesyncConfig{};  // every key absent takes the struct's default: written once
    common::IniSection s(src, section);
    team.sharing = s.flag("sharing", team.sharing);
    std::vector<std::string> order;
    std::istringstream names(s.text("priority", ""));
    for (std::string n; names >> n;) order.push_back(n);
    try {
        team.priority = PriorityOrder(order);
    } catch (const std::exception&) {
        s.fail("priority", "each robot once, highest first");
    }
    team.onRedefinition = s.choice("on_redefinition", "drop", {"drop", "transform"}) == "drop"
                              ? TeamOptions::OnRedefinition::Drop
                              : TeamOptions::OnRedefinition::Transform;
    auto& d = team.detector;
    d.baseline = s.real("erp_baseline", d.baseline, 0.005, 10);
    d.maxPairGap = s.real("pair_gap", d.maxPairGap, d.baseline, 100);
    d.coneMargin = mrpt::DEG2RAD(s.real("cone_margin", 5, 0, 90));
    d.groupAngle = mrpt::DEG2RAD(s.real("group_angle", 10, 0.1, 90));
    d.groupGap = s.real("group_gap", d.groupGap, 0.001, 100);
    d.minErps = size_t(s.integer("min_erps", long(d.minErps), 2, 100000));
    d.minLength = s.real("min_wall_length", d.minLength, 0, 1000);
    d.wallLength = s.real("wall_length", d.wallLength, d.minLength, 1000);
    if (!(d.wallLength > 0)) s.fail("wall_length", "must be positive");
    d.maxResidual = s.real("max_residual", d.maxResidual, 0, 10);
    d.maxRayAngle = mrpt::DEG2RAD(s.real("max_ray_angle", 15, 0, 90));
    auto& m = team.manager;
    m.match.maxBearing = mrpt::DEG2RAD(s.real("max_bearing", 20, 0.01, 90));
    m.match.maxDistance = s.real("max_distance", m.match.maxDistance, 1e-3, 100);
    m.match.minOverlap = s.real("min_overlap", m.match.minOverlap, 0, 1000);
    m.maxAge = s.real("max_age", m.maxAge, 0.1, 1e6);
    m.match.general = s.choice("matching", "local", {"local", "general"}) == "general";
    m.match.generalSupport =
        size_t(s.integer("general_support", long(m.match.generalSupport), 2, 1000));
    // the simulator's sonars
    rig.mounts.clear();
    for (const auto& key : s.keys()) {
        if (key.rfind("sonar_", 0) != 0) continue;
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
    s.allowPrefix("sonar_");
    if (rig.mounts.empty()) rig.mounts = defaultMounts();
    // sonar ids by name, whatever the INI's order: effective.ini gives the same ids back
    std::sort(rig.mounts.begin(), rig.mounts.end(),
              [](const SonarMount& a, const SonarMount& b) { return a.name < b.name; });
    if (rig.mounts.size() > size_t(kMaxSonars))
        s.fail("sonar_", mrpt::format("at most %ld sonars", kMaxSonars));
    rig.aperture = mrpt::DEG2RAD(s.real("sonar_aperture", 25, 0.5, 120));
    rig.minRange = s.real("sonar_min_range", rig.minRange, 0, 100);
    rig.maxRange = s.real("sonar_max_range", rig.maxRange, rig.minRange + 1e-3, 100);
    rig.sigma = s.real("sonar_sigma", rig.sigma, 0, 1);
    rig.rate = s.real("sonar_rate", rig.rate, 0.1, 1000);
    rig.fanStep = mrpt::DEG2RAD(s.real("sonar_fan_step", 0.5, 0.05, 10));
    // the experiment
    experimentSeeds = size_t(s.integer("experiment_seeds", long(experimentSeeds), 0, kMaxSeeds));
    sweepSeeds = size_t(s.integer("experiment_sweep_seeds", long(sweepSeeds), 0, kMaxSeeds));
    sweepNoise = sweep(s, "experiment_noise", sweepNoise, 0, 1);
    sweepDrift = sweep(s, "experiment_drift", sweepDrift, 0, 100);
    s.finish();
}

void FramesyncConfig::saveToConfigFile(mrpt::config::CConfigFileBase& t,
                                       const std::string& section) const {
    t.write(section, "sharing", team.sharing);
    std::string order;
    for (const auto& n : team.priority.listed()) order += (order.empty() ? "" : " ") + n;
    t.write(section, "priority", order);
    t.write(section, "on_redefinition",
            team.onRedefinition == TeamOptions::OnRedefinition::Drop ? "drop" : "transform");
    const auto& d = team.detector;
    t.write(section, "erp_baseline", d.baseline);
    t.write(section, "pair_gap", d.maxPairGap);
    t.write(section, "cone_margin", mrpt::RAD2DEG(d.coneMargin));
    t.write(section, "group_angle", mrpt::RAD2DEG(d.groupAngle));
    t.write(section, "group_gap", d.groupGap);
    t.write(section, "min_erps", int(d.minErps));
    t.write(section, "min_wall_length", d.minLength);
    t.write(section, "wall_length", d.wallLength);
    t.write(section, "max_residual", d.maxResidual);
    t.write(section, "max_ray_angle", mrpt::RAD2DEG(d.maxRayAngle));
    const auto& m = team.manager;
    t.write(section, "max_bearing", mrpt::RAD2DEG(m.match.maxBearing));
    t.write(section, "max_distance", m.match.maxDistance);
    t.write(section, "min_overlap", m.match.minOverlap);
    t.write(section, "max_age", m.maxAge);
    t.write(section, "matching", m.match.general ? "general" : "local");
    t.write(section, "general_support", int(m.match.generalSupport));
    for (const auto& mount : rig.mounts)
        t.write(section, "sonar_" + mount.name,
                mrpt::format("%g %g %g %g", mount.pose.x(), mount.pose.y(), mount.pose.z(),
                             mrpt::RAD2DEG(mount.pose.yaw())));
    t.write(section, "sonar_aperture", mrpt::RAD2DEG(rig.aperture));
    t.write(section, "sonar_min_range", rig.minRange);
    t.write(section, "sonar_max_range", rig.maxRange);
    t.write(section, "sonar_sigma", rig.sigma);
    t.write(section, "sonar_rate", rig.rate);
    t.write(section, "sonar_fan_step", mrpt::RAD2DEG(rig.fanStep));
    t.write(section, "experiment_seeds", int(experimentSeeds));
    t.write(section, "experiment_sweep_seeds", int(sweepSeeds));
    t.write(section, "experiment_noise", join(sweepNoise));
    t.write(section, "experiment_drift", join(sweepDrift));
}

}  // namespace mrloc::framesync
