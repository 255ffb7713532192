// `mrloc eval`: one trajectory file scored against another on the truth's timeline
// (common::evaluate, doc/evaluation.md): what a user runs on the output of mrloc or of
// another tool, so that two localizers are scored the same way.
#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/Evaluation.h>
#include <mrloc/common/GroundTruthFile.h>
#include <mrloc/common/Metrics.h>
#include <mrloc/common/Names.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>

#include <iostream>

#include "CommandLine.h"
#include "Commands.h"

namespace mrloc::app {

namespace {

/** A TUM file; another truth format is named, as it has no times of its own. */
common::Trajectory trajectoryFile(const std::string& path, const std::string& what) {
    const auto format = common::groundTruthFormatOf(path);
    if (format && *format != "tum")
        throw Error(common::pathInWords(path) + ": " + what + " in the " + *format +
                    " format counts odometry steps, not times (`mrloc localize` with "
                    "[scenario] ground_truth times it by the rawlog); eval takes TUM files "
                    "(t x y z qx qy qz qw)");
    auto t = common::loadTum(path);
    if (t.empty()) throw Error(common::pathInWords(path) + ": " + what + " holds no pose");
    return t;
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
        "relative pose error over a distance and a time. Both files TUM (t x y z qx qy qz qw), "
        "as mrloc writes estimates.<robot>.txt and groundtruth.<robot>.txt.");
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
    const auto e = common::evaluate(trajectoryFile(estimate.getValue(), "the estimate"),
                                    trajectoryFile(truth.getValue(), "the truth"), o);
    if (json.getValue())
        std::cout << common::toJson(e).dump(2) << "\n";
    else
        std::cout << table(e);
    return 0;
}

}  // namespace mrloc::app
