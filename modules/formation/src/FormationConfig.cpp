#include <mrloc/common/Error.h>
#include <mrloc/common/IniSection.h>
#include <mrloc/formation/FormationConfig.h>
#include <mrloc/formation/Routes.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>

#include <cmath>
#include <iterator>
#include <sstream>

namespace mrloc::formation {

namespace {

const std::vector<std::string> kCarryNames{"base", "reflection", "algorithm_one"};

std::string join(const std::vector<double>& xs) {
    std::string out;
    for (const double x : xs) out += (out.empty() ? "" : " ") + mrpt::format("%.17g", x);
    return out;
}

}  // namespace

std::vector<std::string> formationRobotNames(size_t robots) {
    std::vector<std::string> names;
    for (size_t i = 0; i < robots; ++i) names.push_back("f" + std::to_string(i + 1));
    return names;
}

std::vector<TPoint2D> FormationConfig::worldRoute() const {
    std::vector<TPoint2D> out;
    for (const auto& p : waypoints) out.push_back(p + origin);
    return out;
}

mrpt::img::TCamera FormationConfig::cameraIntrinsics() const {
    mrpt::img::TCamera k;
    k.ncols = uint32_t(cameraWidth);
    k.nrows = uint32_t(cameraRows);
    k.setIntrinsicParamsFromValues(cameraFocal, cameraFocal, double(cameraWidth) / 2,
                                   double(cameraRows) / 2);
    return k;
}

std::vector<TPoint2D> FormationConfig::worldStrip() const {
    auto strip = initialStrip(robots, formation.side);
    for (auto& p : strip) p = p + origin;
    return strip;
}

void FormationConfig::loadFromConfigFile(const mrpt::config::CConfigFileBase& src,
                                         const std::string& section) {
    *this = FormationConfig{};  // every key absent takes the struct's default: written once
    common::IniSection s(src, section);
    mode = s.choice("mode", "model", {"model", "pixel"}) == "model" ? Mode::Model : Mode::Pixel;
    robots = size_t(s.integer("robots", long(robots), 4, kMaxRobots));
    formation.side = s.real("side", formation.side, 0.1, 100);
    formation.safetyMargin = s.real("safety_margin", formation.safetyMargin, 0, 100);
    const auto o = s.reals("origin", {3, 3}, 2);
    origin = {o[0], o[1]};
    routeName = s.choice("route", "many_turns", {"many_turns", "patrol", "custom"});
    if (routeName == "custom") {
        const auto xy = s.requireReals("waypoints");
        if (xy.size() < 2 || xy.size() % 2 != 0)
            s.fail("waypoints", "give x y pairs: the first is where the formation starts");
        waypoints.clear();
        for (size_t i = 0; i < xy.size(); i += 2) waypoints.push_back({xy[i], xy[i + 1]});
        if (waypoints.size() < 2) s.fail("waypoints", "give at least a start and a destination");
    } else {
        if (s.has("waypoints")) s.fail("waypoints", "only with route = custom");
        waypoints = route(routeName);
    }
    wheelRadius = s.real("wheel_radius", wheelRadius, 1e-3, 10);
    wheelSpeed = s.real("wheel_speed", wheelSpeed, 1e-2, 1000);
    maxTurnRate = s.real("max_turn_rate", maxTurnRate, 1e-2, 100);
    const std::string c = s.choice("carry", "base", kCarryNames);
    carry = MarchOptions::Carry(std::find(kCarryNames.begin(), kCarryNames.end(), c) -
                                kCarryNames.begin());
    vertexErrors.lateralMean = s.real("lateral_error_mean", vertexErrors.lateralMean, 1e-6, 10);
    vertexErrors.lateralSd = s.real("lateral_error_sd", vertexErrors.lateralSd, 1e-6, 10);
    vertexErrors.longitudinalMean =
        s.real("longitudinal_error_mean", vertexErrors.longitudinalMean, 1e-6, 10);
    vertexErrors.longitudinalSd =
        s.real("longitudinal_error_sd", vertexErrors.longitudinalSd, 1e-6, 10);
    auto& dr = deadReckoning;
    dr.headingModel = s.choice("heading_model", "gyro", {"gyro", "heading"}) == "gyro"
                          ? DeadReckoningOptions::HeadingModel::Gyro
                          : DeadReckoningOptions::HeadingModel::Heading;
    dr.headingTau = s.real("heading_tau", dr.headingTau, 1e-3, 1e6);
    dr.headingSigma = mrpt::DEG2RAD(s.real("heading_sigma", 2.5, 0, 90));
    dr.headingWhite = mrpt::DEG2RAD(s.real("heading_white", 0.8, 0, 90));
    dr.radiusBias = s.real("radius_bias", dr.radiusBias, -0.5, 0.5);
    dr.scaleFactor = s.real("scale_factor", dr.scaleFactor, -0.5, 0.5);
    dr.speedNoise = s.real("speed_noise", dr.speedNoise, 0, 10);
    dr.dt = s.real("dr_period", dr.dt, 1e-3, 10);
    cameraWidth = size_t(s.integer("camera_width", long(cameraWidth), 160, 4096));
    if (cameraWidth % 4 != 0)  // the renderer reads rows of whole 4-byte words
        s.fail("camera_width", "a multiple of 4 px");
    cameraRows = size_t(s.integer("camera_rows", long(cameraRows), 60, 4096));
    cameraFocal = s.real("camera_focal", cameraFocal, 50, 5000);
    pixelTolerance = s.real("pixel_tolerance", pixelTolerance, 0.1, 50);
    together = s.choice("corrections", "together", {"together", "one_per_frame"}) == "together";
    latticeFit = s.flag("lattice_fit", latticeFit);
    lens.k1 = s.real("lens_k1", lens.k1, -1, 1);
    lens.k2 = s.real("lens_k2", lens.k2, -1, 1);
    lens.p1 = s.real("lens_p1", lens.p1, -0.1, 0.1);
    lens.p2 = s.real("lens_p2", lens.p2, -0.1, 0.1);
    lens.calibrationError = s.real("lens_calibration_error", lens.calibrationError, -1, 1);
    lens.blur = s.real("camera_blur", lens.blur, 0, 10);
    lens.noise = s.real("camera_noise", lens.noise, 0, 100);
    lens.exposure = s.real("camera_exposure", lens.exposure, 0.05, 4);
    maneuverNoise.slip = s.real("wheel_slip", maneuverNoise.slip, 0, 0.5);
    lateral = s.choice("algorithm_one", "midpoint", {"paper", "midpoint"}) == "paper"
                  ? AlgorithmOneOptions::Lateral::Paper
                  : AlgorithmOneOptions::Lateral::Midpoint;
    gateStop = s.real("gate_stop", gateStop, 0.3, 10);
    maneuverNoise.turn = s.real("turn_noise", maneuverNoise.turn, 0, 0.5);
    maneuverNoise.drive = s.real("drive_noise", maneuverNoise.drive, 0, 0.5);
    obstacleSensor.rays = int(s.integer("obstacle_rays", long(obstacleSensor.rays), 8, 3600));
    obstacleSensor.maxRange = s.real("obstacle_range", obstacleSensor.maxRange, 0.1, 100);
    obstacleSensor.rangeSigma = s.real("obstacle_sigma", obstacleSensor.rangeSigma, 0, 1);
    obstacleSensorHeight = s.real("obstacle_height", obstacleSensorHeight, 0, 10);
    obstacleCell = s.real("obstacle_cell", obstacleCell, 0.01, 10);
    maxMoves = size_t(s.integer("max_moves", long(maxMoves), 1, kMaxMoves));
    runs = size_t(s.integer("runs", long(runs), 0, kMaxRuns));
    experimentSpeeds = s.reals("experiment_speeds", experimentSpeeds);
    if (experimentSpeeds.empty()) s.fail("experiment_speeds", "give at least one wheel speed");
    if (experimentSpeeds.size() > 8)  // each is `runs` runs of every route
        s.fail("experiment_speeds", "at most 8 wheel speeds");
    for (const double w : experimentSpeeds)
        if (!(w >= 1e-2 && w <= 1000)) s.fail("experiment_speeds", "each from 0.01 to 1000 rad/s");
    std::istringstream names(s.text("experiment_routes", "many_turns patrol"));
    experimentRoutes = {std::istream_iterator<std::string>(names), {}};
    if (experimentRoutes.empty()) s.fail("experiment_routes", "give many_turns, patrol or both");
    if (experimentRoutes.size() > 2)
        s.fail("experiment_routes", "many_turns, patrol or both, once each");
    for (const auto& r : experimentRoutes)
        if (r != "many_turns" && r != "patrol")
            s.fail("experiment_routes", "'" + r + "': expected many_turns or patrol");
    experimentRobotsMax =
        size_t(s.integer("experiment_robots_max", long(experimentRobotsMax), 4, 50));
    cameraStarts = size_t(s.integer("camera_starts", long(cameraStarts), 0, 27));
    pixelRuns = size_t(s.integer("pixel_runs", long(pixelRuns), 0, kMaxPixelRuns));
    if (cameraStarts != 0 && cameraStarts != 27)
        s.fail("camera_starts", "0 (none) or 27 (the 3 x 3 x 3 grid of starts)");
    // without the key, the experiment draws from the run's seed (--seed reaches it)
    experimentSeed = common::subSeed(s, "experiment_seed", common::runSeed(src));
    s.finish();
}

void FormationConfig::saveToConfigFile(mrpt::config::CConfigFileBase& t,
                                       const std::string& section) const {
    t.write(section, "mode", std::string(mode == Mode::Model ? "model" : "pixel"));
    t.write(section, "robots", int(robots));
    t.write(section, "side", formation.side);
    t.write(section, "safety_margin", formation.safetyMargin);
    t.write(section, "origin", join({origin.x, origin.y}));
    t.write(section, "route", routeName);
    if (routeName == "custom") {
        std::vector<double> xy;
        for (const auto& p : waypoints) xy.push_back(p.x), xy.push_back(p.y);
        t.write(section, "waypoints", join(xy));
    }
    t.write(section, "wheel_radius", wheelRadius);
    t.write(section, "wheel_speed", wheelSpeed);
    t.write(section, "max_turn_rate", maxTurnRate);
    t.write(section, "carry", kCarryNames[size_t(carry)]);
    t.write(section, "lateral_error_mean", vertexErrors.lateralMean);
    t.write(section, "lateral_error_sd", vertexErrors.lateralSd);
    t.write(section, "longitudinal_error_mean", vertexErrors.longitudinalMean);
    t.write(section, "longitudinal_error_sd", vertexErrors.longitudinalSd);
    const auto& dr = deadReckoning;
    t.write(section, "heading_model",
            std::string(dr.headingModel == DeadReckoningOptions::HeadingModel::Gyro ? "gyro"
                                                                                    : "heading"));
    t.write(section, "heading_tau", dr.headingTau);
    t.write(section, "heading_sigma", mrpt::RAD2DEG(dr.headingSigma));
    t.write(section, "heading_white", mrpt::RAD2DEG(dr.headingWhite));
    t.write(section, "radius_bias", dr.radiusBias);
    t.write(section, "scale_factor", dr.scaleFactor);
    t.write(section, "speed_noise", dr.speedNoise);
    t.write(section, "dr_period", dr.dt);
    t.write(section, "camera_width", int(cameraWidth));
    t.write(section, "camera_rows", int(cameraRows));
    t.write(section, "camera_focal", cameraFocal);
    t.write(section, "pixel_tolerance", pixelTolerance);
    t.write(section, "corrections", std::string(together ? "together" : "one_per_frame"));
    t.write(section, "lattice_fit", latticeFit);
    t.write(section, "lens_k1", lens.k1);
    t.write(section, "lens_k2", lens.k2);
    t.write(section, "lens_p1", lens.p1);
    t.write(section, "lens_p2", lens.p2);
    t.write(section, "lens_calibration_error", lens.calibrationError);
    t.write(section, "camera_blur", lens.blur);
    t.write(section, "camera_noise", lens.noise);
    t.write(section, "camera_exposure", lens.exposure);
    t.write(section, "wheel_slip", maneuverNoise.slip);
    t.write(section, "algorithm_one",
            std::string(lateral == AlgorithmOneOptions::Lateral::Paper ? "paper" : "midpoint"));
    t.write(section, "gate_stop", gateStop);
    t.write(section, "turn_noise", maneuverNoise.turn);
    t.write(section, "drive_noise", maneuverNoise.drive);
    t.write(section, "obstacle_rays", obstacleSensor.rays);
    t.write(section, "obstacle_range", obstacleSensor.maxRange);
    t.write(section, "obstacle_sigma", obstacleSensor.rangeSigma);
    t.write(section, "obstacle_height", obstacleSensorHeight);
    t.write(section, "obstacle_cell", obstacleCell);
    t.write(section, "max_moves", int(maxMoves));
    t.write(section, "runs", int(runs));
    t.write(section, "experiment_speeds", join(experimentSpeeds));
    std::string routes;
    for (const auto& r : experimentRoutes) routes += (routes.empty() ? "" : " ") + r;
    t.write(section, "experiment_routes", routes);
    t.write(section, "experiment_robots_max", int(experimentRobotsMax));
    t.write(section, "camera_starts", int(cameraStarts));
    t.write(section, "pixel_runs", int(pixelRuns));
    if (experimentSeed.given)
        t.write(section, "experiment_seed", std::to_string(experimentSeed.value));
}

}  // namespace mrloc::formation
