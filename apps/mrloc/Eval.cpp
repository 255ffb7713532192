// `mrloc eval`: one trajectory file scored against another on the truth's timeline
// (common::evaluate, doc/evaluation.md): what a user runs on the output of mrloc or of
// another tool, so that two localizers are scored the same way.
#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/Evaluation.h>
#include <mrloc/common/GroundTruthFile.h>
#include <mrloc/common/Metrics.h>
#include <mrloc/common/Names.h>
#include <mrloc/common/Rawlog.h>
#include <mrloc/common/RunDirectory.h>
#include <mrloc/common/RunTransaction.h>
#include <mrloc/report/EvaluationPlots.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>
#include <mrpt/obs/CObservationOdometry.h>

#include <iostream>

#include "CommandLine.h"
#include "Commands.h"
#include "RunSteps.h"
#include "StderrLog.h"

namespace mrloc::app {

namespace {

/** A step's time: its odometry reading's (the action, as `mrloc localize` times MRPT's
 *  ground truth), or its sensory frame's (the observations after the action: where
 *  pf-localization's estimate after step i is). */
enum class StepTime { Odometry, Frame };

/** The time of each step of a rawlog, by its first odometry stream (MRPT's actions give one
 *  reading per step): the time base of a file that counts steps. */
std::vector<double> stepTimes(const std::string& rawlog, StepTime at) {
    common::RawlogReader reader(rawlog);
    std::vector<double> times;
    std::string label;
    bool waitingForFrame = false;  // a step whose frame's time is not known yet
    for (mrpt::obs::CObservation::Ptr obs; reader.next(obs);) {
        const auto odo = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(obs);
        if (odo && label.empty()) label = odo->sensorLabel;
        if (odo && odo->sensorLabel == label && odo->timestamp != INVALID_TIMESTAMP) {
            if (waitingForFrame) times.pop_back();  // a step with no frame: none to time it
            times.push_back(common::stampSeconds(odo->timestamp));
            waitingForFrame = at == StepTime::Frame;
        } else if (!odo && waitingForFrame && obs->timestamp != INVALID_TIMESTAMP) {
            times.back() = common::stampSeconds(obs->timestamp);
            waitingForFrame = false;
        }
    }
    if (waitingForFrame) times.pop_back();
    if (times.empty())
        throw Error("rawlog " + common::pathInWords(rawlog) +
                    ": no odometry to time a file of steps by");
    return times;
}

/** A TUM file, or a file of steps (MRPT's ground truth formats, doc/import.md) timed by the
 *  odometry of `rawlog`. */
common::Trajectory trajectoryFile(const std::string& path, const std::string& what,
                                  const std::string& rawlog, StepTime at) {
    const auto format = common::groundTruthFormatOf(path);
    common::Trajectory t;
    if (format && *format != "tum") {
        if (rawlog.empty())
            throw Error(common::pathInWords(path) + ": " + what + " in the " + *format +
                        " format counts odometry steps, not times: give the rawlog they are "
                        "steps of (--rawlog), or a TUM file (t x y z qx qy qz qw)");
        common::GroundTruthSource source;
        source.path = path;
        source.format = *format;
        t = common::loadGroundTruth(source, stepTimes(rawlog, at));
    } else {
        t = common::loadTum(path);
    }
    if (t.empty()) throw Error(common::pathInWords(path) + ": " + what + " holds no pose");
    // two poses at one time (to the microsecond TUM keeps) cannot both be the pose there:
    // interpolation would take either (MRPT's kf-slam demo stamps 249 steps within 8 ms)
    for (size_t k = 1; k < t.size(); ++k)
        if (!(t[k].t - t[k - 1].t > 1e-6))
            throw Error(common::pathInWords(path) + ": " + what + "'s poses " + std::to_string(k) +
                        " and " + std::to_string(k + 1) + " are not 1 us apart in time (" +
                        (rawlog.empty() || !format || *format == "tum"
                             ? std::string("the file's stamps")
                             : "the stamps of " + common::pathInWords(rawlog) + "'s odometry") +
                        "): their order in time cannot be told");
    return t;
}

/** eval.json, provenance.json (the command line) and the pictures of doc/evaluation.md, in
 *  `dir` (the run folder's staging copy: all of them, or the folder as it was). */
void writeEvalFolder(const std::string& dir, const common::Evaluation& e,
                     const common::Trajectory& truth, const std::string& estimatePath,
                     const std::string& truthPath, const std::string& command) {
    nlohmann::json j = common::toJson(e);
    j["estimate_file"] = estimatePath;
    j["truth_file"] = truthPath;
    common::saveJson(dir + "/eval.json", j);
    common::saveJson(common::run_dir::provenance(dir), {{"steps", {{"eval", command}}}});
    if (e.errors.empty()) return;  // nothing covered: eval.json says so, no picture to draw
    report::EvaluatedTrack track;
    track.name = "estimate";
    track.estimate = e;
    track.truth = truth;
    report::plotTruthTimelineError({track}, dir + "/error_time.png");
    report::plotTruthTimelineCdf({track}, dir + "/error_cdf.png");
    report::plotPoseOverTime(track, dir + "/pose_time.png");
    report::plotErrorTopView(track, dir + "/error_topview.png");
}

/** "1m" or "0.5s": an RPE delta. */
void readDelta(const std::string& text, common::EvaluationOptions& o) {
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    const std::string unit = end ? std::string(end) : "";
    if (end == text.c_str() || !(v > 0) || !(v <= 1e6) || (unit != "m" && unit != "s"))
        throw Error("--delta " + common::printable(text) +
                    ": a distance or a time above 0, as 1m or 0.5s");
    (unit == "m" ? o.rpeDistance : o.rpeTime) = v;
}

std::string statsLine(const char* name, const common::ErrorStats& s, double scale,
                      const char* unit) {
    if (!s.n) return mrpt::format("%-22s no pairs\n", name);
    return mrpt::format("%-22s rmse %.4g  mean %.4g  median %.4g  p95 %.4g  max %.4g %s (n %zu)\n",
                        name, s.rmse * scale, s.mean * scale, s.median * scale, s.p95 * scale,
                        s.max * scale, unit, s.n);
}

std::string table(const common::Evaluation& e) {
    const auto& c = e.coverage;
    const double kDeg = mrpt::RAD2DEG(1.0);
    std::string out = mrpt::format(
        "alignment %s; coverage %.1f %% (%zu of %zu truth stamps, %.3f .. %.3f s), longest gap "
        "%.3f s (gap limit %.3f s)\n",
        common::alignmentName(e.align), 100 * c.share(), c.covered, c.truthStamps, c.start, c.end,
        c.longestGap, c.maxGap);
    out += statsLine("APE translation", e.translation, 1, "m");
    out += statsLine("APE heading", e.heading, kDeg, "deg");
    out += statsLine(mrpt::format("RPE %gm translation", e.rpeDistance.delta).c_str(),
                     e.rpeDistance.translation, 1, "m");
    out += statsLine(mrpt::format("RPE %gm heading", e.rpeDistance.delta).c_str(),
                     e.rpeDistance.heading, kDeg, "deg");
    out += statsLine(mrpt::format("RPE %gs translation", e.rpeTime.delta).c_str(),
                     e.rpeTime.translation, 1, "m");
    out += statsLine(mrpt::format("RPE %gs heading", e.rpeTime.delta).c_str(), e.rpeTime.heading,
                     kDeg, "deg");
    return out;
}

}  // namespace

int eval(int argc, char** argv) {
    CommandLine cmd(
        "mrloc eval: an estimated trajectory scored against the truth on the truth's time "
        "stamps (doc/evaluation.md): absolute pose error with its coverage (truth stamps before "
        "the first estimate, after the last or inside a gap are not covered, and counted), "
        "relative pose error over a distance and a time. Files in TUM (t x y z qx qy qz qw), "
        "as mrloc writes estimates.<robot>.txt and groundtruth.<robot>.txt, or in MRPT's "
        "ground truth formats of steps timed by --rawlog's odometry.");
    TCLAP::UnlabeledValueArg<std::string> estimate("estimate", "estimated trajectory (TUM)", true,
                                                   "", "ESTIMATE", cmd);
    TCLAP::UnlabeledValueArg<std::string> truth("truth", "ground truth (TUM)", true, "", "TRUTH",
                                                cmd);
    TCLAP::ValueArg<std::string> align("", "align", "none (default), se2 or origin", false, "none",
                                       "none|se2|origin", cmd);
    TCLAP::MultiArg<std::string> delta("", "delta",
                                       "an RPE delta: 1m of travelled truth, 1s (defaults both)",
                                       false, "1m|1s", cmd);
    TCLAP::ValueArg<double> maxGap(
        "", "max-gap",
        "s between two estimates beyond which the truth stamps between them are not covered "
        "(default: 5 x the median estimate interval, at least 1 s)",
        false, 0, "S", cmd);
    TCLAP::SwitchArg json("j", "json", "print eval.json's JSON instead of a table", cmd);
    TCLAP::ValueArg<std::string> rawlog(
        "", "rawlog",
        "the rawlog whose odometry steps time a file of steps (MRPT's i x y phi or x y z yaw "
        "pitch roll ground truth)",
        false, "", "RAWLOG", cmd);
    TCLAP::ValueArg<std::string> stepsAt(
        "", "steps-at",
        "a step's time with --rawlog: its odometry reading (default, as mrloc localize times "
        "MRPT's ground truth) or its sensory frame (frame: where pf-localization's estimate "
        "after the step is)",
        false, "odometry", "odometry|frame", cmd);
    TCLAP::ValueArg<std::string> out(
        "o", "out", "a folder to write eval.json and the pictures to (doc/evaluation.md)", false,
        "", "DIR", cmd);
    if (const auto code = parseArgs(cmd, argc, argv)) return *code;

    common::EvaluationOptions o;
    const auto a = common::alignmentNamed(align.getValue());
    if (!a) throw Error("--align " + common::printable(align.getValue()) + ": none, se2 or origin");
    o.align = *a;
    for (const auto& d : delta.getValue()) readDelta(d, o);
    if (maxGap.isSet()) {
        if (!(maxGap.getValue() > 0) || !(maxGap.getValue() <= 1e9))
            throw Error("--max-gap must be a time above 0 s");
        o.maxGap = maxGap.getValue();
    }
    if (stepsAt.getValue() != "odometry" && stepsAt.getValue() != "frame")
        throw Error("--steps-at " + common::printable(stepsAt.getValue()) + ": odometry or frame");
    const StepTime at = stepsAt.getValue() == "frame" ? StepTime::Frame : StepTime::Odometry;
    const auto truthPath = truth.getValue();
    const auto truthTrajectory = trajectoryFile(truthPath, "the truth", rawlog.getValue(), at);
    const auto e =
        common::evaluate(trajectoryFile(estimate.getValue(), "the estimate", rawlog.getValue(), at),
                         truthTrajectory, o);
    if (out.isSet()) {
        common::checkRunFolderPath(out.getValue(), "--out");
        const StderrLog log(false);
        inTransaction(out.getValue(), "eval", log, [&](const std::string& dir) {
            writeEvalFolder(dir, e, truthTrajectory, estimate.getValue(), truthPath,
                            commandLine(argc, argv));
        });
    }
    if (json.getValue())
        std::cout << common::toJson(e).dump(2) << "\n";
    else
        std::cout << table(e);
    return 0;
}

}  // namespace mrloc::app
