#include <mrloc/common/Error.h>
#include <mrloc/common/KeyTable.h>
#include <mrloc/formation/FormationConfig.h>
#include <mrloc/formation/Routes.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>

#include <cmath>
#include <iterator>
#include <sstream>

namespace mrloc::formation {

namespace {

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

const common::KeyTable<FormationConfig>& FormationConfig::keys() {
    using Cfg = FormationConfig;
    using Heading = DeadReckoningOptions::HeadingModel;
    using Lateral = AlgorithmOneOptions::Lateral;
    using Carry = MarchOptions::Carry;
    static const auto table =
        common::KeyTable<Cfg>("formation")
            .choice("mode", MRLOC_KEY_FIELD(mode),
                    std::vector<std::pair<std::string, Mode>>{{"model", Mode::Model},
                                                              {"pixel", Mode::Pixel}},
                    "where a move ends: `model` (the paper's per-step errors drawn, fast) or "
                    "`pixel` (the moving robot's cameras steer it, frame by frame)")
            .integer("robots", MRLOC_KEY_FIELD(robots), 4, kMaxRobots, "",
                     "N (four tags per robot in the 36h11 family)")
            .real("side", MRLOC_KEY_FIELD(formation.side), {0.1, 100}, "m", "the triangles' side")
            .real("safety_margin", MRLOC_KEY_FIELD(formation.safetyMargin), {0, 100}, "m",
                  "beyond an obstacle that a path must keep out of")
            .custom(
                "origin", "m", "",
                "`x y`: where the paper's (0, 0) is in the room; every route point must be "
                "`side` inside `[world]`'s room",
                [](common::IniSection& s, Cfg& c) {
                    const auto o = s.reals("origin", {c.origin.x, c.origin.y}, 2);
                    c.origin = {o[0], o[1]};
                },
                [](const Cfg& c) {
                    return join({c.origin.x, c.origin.y});
                },
                "3 3")
            .choice("route", MRLOC_KEY_FIELD(routeName), {"many_turns", "patrol", "custom"},
                    "`many_turns` (fig. 12), `patrol` (fig. 13) or `custom` (`waypoints`)")
            .custom(
                "waypoints", "m", "",
                "with `route = custom`: `x y x y ...`, paper frame; the first is the strip's "
                "centre, the last the destination",
                [](common::IniSection& s, Cfg& c) {
                    if (c.routeName != "custom") {
                        if (s.has("waypoints")) s.fail("waypoints", "only with route = custom");
                        (void)s.text("waypoints", "");
                        c.waypoints = route(c.routeName);
                        return;
                    }
                    const auto xy = s.requireReals("waypoints");
                    if (xy.size() < 2 || xy.size() % 2 != 0)
                        s.fail("waypoints",
                               "give x y pairs: the first is where the formation starts");
                    c.waypoints.clear();
                    for (size_t i = 0; i < xy.size(); i += 2)
                        c.waypoints.push_back({xy[i], xy[i + 1]});
                    if (c.waypoints.size() < 2)
                        s.fail("waypoints", "give at least a start and a destination");
                },
                [](const Cfg& c) -> std::optional<std::string> {
                    if (c.routeName != "custom") return std::nullopt;
                    std::vector<double> xy;
                    for (const auto& p : c.waypoints) xy.push_back(p.x), xy.push_back(p.y);
                    return join(xy);
                },
                "(none)")
            .real("wheel_radius", MRLOC_KEY_FIELD(wheelRadius), {1e-3, 10}, "m",
                  "the robots' speed is `wheel_radius` x `wheel_speed`")
            .real("wheel_speed", MRLOC_KEY_FIELD(wheelSpeed), {1e-2, 1000}, "rad/s",
                  "the wheels' turn rate when driving")
            .real("max_turn_rate", MRLOC_KEY_FIELD(maxTurnRate), {1e-2, 100}, "rad/s",
                  "turning on the spot")
            .choice(
                "carry", MRLOC_KEY_FIELD(carry),
                std::vector<std::pair<std::string, Carry>>{{"base", Carry::Base},
                                                           {"reflection", Carry::Reflection},
                                                           {"algorithm_one", Carry::AlgorithmOne}},
                "model mode: how a move's error carries on (doc/formation.md)")
            .real("lateral_error_mean", MRLOC_KEY_FIELD(vertexErrors.lateralMean), {1e-6, 10}, "m",
                  "per-step error along the new triangle's base (fig. 11)")
            .real("lateral_error_sd", MRLOC_KEY_FIELD(vertexErrors.lateralSd), {1e-6, 10}, "m",
                  "its deviation")
            .real("longitudinal_error_mean", MRLOC_KEY_FIELD(vertexErrors.longitudinalMean),
                  {1e-6, 10}, "m", "per-step error across the base (fig. 11)")
            .real("longitudinal_error_sd", MRLOC_KEY_FIELD(vertexErrors.longitudinalSd), {1e-6, 10},
                  "m", "its deviation")
            .choice("heading_model", MRLOC_KEY_FIELD(deadReckoning.headingModel),
                    std::vector<std::pair<std::string, Heading>>{{"gyro", Heading::Gyro},
                                                                 {"heading", Heading::Heading}},
                    "dead reckoning's heading error: `gyro` (the Gauss-Markov process is the "
                    "gyro's rate error) or `heading` (it is the heading's)")
            .real("heading_tau", MRLOC_KEY_FIELD(deadReckoning.headingTau), {1e-3, 1e6}, "s",
                  "the process's time constant (paper 003 sec. 4.2)")
            .degrees("heading_sigma", MRLOC_KEY_FIELD(deadReckoning.headingSigma), {0, 90},
                     "the process's deviation (paper 003 sec. 4.2)")
            .degrees("heading_white", MRLOC_KEY_FIELD(deadReckoning.headingWhite), {0, 90},
                     "white noise on it (paper 003 sec. 4.2)")
            .real("radius_bias", MRLOC_KEY_FIELD(deadReckoning.radiusBias), {-0.5, 0.5}, "m",
                  "the wheel speed sensor's radius error (paper 003 eq. 3)")
            .real("scale_factor", MRLOC_KEY_FIELD(deadReckoning.scaleFactor), {-0.5, 0.5}, "",
                  "its scale factor error (paper 003 eq. 3)")
            .real("speed_noise", MRLOC_KEY_FIELD(deadReckoning.speedNoise), {0, 10}, "m/s",
                  "its noise (paper 003 eq. 3)")
            .real("dr_period", MRLOC_KEY_FIELD(deadReckoning.dt), {1e-3, 10}, "s",
                  "between dead-reckoning readings; a whole number of `[scenario] dt`")
            .integer("camera_width", MRLOC_KEY_FIELD(cameraWidth), 160, 4096, "px",
                     "pixel mode: the front and rear cameras' picture width, a multiple of 4")
            .integer("camera_rows", MRLOC_KEY_FIELD(cameraRows), 60, 4096, "px",
                     "pixel mode: its rows, a band about the horizon, where the tags stand at "
                     "the cameras' height")
            .real("camera_focal", MRLOC_KEY_FIELD(cameraFocal), {50, 5000}, "px",
                  "pixel mode: the cameras' focal length (242.5 at 640 px wide is a 105-degree "
                  "field of view)")
            .real("pixel_tolerance", MRLOC_KEY_FIELD(pixelTolerance), {0.1, 50}, "px",
                  "pixel mode: within which Algorithm 1's conditions count as met")
            .choice("corrections", MRLOC_KEY_FIELD(together),
                    std::vector<std::pair<std::string, bool>>{{"together", true},
                                                              {"one_per_frame", false}},
                    "pixel mode: `together` (every correction one frame asks for, executed "
                    "before the next frame) or `one_per_frame` (the paper's steps one at a "
                    "time: about 1.7 times the frames)")
            .flag("lattice_fit", MRLOC_KEY_FIELD(latticeFit),
                  "pixel mode, N >= 5: after Algorithm 1, fit the pose to every robot the rear "
                  "camera sees (bearings) and correct the vertex by it (ours, beyond the paper; "
                  "measured no better, doc/formation.md)")
            .real("lens_k1", MRLOC_KEY_FIELD(lens.k1), {-1, 1}, "",
                  "pixel mode, camera model: the lens's radial distortion, OpenCV's model; the "
                  "robot undistorts the tags' corners")
            .real("lens_k2", MRLOC_KEY_FIELD(lens.k2), {-1, 1}, "", "the same, second order")
            .real("lens_p1", MRLOC_KEY_FIELD(lens.p1), {-0.1, 0.1}, "",
                  "pixel mode, camera model: tangential distortion")
            .real("lens_p2", MRLOC_KEY_FIELD(lens.p2), {-0.1, 0.1}, "", "the same, second term")
            .real("lens_calibration_error", MRLOC_KEY_FIELD(lens.calibrationError), {-1, 1}, "",
                  "pixel mode, camera model: the robot's own distortion coefficients are the "
                  "lens's times 1 + this (-1: it does not undistort)")
            .real("camera_blur", MRLOC_KEY_FIELD(lens.blur), {0, 10}, "px",
                  "pixel mode, camera model: Gaussian blur sd")
            .real("camera_noise", MRLOC_KEY_FIELD(lens.noise), {0, 100}, "grey levels",
                  "pixel mode, camera model: sensor noise sd")
            .real("camera_exposure", MRLOC_KEY_FIELD(lens.exposure), {0.05, 4}, "",
                  "pixel mode, camera model: gain on the levels (saturating)")
            .real("wheel_slip", MRLOC_KEY_FIELD(maneuverNoise.slip), {0, 0.5}, "",
                  "pixel mode: the share of each turn and drive the wheels lose, half-normal "
                  "with this sd")
            .choice("algorithm_one", MRLOC_KEY_FIELD(lateral),
                    std::vector<std::pair<std::string, Lateral>>{{"paper", Lateral::Paper},
                                                                 {"midpoint", Lateral::Midpoint}},
                    "pixel mode: Algorithm 1's lateral condition, `midpoint` (ours: the anchor "
                    "in line with the base's midpoint) or `paper` (d_m1 = d_m2, which amplifies "
                    "errors from move to move; doc/formation.md)")
            .real("gate_stop", MRLOC_KEY_FIELD(gateStop), {0.3, 10}, "m",
                  "pixel mode: before a gate between beacons, where the robot centres the gate "
                  "again")
            .real("turn_noise", MRLOC_KEY_FIELD(maneuverNoise.turn), {0, 0.5}, "",
                  "pixel mode: relative sd of each turn")
            .real("drive_noise", MRLOC_KEY_FIELD(maneuverNoise.drive), {0, 0.5}, "",
                  "pixel mode: relative sd of each drive")
            .integer("obstacle_rays", MRLOC_KEY_FIELD(obstacleSensor.rays), 8, 3600, "",
                     "the obstacle sensor's beams over 360 degrees")
            .real("obstacle_range", MRLOC_KEY_FIELD(obstacleSensor.maxRange), {0.1, 100}, "m",
                  "its range")
            .real("obstacle_sigma", MRLOC_KEY_FIELD(obstacleSensor.rangeSigma), {0, 1}, "m",
                  "its noise")
            .real("obstacle_height", MRLOC_KEY_FIELD(obstacleSensorHeight), {0, 10}, "m",
                  "its height above the floor")
            .real("obstacle_cell", MRLOC_KEY_FIELD(obstacleCell), {0.01, 10}, "m",
                  "detections are shared one per cell")
            .integer("max_moves", MRLOC_KEY_FIELD(maxMoves), 1, kMaxMoves, "",
                     "a route that needs more is an error")
            .integer("runs", MRLOC_KEY_FIELD(runs), 0, kMaxRuns, "",
                     "Monte Carlo runs per route and speed of the experiment (Table 1, figs. "
                     "11, 14, 15); 0: none")
            .numbers("experiment_speeds", MRLOC_KEY_FIELD(experimentSpeeds), {1e-2, 1000, 8, 1},
                     "rad/s", "the experiment's wheel speeds (each is `runs` runs of every route)")
            .custom(
                "experiment_routes", "", "many_turns, patrol", "the experiment's routes",
                [](common::IniSection& s, Cfg& c) {
                    std::string given;
                    for (const auto& r : c.experimentRoutes)
                        given += (given.empty() ? "" : " ") + r;
                    std::istringstream names(s.text("experiment_routes", given));
                    c.experimentRoutes = {std::istream_iterator<std::string>(names), {}};
                    if (c.experimentRoutes.empty())
                        s.fail("experiment_routes", "give many_turns, patrol or both");
                    if (c.experimentRoutes.size() > 2)
                        s.fail("experiment_routes", "many_turns, patrol or both, once each");
                    for (const auto& r : c.experimentRoutes)
                        if (r != "many_turns" && r != "patrol")
                            s.fail("experiment_routes",
                                   "'" + r + "': expected many_turns or patrol");
                },
                [](const Cfg& c) {
                    std::string routes;
                    for (const auto& r : c.experimentRoutes)
                        routes += (routes.empty() ? "" : " ") + r;
                    return routes;
                })
            .integer("experiment_robots_max", MRLOC_KEY_FIELD(experimentRobotsMax), 4, 50, "",
                     "fig. 15: N = 4 to this, on the first route at the first speed")
            .integer("camera_starts", MRLOC_KEY_FIELD(cameraStarts), 0, 27, "",
                     "27: Algorithm 1 (with `algorithm_one`'s condition) from rendered frames "
                     "on a 3 x 3 x 3 grid of starts, for fig. 11's camera row; 0: none")
            .integer("pixel_runs", MRLOC_KEY_FIELD(pixelRuns), 0, kMaxPixelRuns, "",
                     "Table 1 from pixels: pixel marches per route and speed "
                     "(`experiment_routes` x `experiment_speeds`), on every core, each beside a "
                     "dead-reckoned drive; 0: none (a march takes 3.4-4.8 s on one core at 640 "
                     "x 200, about 8.5 s at 960 x 300)")
            .subSeed("experiment_seed", MRLOC_KEY_FIELD(experimentSeed), "",
                     "the experiment's random seed: run r of Table 1 draws from "
                     "`experiment_seed + r`; absent, `[scenario] seed` (so `--seed` and `mrloc "
                     "batch --seeds` reach it); given, an override the report names");
    return table;
}

void FormationConfig::loadFromConfigFile(const mrpt::config::CConfigFileBase& src,
                                         const std::string& section) {
    *this = FormationConfig{};  // every key absent takes the struct's default: written once
    common::IniSection s(src, section);
    keys().load(s, *this);
    if (cameraWidth % 4 != 0)  // the renderer reads rows of whole 4-byte words
        s.fail("camera_width", "a multiple of 4 px");
    if (cameraStarts != 0 && cameraStarts != 27)
        s.fail("camera_starts", "0 (none) or 27 (the 3 x 3 x 3 grid of starts)");
    s.finish();
}

void FormationConfig::saveToConfigFile(mrpt::config::CConfigFileBase& t,
                                       const std::string& section) const {
    keys().save(*this, t, section);
}

}  // namespace mrloc::formation
