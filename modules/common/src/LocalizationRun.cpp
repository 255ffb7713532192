#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/Evaluation.h>
#include <mrloc/common/LocalizationRun.h>
#include <mrloc/common/Metrics.h>
#include <mrloc/common/Names.h>
#include <mrloc/common/ObservationCheck.h>
#include <mrloc/common/Progress.h>
#include <mrloc/common/Rawlog.h>
#include <mrloc/common/RunDirectory.h>
#include <mrloc/common/Trajectory.h>
#include <mrpt/core/format.h>
#include <mrpt/obs/CObservationComment.h>
#include <mrpt/obs/CObservationOdometry.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>

namespace mrloc::common {

namespace {

/** Dead reckoning's errors against the robot's ground truth (world frame): the odometry
 *  path started at the true pose of its first reading (a log's odometry starts where its
 *  robot's encoders were reset), then compared at every reading. Readings and, with truth,
 *  the error statistics and the final error. */
nlohmann::json odometryErrors(const Trajectory& odometry, const Trajectories& worldTruth,
                              const std::string& robot) {
    nlohmann::json j;
    j["readings"] = odometry.size();
    const auto gt = worldTruth.find(robot);
    if (gt == worldTruth.end()) return j;
    const auto start = startPoseOf(gt->second, odometry.front().t);
    if (!start) return j;
    const mrpt::poses::CPose3D align = *start + (-odometry.front().pose);
    Trajectory aligned;
    for (const auto& p : odometry) aligned.push_back({p.t, align + p.pose});
    std::vector<double> e;
    for (const auto& te : positionErrors(aligned, gt->second)) e.push_back(te.error);
    j.update(statsToJson(computeStats(e)));
    if (!e.empty()) j["final_m"] = e.back();
    // the same on the truth's timeline, as the estimate's (doc/evaluation.md)
    j["truth_timeline"] = toJson(evaluate(aligned, gt->second));
    return j;
}

}  // namespace

std::string shortClassName(const mrpt::obs::CObservation& obs) {
    const std::string cls = obs.GetRuntimeClass()->className;
    const auto colon = cls.rfind(':');
    return colon == std::string::npos ? cls : cls.substr(colon + 1);
}

std::string contentInWords(const std::map<std::string, size_t>& classCounts) {
    std::string words;
    for (const auto& [cls, count] : classCounts)
        words += (words.empty() ? "" : ", ") + std::to_string(count) + " " + cls;
    return words.empty() ? "no observation" : words;
}

/** How far the robot's odometry moves after time t (m): 0 when it stands still from then
 *  on, or has no odometry. */
double odometryTravelAfter(const Trajectory& odometry, double t) {
    double travel = 0;
    for (size_t i = 1; i < odometry.size(); ++i)
        if (odometry[i].t > t)
            travel += std::hypot(odometry[i].pose.x() - odometry[i - 1].pose.x(),
                                 odometry[i].pose.y() - odometry[i - 1].pose.y());
    return travel;
}

std::vector<std::string> earlyEnds(const Trajectories& estimates, const Trajectories& odometry,
                                   double logStart, double logEnd) {
    constexpr double kStandingTravel = 0.05;  // m of odometry: jitter, not a drive
    std::vector<std::string> warnings;
    const double span = logEnd - logStart;
    if (!(span > 1.0)) return warnings;  // a snapshot log: nothing to cover
    for (const auto& [robot, traj] : estimates) {
        if (traj.size() < 2) continue;  // one estimate per robot (a layout, a start)
        if (const auto odo = odometry.find(robot);
            odo != odometry.end() &&
            odometryTravelAfter(odo->second, traj.back().t) < kStandingTravel)
            continue;
        const double covered = traj.back().t - logStart;
        if (covered < 0.9 * span)
            warnings.push_back(
                mrpt::format("robot '%s': the estimates stop at %.1f s of the log's %.1f s",
                             robot.c_str(), covered, span));
    }
    return warnings;
}

namespace {

/** What one pass over the rawlog learnt besides what the localizer took from it. */
struct LogPass {
    size_t observations = 0;  ///< given to the localizer
    /** Odometry alone per robot, as MRPT's pf-localization writes it: the robot's odometry
     *  stream (<robot>.odom, or MRPT's actions), the first such label seen. */
    Trajectories odometry;
    std::map<std::string, size_t> unstamped, copies, classes;
    double start = INFINITY, end = -INFINITY;  ///< the log's first and last stamps (s)
};

/** Gives every checked observation of the rawlog to the localizer, in order, with progress;
 *  an observation the check or the method refuses is an Error naming it. */
LogPass passRawlog(RawlogReader& reader, Localizer& localizer, const LocalizationRunOptions& o) {
    Progress progress("localizing", 0, *o.log);
    LogPass pass;
    std::map<std::string, std::string> odometryLabel;
    ObservationCheck check;
    size_t& n = pass.observations;
    for (mrpt::obs::CObservation::Ptr obs; reader.next(obs);) {
        // stamped 0 with no sensory frame to take a time from (the last action of MRPT's
        // logs): left out and counted, as no method can place it in time
        if (obs->timestamp == INVALID_TIMESTAMP &&
            !IS_CLASS(*obs, mrpt::obs::CObservationComment)) {
            ++pass.unstamped[obs->sensorLabel];
            continue;
        }
        try {
            check.check(*obs);
        } catch (const Error& e) {
            throw Error(mrpt::format("rawlog %s: entry %zu, observation %zu ('%s', %s): %s",
                                     o.rawlogPath.c_str(), reader.entriesRead(), n + 1,
                                     printable(obs->sensorLabel).c_str(),
                                     obs->GetRuntimeClass()->className, e.what()));
        }
        if (check.isCopyOfTheOneBefore(obs)) {  // a log that repeats itself: counted, left out
            ++pass.copies[obs->sensorLabel];
            continue;
        }
        ++pass.classes[shortClassName(*obs)];
        // only a comment may be unstamped here (the others were left out above)
        const bool stamped = obs->timestamp != INVALID_TIMESTAMP;
        const double stamp = stamped ? stampSeconds(obs->timestamp) : 0.0;
        if (stamped) pass.start = std::min(pass.start, stamp), pass.end = std::max(pass.end, stamp);
        if (const auto odo = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(obs)) {
            const std::string robot = robotOfLabel(odo->sensorLabel);
            const std::string sensor = sensorOfLabel(odo->sensorLabel);
            if (sensor == "odom" || sensor == "odometry") {
                const auto [it, fresh] = odometryLabel.emplace(robot, odo->sensorLabel);
                if (it->second == odo->sensorLabel && stamped)
                    pass.odometry[robot].push_back({stamp, mrpt::poses::CPose3D(odo->odometry)});
            }
        }
        try {
            localizer.process(obs);
        } catch (const Error& e) {
            // Say which observation the method could not use.
            throw Error(mrpt::format("rawlog %s: observation %zu ('%s', %s, t = %.3f s): %s",
                                     o.rawlogPath.c_str(), n + 1, obs->sensorLabel.c_str(),
                                     obs->GetRuntimeClass()->className,
                                     stampSeconds(obs->timestamp), e.what()));
        }
        progress.updateFraction(reader.fractionRead(), ++n);
    }
    progress.finish();
    return pass;
}

/** The observations the pass changed or left out, one warning per label, and their counts
 *  per label in metrics.json (restamped_observations, unstamped_left_out, copies_left_out). */
void reportLeftOut(const RawlogReader& reader, const LogPass& pass, const LocalizationRunOptions& o,
                   nlohmann::json& metrics) {
    nlohmann::json restamped = nlohmann::json::object();
    for (const auto& [key, count] : reader.restamped()) {
        const auto& [label, cls] = key;
        o.log->warning("rawlog " + o.rawlogPath + ": " + std::to_string(count) + " " +
                       (label.empty() ? std::string("unlabelled") : "'" + label + "'") + " " + cls +
                       " stamped 0 took their sensory frame's time");
        restamped[label.empty() ? "(no label)" : label] = count;
    }
    const auto leftOut = [&](const std::map<std::string, size_t>& counts, const char* why,
                             const char* key) {
        for (const auto& [label, count] : counts)
            o.log->warning("rawlog " + o.rawlogPath + ": " + std::to_string(count) + " '" +
                           printable(label) + "' observation(s) " + why + ": left out");
        if (!counts.empty()) metrics[key] = counts;
    };
    if (!restamped.empty()) metrics["restamped_observations"] = restamped;
    leftOut(pass.unstamped, "stamped 0 with no sensory frame time to take", "unstamped_left_out");
    leftOut(pass.copies, "were exact copies of the one before (same time stamp)",
            "copies_left_out");
}

/** Refuses a run in which the method used none of what it localizes from (naming what the
 *  log holds, and a method that fits it); else the warnings of what it did not use and of
 *  estimates that stop early. */
std::vector<std::string> useWarnings(const ObservationUse& use, const LogPass& pass,
                                     const Trajectories& estimates,
                                     const LocalizationRunOptions& o) {
    if (use.used == 0) {
        std::string why;
        for (const auto& [reason, count] : use.unmatched)
            if (count > 0) why += "; " + std::to_string(count) + " " + reason;
        const std::string hint = o.fitHint ? o.fitHint(pass.classes) : "";
        throw Error("rawlog " + o.rawlogPath + ": the method '" + o.methodName + "' used none of " +
                    std::to_string(use.seen) + " " + use.kind + why + "; the log holds " +
                    contentInWords(pass.classes) + (hint.empty() ? "" : " (" + hint + ")"));
    }
    std::vector<std::string> warnings;
    for (const auto& [reason, count] : use.unmatched)
        if (count > 0)
            warnings.push_back(std::to_string(count) + " " + reason + " (of " +
                               std::to_string(use.seen) + " " + use.kind + " in the log)");
    for (auto& w : earlyEnds(estimates, pass.odometry, pass.start, pass.end))
        warnings.push_back(std::move(w));
    return warnings;
}

/** The ground truth in the world frame: the options' file (its steps timed by the robot's
 *  odometry when its format counts steps), else <rawlog>.<robot>.gt.txt beside the rawlog
 *  for each robot estimated. Says in metrics.json where it came from. */
Trajectories worldTruthOf(const LocalizationRunOptions& o, const LogPass& pass,
                          const Trajectories& estimates, nlohmann::json& metrics) {
    Trajectories worldTruth;
    if (!o.groundTruth.path.empty()) {
        std::vector<double> steps;
        if (const auto odo = pass.odometry.find(o.groundTruth.robot); odo != pass.odometry.end())
            for (const auto& p : odo->second) steps.push_back(p.t);
        if (steps.empty() && o.groundTruth.format != "tum")
            throw Error("ground truth " + o.groundTruth.path + ": the format " +
                        o.groundTruth.format + " counts steps, and robot '" + o.groundTruth.robot +
                        "' has no odometry in " + o.rawlogPath + " to time them");
        worldTruth[o.groundTruth.robot] = loadGroundTruth(o.groundTruth, steps);
        metrics["ground_truth_file"] = o.groundTruth.path;
        metrics["ground_truth_from"] =
            o.groundTruthFrom.empty() ? "the INI's [scenario] ground_truth" : o.groundTruthFrom;
        return worldTruth;
    }
    for (const auto& [robot, traj] : estimates)
        if (const std::string gtPath = groundTruthPath(o.rawlogPath, robot);
            std::filesystem::exists(gtPath))
            worldTruth[robot] = loadTum(gtPath);
    if (!worldTruth.empty())
        metrics["ground_truth_from"] =
            "<rawlog>.<robot>.gt.txt beside the rawlog (mrloc's simulator)";
    return worldTruth;
}

/** Each robot's files (estimates, truth, odometry, covariances) and figures in
 *  metrics.json's "robots"; returns the errors of every robot that is not a baseline. */
std::vector<double> scoreRobots(const Localizer& localizer, const Trajectories& estimates,
                                const LogPass& pass, const Trajectories& worldTruth,
                                const Trajectories& truth, const std::string& outDir,
                                nlohmann::json& metrics) {
    std::vector<Evaluation> truthTimeline;  // the method's robots, not its baselines
    std::vector<double> allErrors;
    const auto baselines = localizer.baselineRobots();
    for (const auto& [robot, traj] : estimates) {
        saveTum(run_dir::estimates(outDir, robot), traj);
        nlohmann::json r;
        r["estimates"] = traj.size();
        if (const auto it = truth.find(robot); it != truth.end()) {
            const auto& gt = it->second;
            saveTum(run_dir::groundTruth(outDir, robot), gt);
            std::vector<double> e;
            for (const auto& te : positionErrors(traj, gt)) e.push_back(te.error);
            // a baseline's errors are its own figure, not the method's
            if (!baselines.count(robot)) allErrors.insert(allErrors.end(), e.begin(), e.end());
            r.update(statsToJson(computeStats(e)));
            // on the truth's timeline: every truth stamp, covered or not (doc/evaluation.md)
            auto onTruth = evaluate(traj, gt);
            r["truth_timeline"] = toJson(onTruth);
            if (!baselines.count(robot)) truthTimeline.push_back(std::move(onTruth));
            if (const auto g = localizer.groundTruthMetrics(robot, gt); g.is_object()) r.update(g);
        }
        if (const auto odo = pass.odometry.find(robot);
            odo != pass.odometry.end() && !odo->second.empty()) {
            saveTum(run_dir::odometry(outDir, robot), odo->second);
            r["odometry"] = odometryErrors(odo->second, worldTruth, robot);
        }
        if (baselines.count(robot)) r["baseline"] = true;
        metrics["robots"][robot] = r;
    }
    for (const auto& [robot, track] : localizer.covariances())
        if (estimates.count(robot) && !track.empty()) {
            saveCovariances(run_dir::covariance(outDir, robot), track);
            metrics["robots"][robot]["covariances"] = track.size();
        }
    if (!truthTimeline.empty()) metrics["truth_timeline"] = pooledJson(truthTimeline);
    return allErrors;
}

}  // namespace

LocalizationResult runLocalization(Localizer& localizer, const LocalizationRunOptions& o) {
    RawlogReader reader(o.rawlogPath);
    const auto start = std::chrono::steady_clock::now();
    const LogPass pass = passRawlog(reader, localizer, o);
    LocalizationResult result;
    auto& metrics = result.metrics;
    metrics["method"] = o.methodName;
    metrics["rawlog"] = o.rawlogShownAs.empty() ? o.rawlogPath : o.rawlogShownAs;
    metrics["observations"] = pass.observations;
    metrics["robots"] = nlohmann::json::object();  // none: a method that found nothing
    metrics["rawlog_content"] = pass.classes;
    reportLeftOut(reader, pass, o, metrics);
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const auto estimates = localizer.estimates();
    const ObservationUse use = localizer.observationUse();
    const auto warnings = useWarnings(use, pass, estimates, o);
    for (const auto& w : warnings) o.log->warning(o.methodName + ": " + w);
    makeDirectories(o.outDir);
    metrics["use"] = toJson(use);
    metrics["warnings"] = warnings;
    metrics["rawlog_format"] = reader.format() == RawlogFormat::ActionsSensoryFrames
                                   ? "actions+sensory-frames"
                                   : "observations-only";
    const Trajectories worldTruth = worldTruthOf(o, pass, estimates, metrics);
    result.truth = localizer.truthInEstimateFrame(worldTruth);
    const auto allErrors =
        scoreRobots(localizer, estimates, pass, worldTruth, result.truth, o.outDir, metrics);
    metrics["ground_truth"] = !allErrors.empty();
    metrics.update(statsToJson(computeStats(allErrors)));
    metrics["wall_s"] = wall;
    auto method = localizer.methodMetrics();
    if (const auto t = localizer.truthMetrics(result.truth); t.is_object()) method.update(t);
    metrics[o.methodName] = method;

    localizer.writeOutputs(o.outDir, result.truth);
    saveJson(run_dir::metrics(o.outDir), metrics);
    return result;
}

}  // namespace mrloc::common
