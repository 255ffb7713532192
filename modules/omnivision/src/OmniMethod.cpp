#include <mrloc/common/Error.h>
#include <mrloc/common/IniSection.h>
#include <mrloc/common/Outcome.h>
#include <mrloc/omnivision/OmniFiles.h>
#include <mrloc/omnivision/OmniLocalizer.h>
#include <mrloc/omnivision/OmniMethod.h>
#include <mrpt/core/format.h>
#include <mrpt/obs/CObservationImage.h>
#include <mrpt/obs/CObservationRange.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>

namespace mrloc::omnivision {

OmniPayload::OmniPayload(OmniSetup setup, sim::WorldOptions world)
    : setup_(std::move(setup)), world_(std::move(world)) {}
OmniPayload::~OmniPayload() = default;

void OmniPayload::command(sim::Step& step) {
    // Seed 000: the pair that stops stands still in (from, to].
    for (size_t i = 0; i < step.fleet.size(); ++i) {
        auto& robot = step.fleet.robot(i);
        const bool stopped =
            std::any_of(setup_.stops.begin(), setup_.stops.end(), [&](const auto& s) {
                return s.robot == robot.options().name && step.t > s.from + 1e-9 &&
                       step.t <= s.to + 1e-9;
            });
        if (stopped)
            robot.stop();
        else
            robot.go();
    }
}

void OmniPayload::sense(sim::Step& step) {
    const bool snapshot =
        std::any_of(setup_.snapshotTimes.begin(), setup_.snapshotTimes.end(),
                    [&](double ts) { return std::abs(step.t - ts) < 0.5 * step.dt; });
    if (!snapshot) return;
    if (setup_.camera.render && !renderer_)
        renderer_ = std::make_unique<OmniRenderer>(setup_.camera, world_);
    const auto poses = step.fleet.poses();
    for (size_t i = 0; i < step.fleet.size(); ++i) {  // every camera fires at once
        const std::string& name = step.fleet.robot(i).options().name;
        mrpt::obs::CObservation::Ptr obs;
        if (renderer_) {
            auto img = mrpt::obs::CObservationImage::Create();
            img->image = renderer_->render(poses, i);
            img->cameraPose = mrpt::poses::CPose3D(0, 0, setup_.camera.cameraHeight, 0, 0, 0);
            img->sensorLabel = name + ".omni";
            obs = img;
        } else {
            obs = senseBearings(
                poses, i, setup_.camera, step.rng,
                [&](const auto& a, const auto& b) { return step.world.lineOfSight(a, b); });
            obs->sensorLabel = name + ".omni_bearings";
        }
        obs->timestamp = step.stamp;
        step.emit(obs);
    }
    if (!setup_.lidar) return;
    const auto& l = *setup_.lidar;  // the conventional method's one measured distance
    const auto& a = poses[step.fleet.indexOf(l.from)];
    const auto& b = poses[step.fleet.indexOf(l.to)];
    auto range = mrpt::obs::CObservationRange::Create();
    range->sensorLabel = l.from + ".lidar." + l.to;
    range->timestamp = step.stamp;
    range->minSensorDistance = 0;
    range->maxSensorDistance = 1e3;
    mrpt::obs::CObservationRange::TMeasurement m;
    m.sensorID = 0;
    m.sensedDistance =
        float(std::hypot(b.x() - a.x(), b.y() - a.y()) + step.rng.drawGaussian1D(0, l.sigma));
    range->sensedData.push_back(m);
    step.emit(range);
}

std::vector<sim::RobotOptions> generateSwarm(const OmniOptions& o, const sim::WorldOptions& world) {
    mrpt::random::CRandomGenerator rng(uint32_t(o.swarmSeed.value));
    const double side = std::min({o.swarmArea, world.sizeX, world.sizeY});
    const double x0 = 0.5 * (world.sizeX - side), y0 = 0.5 * (world.sizeY - side);
    std::vector<sim::RobotOptions> robots;
    for (int tries = 0; int(robots.size()) < o.swarm; ++tries) {
        if (tries > 100000)
            throw Error("[omnivision] swarm: cannot place " + std::to_string(o.swarm) + " robots " +
                        std::to_string(o.swarmSeparation) + " m apart in swarm_area");
        const double x = x0 + rng.drawUniform(0.05, 0.95) * side;
        const double y = y0 + rng.drawUniform(0.05, 0.95) * side;
        if (std::any_of(robots.begin(), robots.end(), [&](const auto& r) {
                return std::hypot(r.start.x() - x, r.start.y() - y) < o.swarmSeparation;
            }))
            continue;
        sim::RobotOptions r;
        r.name = mrpt::format("R%02d", int(robots.size()) + 1);
        const double heading = rng.drawUniform(-M_PI, M_PI);
        r.start = mrpt::poses::CPose2D(x, y, heading);
        r.speed = std::max(o.swarmSpeed, 1e-3);
        if (o.swarmSpeed > 0)  // a far waypoint straight ahead: the robot drives straight
            r.waypoints = {{x + 1e3 * std::cos(heading), y + 1e3 * std::sin(heading)}};
        r.loop = false;
        robots.push_back(r);
    }
    return robots;
}

OmniSetup omniSetupOf(const OmniOptions& o, const std::vector<std::string>& robots, double duration,
                      const std::string& origin) {
    const auto need = [&](const std::string& robot, const char* key) {
        if (std::find(robots.begin(), robots.end(), robot) == robots.end())
            throw Error(origin + ": [omnivision] " + key + ": robot '" + robot +
                        "' is not in the scenario");
    };
    OmniSetup setup;
    setup.camera.render = o.render;
    setup.camera.panorama = o.panorama;
    setup.camera.bearingSigma = o.bearingSigma * M_PI / 180;
    setup.camera.maxRange = o.maxRange;
    setup.camera.markerRadius = o.markerRadius;
    setup.camera.markerHeight = o.markerHeight;
    setup.camera.cameraHeight = o.cameraHeight;
    setup.snapshotTimes = o.snapshotTimes();
    for (double t : setup.snapshotTimes)
        if (t > duration)
            throw Error(origin + ": [omnivision]: a snapshot at " + std::to_string(t) +
                        " s is after [scenario] duration");
    if (o.method == "proposed") {
        for (size_t r = 0; r < o.pairs.size(); ++r) {
            const auto& [a, b] = o.pairs[r];
            need(a, "pairs");
            need(b, "pairs");
            const double shift = double(r) * o.roundPeriod;
            setup.stops.push_back({a, o.tb + shift, o.te + shift});
            setup.stops.push_back({b, o.tb + shift, o.te + shift});
        }
    } else {
        need(o.measuredPair.first, "measured_pair");
        need(o.measuredPair.second, "measured_pair");
        setup.lidar = OmniSetup::Lidar{o.measuredPair.first, o.measuredPair.second, o.lidarSigma};
    }
    return setup;
}

namespace {

method::Scenario loadScenario(const mrpt::config::CConfigFileBase& ini,
                              const OmniLocalizer& localizer) {
    const OmniOptions& o = localizer.options();
    method::Scenario s;
    if (o.swarm > 0) {
        s.config = sim::ScenarioConfig::loadWithoutRobots(ini);
        s.config.addGeneratedRobots(ini, generateSwarm(o, s.config.world));
    } else {
        s.config = sim::ScenarioConfig::load(ini);
    }
    s.payload = std::make_unique<OmniPayload>(
        omniSetupOf(o, s.config.scenario.robots, s.config.scenario.duration,
                    common::configOrigin(ini)),
        s.config.world);
    return s;
}

/** The accuracy sweep ([omnivision] accuracy_trials > 0): Monte Carlo on the run's true
 *  layout with its sightings, written to accuracy.txt. */
std::vector<std::string> accuracySweepStep(const method::ExperimentOf<OmniLocalizer>& in) {
    const OmniOptions& o = in.localizer.options();
    if (o.accuracyTrials <= 0) return {};
    if (in.truth.empty())
        throw Error("[omnivision] accuracy_trials: the sweep needs the run's ground truth");
    const auto layout = in.localizer.accuracyLayout(in.truth);
    AccuracyFile file;
    file.distanceName = layout.proposed ? "odometer" : "LiDAR";
    file.points = accuracySweep(layout, o.accuracyTrials, in.seed, in.log);
    file.write(in.outDir);
    return {AccuracyFile::path(in.outDir)};
}

/** The work the configuration asks (method/Work.h): the rendered panoramas and the
 *  accuracy sweep. */
std::vector<method::WorkItem> omnivisionWork(const OmniLocalizer& localizer,
                                             const sim::ScenarioConfig* scenario) {
    const OmniOptions& o = localizer.options();
    // Measured (doc/errors.md, "Work"): rendering costs 32 ns per panorama pixel
    // (omnivision_5robots.ini at 640 to 2560 x 960 px per view), and holds the strip twice
    // (render target and image, 3 bytes a pixel); a trial of the accuracy sweep 2.1 ms with
    // 5 robots, taken to grow as N^3 (the refinement's normal equations).
    constexpr double kSecondsPerPixel = 3.2e-8, kSecondsPerTrial = 2.1e-3;
    // a swarm's robots are generated: [scenario] robots stays empty
    const double robots =
        o.swarm > 0 || !scenario ? double(o.swarm) : double(scenario->robots.size());
    const double snapshots = double(o.snapshotTimes().size());
    std::vector<method::WorkItem> out;
    if (robots >= 3) {
        // The identification's table holds every ordered pair of every robot's images, N^3
        // of them at 16 bytes; measured with omnivision_swarm.ini's bearings: 76 MB at N = 30,
        // 168 MB at N = 120, about 53 bytes per N^3 at the peak; its time 2.5 us per N^3
        // per snapshot at N = 100 (5 s for the run). The search beyond the table depends on
        // the bearings: it is bounded by its work meter (maxPairVisits), not estimated here.
        constexpr double kBytesPerRobotCubed = 56, kSecondsPerRobotCubed = 2.5e-6;
        const double cubed = robots * robots * robots;
        method::WorkItem w;
        w.what = mrpt::format("the identification of %.0f robots at %.0f snapshots", robots,
                              snapshots);
        w.keys = "[scenario] robots or [omnivision] swarm, cubed, x pairs";
        w.seconds = snapshots * cubed * kSecondsPerRobotCubed;
        w.memory = cubed * kBytesPerRobotCubed;
        out.push_back(w);
    }
    if (scenario && o.render) {
        const double pixels =
            double(o.panorama.views) * double(o.panorama.viewWidth) * double(o.panorama.height);
        method::WorkItem w;
        w.what = mrpt::format("%.0f rendered panoramas", snapshots * robots);
        w.keys = "[omnivision] views x view_width x view_height x pairs, per robot";
        w.seconds = pixels * snapshots * robots * kSecondsPerPixel;
        w.memory = 2 * 3 * pixels;
        w.simulation = true;
        out.push_back(w);
    }
    if (o.accuracyTrials > 0) {
        method::WorkItem w;
        w.what = "the accuracy sweep";
        w.keys = "[omnivision] accuracy_trials";
        w.seconds = double(o.accuracyTrials) * kSecondsPerTrial * std::pow(robots / 5, 3);
        out.push_back(w);
    }
    return out;
}

report::Html omnivisionSection(const report::RunView& run) {
    using report::heading, report::paragraph;
    const auto layout = LayoutFile::read(run.dir);
    plotLayout(layout, run.dir + "/layout.png");
    const auto& m = run.metrics.value("omnivision", nlohmann::json::object());
    report::Html out =
        heading(2, "Relative layout (paper 000)") +
        paragraph(
            "The truth, the paper's solution (eq. (8) for L, then the sine rule) and the "
            "least-squares refinement over every identified bearing and measured "
            "distance, with its 3-sigma ellipses; the legend is in the picture.") +
        report::Figure{"layout.png",
                       "each robot's recovered position should sit in its true circle, within its "
                       "3-sigma ellipse"}
            .html();
    // the headline figures: every pairwise distance against the truth, and the triangles
    // each snapshot gave (seed 000 finds a layout from the triangles' interior angles)
    const auto pct = [&](const char* key, const char* stat) {
        const auto e = m.value(key, nlohmann::json::object());
        return e.is_object() && e.contains(stat) && e[stat].is_number()
                   ? mrpt::format("%.2f %%", 100 * e[stat].get<double>())
                   : std::string("none");
    };
    if (m.contains("relative_distance_error_paper") &&
        m["relative_distance_error_paper"].is_object()) {
        report::Html headline = report::bold(
            "Relative distance error, median (max) over the " +
            report::cellText(m["relative_distance_error_paper"].value("pairs", nlohmann::json())) +
            " pairs: the paper's solution " + pct("relative_distance_error_paper", "median") +
            " (" + pct("relative_distance_error_paper", "max") + "), refined " +
            pct("relative_distance_error_refined", "median") + " (" +
            pct("relative_distance_error_refined", "max") + ").");
        const long long robots = m.contains("robots") && m["robots"].is_number_integer()
                                     ? m["robots"].get<long long>()
                                     : 0;
        const size_t n = size_t(std::clamp(robots, 0LL, 1LL << 20));
        const size_t all = n >= 3 ? n * (n - 1) * (n - 2) / 6 : 0;
        const auto snapshots = m.value("snapshots", nlohmann::json::object());
        const auto degrees = [&](const char* key, const char* stat) {
            const auto v = common::numberAt(m, std::string(key) + "/" + stat);
            return v ? mrpt::format("%.3f deg", *v) : std::string("none");
        };
        if (m.contains("heading_error_deg_paper"))
            headline += " Heading error, median (max): the paper's layout " +
                        degrees("heading_error_deg_paper", "median") + " (" +
                        degrees("heading_error_deg_paper", "max") + "), refined " +
                        degrees("heading_error_deg_refined", "median") + " (" +
                        degrees("heading_error_deg_refined", "max") + ").";
        for (const auto& [name, snap] : snapshots.items()) {
            if (!snap.is_object()) continue;
            const bool localized = snap.value("search", "") == "localized";
            headline += " Snapshot " + name + ": " +
                        report::cellText(snap.value("triangles", nlohmann::json())) +
                        mrpt::format(" of the %zu triangles found", all) +
                        (localized ? " (the localized search of eq. (11)-(12): one is asked)."
                         : snap.value("unresolved", nlohmann::json::array()).empty()
                             ? "."
                             : ", some robots unresolved.");
        }
        out += paragraph(headline + " Paper 000 gives no figure to compare with.");
    }
    if (m.contains("restarts") && m["restarts"].is_array() && !m["restarts"].empty()) {
        std::vector<report::Html> restarts;
        for (const auto& r : m["restarts"]) restarts.push_back(report::cellText(r));
        out += paragraph("Restarts (the stopped pair shared no witness):") +
               report::bulletList(restarts);
    }
    const auto xy = [](double x, double y) {
        return std::isfinite(x) ? mrpt::format("%.3f, %.3f", x, y) : std::string("none");
    };
    report::Table table({"robot", "paper x, y (m)", "refined x, y (m)", "sigma x, y (mm)",
                         "truth x, y (m)", "normalised squared error"});
    for (const auto& p : layout.points) {
        const auto nees = normalisedSquaredError(p);
        table.row({p.robot, xy(p.paperX, p.paperY), xy(p.refinedX, p.refinedY),
                   std::isfinite(p.cxx)
                       ? mrpt::format("%.1f, %.1f", 1000 * std::sqrt(std::max(0.0, p.cxx)),
                                      1000 * std::sqrt(std::max(0.0, p.cyy)))
                       : std::string("none"),
                   xy(p.trueX, p.trueY), nees ? mrpt::format("%.2f", *nees) : std::string("none")});
    }
    out += table.html() +
           paragraph(
               "Normalised squared error: the refined position's error weighed by its "
               "covariance, per coordinate (B's y is the frame's, so B has one). With a "
               "covariance that matches the errors it averages 1 over runs (measured per "
               "robot over 20 seeds of omnivision_5robots.ini: 0.58 to 1.00); one run's "
               "value is one draw, mostly below 3.");
    if (!std::filesystem::exists(AccuracyFile::path(run.dir))) return out;
    const auto sweep = AccuracyFile::read(run.dir);
    plotAccuracy(sweep, run.dir + "/accuracy.png");
    report::Table accuracy({"varied", "bearing sigma (deg)", "distance sigma (%)",
                            "paper's solution (%)", "least squares (%)", "trials", "failed"});
    for (const auto& r : sweep.points)
        accuracy.row({r.axis, mrpt::format("%g", r.angleSigmaDeg),
                      mrpt::format("%g", 100 * r.distanceSigma),
                      mrpt::format("%.3f", 100 * r.paper), mrpt::format("%.3f", 100 * r.refined),
                      std::to_string(r.trials), std::to_string(r.failures)});
    return out + heading(3, "Accuracy against noise (Monte Carlo on this run's true layout)") +
           paragraph(
               "Median relative error of all pairwise distances, mean over the trials. "
               "Paper 000 gives no figure to compare with.") +
           report::Figure{"accuracy.png", "error against the bearings' noise: how fast it grows"}
               .html() +
           accuracy.html();
}

/** Every robot placed or not, and the relative error of the pairwise distances (seed 000's
 *  solution and the refined one); seed 000 publishes no figure of its own. */
common::Headline omnivisionHeadline(const method::HeadlineOf<OmniLocalizer>& in) {
    common::Headline h;
    size_t unresolved = 0;
    std::map<UnresolvedReason, size_t> why;  // over the snapshots, in the table's order
    const auto method = in.metrics.value("omnivision", nlohmann::json::object());
    if (method.contains("snapshots") && method["snapshots"].is_object())
        for (const auto& [name, snapshot] : method["snapshots"].items())
            if (snapshot.is_object() && snapshot.value("search", "") != "localized" &&
                snapshot.contains("unresolved") && snapshot["unresolved"].is_array()) {
                unresolved += snapshot["unresolved"].size();  // localized: one triangle asked
                const auto counts = snapshot.value("unresolved_why", nlohmann::json::object());
                for (const auto& t : kUnresolvedReasons)
                    if (const auto n = counts.find(t.key);
                        n != counts.end() && n->is_number_unsigned())
                        why[t.reason] += n->get<size_t>();
            }
    h.reached = unresolved == 0;
    // doc/omnivision.md, "The paper's mechanism: as stated, as shipped"
    const auto& options = in.localizer.options();
    if (options.method == "proposed") {
        using Search = OmniOptions::SearchAtTb;
        const auto searches = method.value("localized_searches", nlohmann::json::array());
        const bool fellBack = searches.is_array() && !searches.empty() &&
                              searches.back().is_object() &&
                              searches.back().contains("full_search_instead");
        if (options.searchAtTb == Search::Full)
            h.mechanism =
                "t_b: the full search, as at t_e (search_at_tb = full; paper 000's eq. "
                "(11)-(12) is search_at_tb = localized)";
        else if (fellBack)
            h.mechanism =
                "t_b: the full search, paper 000's fall-back: eq. (11)-(12) (search_at_tb = " +
                OmniOptions::wordOf(options.searchAtTb) + ") confirmed no witness's triangle";
        else if (options.searchAtTb == Search::Localized)
            h.mechanism =
                "t_b: paper 000's eq. (11)-(12), a triangle of the stopped pair and one witness "
                "(search_at_tb = localized), confirmed without headings by the robots the "
                "witness saw at t_e";
        else
            h.mechanism =
                "t_b: paper 000's eq. (11)-(12), a triangle of the stopped pair and one witness "
                "(search_at_tb = localized_turn), confirmed by the witness's odometer turn "
                "(beyond the paper, which rules out heading information)";
    } else
        h.mechanism =
            "the conventional method: one measured distance and the sine rule "
            "(paper 000 section 2)";
    h.status = h.reached ? "every robot identified"
                         : mrpt::format("%zu robot views unresolved", unresolved);
    std::string reasons;
    for (const auto& [reason, count] : why)
        reasons +=
            (reasons.empty() ? " (" : "; ") + std::to_string(count) + " " + textOf(reason).words;
    if (!reasons.empty()) h.status += reasons + ")";
    const auto percent = [&](const char* key) -> std::optional<double> {
        const auto v = common::numberAt(method, std::string(key) + "/median");
        return v ? std::optional<double>(100 * *v) : std::nullopt;
    };
    const char* none = "paper 000 publishes no figure";
    if (const auto refined = percent("relative_distance_error_refined"))
        h.figures.push_back(
            {"relative distance error, refined (median)", refined, "%", none, "", false});
    h.figures.push_back({"relative distance error, paper 000's solution (median)",
                         percent("relative_distance_error_paper"), "%", none, "", false});
    h.figures.push_back({"heading error, refined (median)",
                         common::numberAt(method, "heading_error_deg_refined/median"), "deg",
                         "paper 000 does not estimate headings", "", false});
    // on the truth's timeline: the layout, then each robot carried by its odometry (the
    // stamps before the layout are not covered: paper 000 solves one instant)
    for (auto f : common::trajectoryFigures(in.metrics)) {
        // the baseline is odometry alone from the true start, over the whole log
        if (!f.baseline) f.name = "from the layout on, carried by odometry: " + f.name;
        h.figures.push_back(std::move(f));
    }
    return h;
}

}  // namespace

void registerMethod(method::Registry& registry) {
    method::MethodUnit<OmniLocalizer> m;
    m.name = "omnivision";
    m.sections = {"omnivision"};
    m.keys = {OmniOptions::keys().docs()};
    m.reads = {"CObservationImage", "CObservationBearingRange"};
    m.exampleConfig = "config/omnivision_5robots.ini";
    m.headline = omnivisionHeadline;
    m.scenario = loadScenario;
    m.experiment = accuracySweepStep;
    m.work = omnivisionWork;
    m.report.subject = "relative positions from omni-directional cameras (paper 000)";
    m.report.html = omnivisionSection;  // its own picture: no world top view
    registry.add(std::move(m));
}

}  // namespace mrloc::omnivision
