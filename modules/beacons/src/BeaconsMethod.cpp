#include <mrloc/beacons/BeaconPayload.h>
#include <mrloc/beacons/BeaconStudyReport.h>
#include <mrloc/beacons/BeaconsMethod.h>
#include <mrloc/beacons/PaperValues.h>
#include <mrloc/common/Error.h>
#include <mrloc/report/ReportOptions.h>
#include <mrpt/core/format.h>

#include <algorithm>
#include <filesystem>
#include <map>

namespace mrloc::beacons {

method::Scenario loadScenario(const mrpt::config::CConfigFileBase& ini) {
    method::Scenario s;
    s.config = sim::ScenarioConfig::load(ini, BeaconRobotOptions::keyNames());
    std::vector<BeaconRobotOptions> robots(s.config.robots.size());
    for (size_t i = 0; i < robots.size(); ++i) robots[i].load(ini, s.config.robots[i].name);
    SensorOptions sensors;
    sensors.loadFromConfigFile(ini, "sensors");
    UltrasonicOptions ultrasonic;
    ultrasonic.loadFromConfigFile(ini, "ultrasonic");
    common::IniSection section(ini, "beacons");  // keys are checked by the localizer's options
    const BeaconMap map = loadBeaconMap(ini, section);
    for (const auto& [id, p] : map)
        if (!s.config.world.contains(p, 1e-9))
            throw Error(common::configOrigin(ini) + ": [beacons] beacon_" + std::to_string(id) +
                        ": position " + p.asString() + " is outside the room [world] size");
    s.payload = std::make_unique<BeaconPayload>(ini, map, sensors, ultrasonic, robots);
    s.saveOptions = [sensors, ultrasonic, robots,
                     names = s.config.scenario.robots](mrpt::config::CConfigFileBase& t) {
        sensors.saveToConfigFile(t, "sensors");
        ultrasonic.saveToConfigFile(t, "ultrasonic");
        for (size_t i = 0; i < robots.size(); ++i) robots[i].save(t, names[i]);
    };
    return s;
}

namespace {

/** Seed 001 Tables 3/4 and Figs. 10/11 for this run: per robot (test point) the reception
 *  rate of each beacon from the simulator's shot log, and the mean and max error, beside
 *  the paper's figures ([beacons] paper_reception_<id>). */
report::Html receptionSection(const report::RunView& run) {
    using report::Html;
    const auto& metrics = run.metrics;
    // the shot log of a rawlog simulated into this run folder: the report reads nothing
    // outside the folder, whatever metrics.json names
    const std::string rawlogName =
        std::filesystem::path(metrics.value("rawlog", "")).filename().string();
    const std::string shotsPath = shotLogPath(run.dir + "/" + rawlogName);
    if (!std::filesystem::exists(shotsPath))
        return report::paragraph(
            "No shot log beside the rawlog (not simulated here): no reception table.");
    const auto shots = loadShotLog(shotsPath);
    if (shots.empty()) return report::paragraph("The shot log is empty: no beacon fired.");
    BeaconOptions options;
    options.loadFromConfigFile(*run.effective, "beacons");
    report::ReportOptions paper;
    paper.loadFromConfigFile(*run.effective, "report");
    std::vector<std::string> robots;
    std::map<int, std::map<std::string, std::pair<int, int>>> heard;  // beacon, robot: n, ok
    for (const auto& s : shots) {
        if (std::find(robots.begin(), robots.end(), s.robot) == robots.end())
            robots.push_back(s.robot);
        auto& c = heard[s.beacon][s.robot];
        ++c.first;
        c.second += s.detected;
    }
    Html out = report::heading(2, "Beacon system: reception and errors per robot");
    if (!options.paperReception.empty())
        out +=
            report::paragraph("Ours, with the paper's in brackets" +
                              (paper.paperCaption.empty() ? "" : ": " + paper.paperCaption) + ".");
    std::vector<Html> head{"successful receiving rate (%)"};
    head.insert(head.end(), robots.begin(), robots.end());
    report::Table table(head);
    for (const auto& [beacon, perRobot] : heard) {
        const auto p = options.paperReception.find(beacon);
        std::vector<Html> cells;
        for (size_t i = 0; i < robots.size(); ++i) {
            const auto c = perRobot.find(robots[i]);
            std::string cell;
            if (c != perRobot.end())
                cell = mrpt::format("%.0f", 100.0 * c->second.second / c->second.first);
            if (p != options.paperReception.end() && i < p->second.size())
                cell += mrpt::format(" (%g)", p->second[i]);
            cells.push_back(cell);
        }
        table.headedRow("beacon " + std::to_string(beacon), cells);
    }
    const auto methodRobots = metrics.value("beacons", nlohmann::json::object())
                                  .value("robots", nlohmann::json::object());
    const auto rowOf = [&](const nlohmann::json& m, const char* name, const char* key, double scale,
                           const char* fmt) {
        std::vector<Html> cells;
        for (const auto& robot : robots)
            cells.push_back(m.contains(robot) && m[robot].contains(key) && m[robot][key].is_number()
                                ? mrpt::format(fmt, scale * m[robot][key].get<double>())
                                : std::string("none"));
        table.headedRow(name, cells);
    };
    const auto row = [&](const char* name, const char* key, double scale, const char* fmt) {
        rowOf(metrics["robots"], name, key, scale, fmt);
    };
    row("mean error (mm)", "mean_m", 1000, "%.1f");
    row("max error (mm)", "max_m", 1000, "%.1f");
    row("estimates", "estimates", 1, "%.0f");
    // seed 001 sec. 4's figure for the scheduler: how far a robot moves between two fixes
    rowOf(methodRobots, "mean distance between fixes (m)", "mean_distance_between_fixes_m", 1,
          "%.3f");
    rowOf(methodRobots, "max distance between fixes (m)", "max_distance_between_fixes_m", 1,
          "%.3f");
    // the link's biases as each robot's tracker estimated them (estimate_bias)
    bool anyBias = false;
    std::vector<Html> offsets, scales;
    for (const auto& robot : robots) {
        const auto m = methodRobots.value(robot, nlohmann::json::object());
        if (m.contains("range_offsets_m") && m["range_offsets_m"].is_object()) {
            anyBias = true;
            std::string cell;
            for (const auto& [id, v] : m["range_offsets_m"].items())
                cell += (cell.empty() ? "" : ", ") + id + ": " +
                        (v.is_number() ? mrpt::format("%+.1f", 1000 * v.get<double>()) : "none");
            offsets.push_back(cell);
            scales.push_back(mrpt::format("%+.2f", 1000 * m.value("range_scale", 0.0)));
        } else {
            offsets.push_back("none");
            scales.push_back("none");
        }
    }
    if (anyBias) {
        table.headedRow("range offset per beacon at the end (mm)", offsets);
        table.headedRow("common range scale at the end (per mille)", scales);
    }
    out += table.html();
    out += report::paragraph(
        "Scheduling: " +
        report::bold(options.system.scheduling == Scheduling::Priority
                         ? "priority (slots in proportion to speed, paper 001 sec. 4)"
                         : "round robin") +
        ". Paper 001's point: with priority scheduling the distance a robot moves between two "
        "fixes stays about the same whatever its speed; round robin lets a fast robot go "
        "further.");
    size_t detected = 0;
    for (const auto& s : shots) detected += s.detected;
    out += report::paragraph(
        mrpt::format(
            "Shots fired: %zu, heard: %zu, a reception rate of %.1f %% (of the shots fired: a "
            "section fires only its own beacons). Multilateration fixes: %d (in the tracker "
            "mode, those made while the filter starts or restarts; then every epoch gives an "
            "estimate, the ranges corrected by the offsets and scale above). Log: ",
            shots.size(), detected, 100.0 * double(detected) / double(shots.size()),
            metrics.value("beacons", nlohmann::json::object()).value("multilateration_fixes", 0)) +
        report::code(std::filesystem::path(shotsPath).filename().string()) + " (in this folder).");
    return out;
}

void beaconsInTopView(const report::RunView& run, report::TopViewContent& view) {
    common::IniSection section(*run.effective, "beacons");
    for (const auto& [id, p] : readBeaconKeys(section)) {
        view.landmarks.push_back(p);
        view.landmarkLabels.push_back(std::to_string(id));  // as the tables name them
    }
    view.landmarksName = "beacons";
}

/** The room the run's errors come from, beside the paper's: a sentence when it differs. */
std::string roomDifference(const sim::ScenarioConfig* scenario, double paperX, double paperY) {
    if (!scenario) return "a log recorded elsewhere, not the paper's test points";
    const auto& w = scenario->world;
    if (std::abs(w.sizeX - paperX) < 0.05 && std::abs(w.sizeY - paperY) < 0.05) return "";
    return mrpt::format("this room is %.1f x %.1f m; the paper measured in %.1f x %.1f m", w.sizeX,
                        w.sizeY, paperX, paperY);
}

/** How the receiver's method departs from seed 001's fix (eq. 4-10: one 3-D squared-range
 *  fix per epoch from one shot per beacon), or empty. */
std::string methodDifference(const BeaconOptions& o) {
    std::vector<std::string> parts;
    if (o.mode == BeaconOptions::Mode::Tracker) parts.push_back("a tracking filter");
    if (!o.threeD) parts.push_back("the height known (2-D)");
    if (o.tracker.fix.residual == Residual::Range) parts.push_back("range residual");
    if (o.delayCompensation) parts.push_back("delay compensation");
    if (o.tracker.jitterWeights) parts.push_back("jitter weights");
    if (o.system.shotsPerBeacon > 1)
        parts.push_back(mrpt::format("%d shots per beacon", o.system.shotsPerBeacon));
    if (parts.empty()) return "";
    std::string out = "mrloc's fix, not the paper's: ";
    for (size_t i = 0; i < parts.size(); ++i) out += (i ? ", " : "") + parts[i];
    return out;
}

/** The study's answers to seed 001's two claims: the largest square room one set of beacons
 *  covers with active heads (its goal: over 6 m), and how many active beacons cover a room
 *  against fixed ones (its abstract: about half). */
std::vector<common::HeadlineFigure> studyFigures(const BeaconStudyFile& f) {
    std::vector<common::HeadlineFigure> out;
    const std::string how = mrpt::format(
        "mrloc's simulation (the link calibrated on Table 3): every test point fixed in at least "
        "%.0f %% of its trials, every error under %.0f mm",
        100 * f.criteria.reception, 1000 * f.criteria.errorBound);
    std::optional<double> largest;
    int beacons = 0;
    for (const auto& g : f.grids)
        if (g.part == "coverage" && g.variant.rfind("active", 0) == 0) {
            beacons = g.beacons;
            if (g.covers) largest = std::max(largest.value_or(0.0), g.value);
        }
    if (beacons > 0)
        out.push_back(
            {mrpt::format("side of the largest square room %d active beacons cover", beacons),
             largest, "m",
             mrpt::format("goal: over %g m (paper 001 sec. 6)", paper::kGoalCoverageSide), how,
             false});
    // the largest room both aimings cover within count_max
    std::map<double, std::pair<int, int>> counts;  // side -> fixed, active
    for (const auto& c : f.counts)
        (c.aiming.rfind("active", 0) == 0 ? counts[c.size].second : counts[c.size].first) =
            c.fewest;
    for (auto it = counts.rbegin(); it != counts.rend(); ++it)
        if (it->second.first > 0 && it->second.second > 0) {
            out.push_back(
                {mrpt::format("active / fixed beacons covering %g x %g m", it->first, it->first),
                 double(it->second.second) / it->second.first, "",
                 mrpt::format("about %.1f (paper 001 abstract)", paper::kActiveBeaconShare),
                 how + "; fixed heads point straight down", false});
            break;
        }
    return out;
}

/** APE RMSE, mean and max on the truth's timeline with its coverage, with seed 001's figures beside
 * them (active: section 5.3; fixed: Fig. 10 gives no number), and odometry alone apart. */
common::Headline beaconsHeadline(const method::HeadlineOf<BeaconLocalizer>& in) {
    common::Headline h;
    h.status = "tracked";
    // doc/beacons.md, "The paper's mechanism: as stated, as shipped"
    h.mechanism = in.localizer.options().mode == BeaconOptions::Mode::Fixes
                      ? "paper 001's fixes, one per epoch (mode = fixes)"
                      : "mrloc's tracker between fixes (mode = tracker: odometry and gated "
                        "ranges, beyond paper 001)";
    if (in.scenario)
        h.mechanism +=
            "; one shared acoustic channel, one agent per slot (paper 001's firing of "
            "different beacons at different agents at once runs in [beacons_study] only)";
    h.figures = common::trajectoryFigures(in.metrics);
    common::HeadlineFigure mean{
        "APE mean", common::numberAt(in.metrics, "truth_timeline/ape/mean_m"), "m", "", "", false};
    common::HeadlineFigure max{
        "APE max", common::numberAt(in.metrics, "truth_timeline/ape/max_m"), "m", "", "", false};
    if (in.localizer.options().system.activeAiming) {
        mean.paper = "over 0.030 m (paper 001 sec. 5.3, active beacons)";
        max.paper = "over 0.060 m (paper 001 sec. 5.3)";
        // seed 001 gives no test points for its 4 x 5.7 m room: even there, the points are
        // the INI's, so the experiment always differs from the paper's in that
        const std::string room =
            roomDifference(in.scenario, paper::kActiveRoomX, paper::kActiveRoomY);
        mean.differs = max.differs =
            room.empty() ? "the paper's room; its test points are this INI's (paper 001 gives "
                           "none for this room)"
                         : room;
    } else {
        mean.paper = "Fig. 10, a chart: about twice the active beacons' (paper 001 sec. 5.3)";
        mean.differs = roomDifference(in.scenario, paper::kFixedRoomX, paper::kFixedRoomY);
    }
    if (const auto method = methodDifference(in.localizer.options()); !method.empty())
        for (auto* f : {&mean, &max}) f->differs += (f->differs.empty() ? "" : "; ") + method;
    h.figures.insert(h.figures.begin() + 2, {mean, max});  // after APE RMSE and its coverage
    if (std::filesystem::exists(BeaconStudyFile::path(in.outDir)))
        for (auto& f : studyFigures(BeaconStudyFile::read(in.outDir))) h.figures.push_back(f);
    return h;
}

/** [beacons_study] after localization: the run's room and hardware simulated again. */
std::vector<std::string> beaconsStudy(const method::ExperimentOf<BeaconLocalizer>& in) {
    const auto& l = in.localizer;
    if (!l.study().enabled || !in.scenario) return {};  // a log recorded elsewhere: no room
    StudySetup setup{l.study(), l.studyUltrasonic(), l.studySensors()};
    runStudy(setup, l.options(), *in.scenario, in.seed, in.log).write(in.outDir);
    return {BeaconStudyFile::path(in.outDir)};
}

std::vector<method::WorkItem> beaconsWork(const BeaconLocalizer& l,
                                          const sim::ScenarioConfig* scenario) {
    if (!l.study().enabled || !scenario) return {};
    // Measured (doc/errors.md, "Work"; bench_beacon_study): a trial of 3 or 4 beacons x 4
    // shots and its 2-D fix with two delay refits, 38-57 us on one core.
    constexpr double kSecondsPerTrial = 50e-6;
    method::WorkItem w;
    w.what = "the beacon study's trials";
    w.keys =
        "[beacons_study] trials x the test points (grid, wall_margin) of coverage_sizes, "
        "count_sizes x count_max and the room x (beam_angles + beacon_counts + speeds); "
        "choice_trials; agents x agents_layouts x agents_time";
    w.seconds =
        kSecondsPerTrial * l.study().trialsAtMost(scenario->robots.size(), scenario->world.sizeX,
                                                  scenario->world.sizeY);
    w.parallel = true;
    return {w};
}

}  // namespace

void registerMethod(method::Registry& registry) {
    method::MethodUnit<BeaconLocalizer> m;
    m.name = "beacons";
    m.sections = {"beacons", "sensors", "ultrasonic", "beacons_study"};
    m.keys = {BeaconRobotOptions::keys().docs(), BeaconOptions::keys().docs(),
              SensorOptions::keys().docs(), UltrasonicOptions::keys().docs(),
              StudyOptions::keys().docs()};
    // MRPT's range-only localization INIs (ro-localization, pf-localization's RO demo) name
    // no mrloc section: their beacon likelihood section says they are this method's
    m.foreignSections = {"MetricMap_landmarksMap_00_likelihoodOpts"};
    m.reads = {"CObservationBeaconRanges", "CObservationBearingRange"};
    m.exampleConfig = "config/quickstart.ini (a map of your beacons in [beacons])";
    m.headline = beaconsHeadline;
    m.scenario = [](const mrpt::config::CConfigFileBase& ini, const BeaconLocalizer&) {
        return loadScenario(ini);
    };
    m.report.subject = "active ultrasonic beacons (paper 001)";
    m.report.html = [](const report::RunView& run) {
        return receptionSection(run) + studySection(run.dir);
    };
    m.experiment = beaconsStudy;  // issue 30: coverage, beacon count, sweeps, agents
    m.work = beaconsWork;
    m.report.topView = beaconsInTopView;
    registry.add(std::move(m));
}

}  // namespace mrloc::beacons
