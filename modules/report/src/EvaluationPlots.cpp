#include <mrloc/common/Error.h>
#include <mrloc/report/EvaluationPlots.h>
#include <mrloc/report/Palette.h>
#include <mrloc/report/Plots.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

namespace mrloc::report {

namespace {

/** Points per curve at most: a 10^6-stamp truth is thinned to every k-th stamp, which a
 *  900-pixel-wide picture cannot tell apart from all of them. */
constexpr size_t kMaxPoints = 4000;
/** Shaded stretches at most: the longest, when a log has more. */
constexpr size_t kMaxShaded = 300;
constexpr const char* kShade = "pal_lightgrey";  // Palette.h, a variable in every script

size_t strideFor(size_t n) { return std::max<size_t>(1, (n + kMaxPoints - 1) / kMaxPoints); }

/** The earliest truth stamp of all the tracks: the time axis' origin. */
double originOf(const std::vector<EvaluatedTrack>& tracks) {
    double t0 = std::numeric_limits<double>::infinity();
    for (const auto& tr : tracks)
        if (!tr.truth.empty()) t0 = std::min(t0, tr.truth.front().t);
    return std::isfinite(t0) ? t0 : 0.0;
}

/** A data block of (t - t0, value(error)) at the covered stamps, thinned, with a blank line
 *  (gnuplot breaks the line there) where an uncovered stretch lies between two of them or
 *  `breakBetween` says so. */
template <class Value, class Break>
std::string coveredBlock(const std::string& name, const common::Evaluation& e, double t0,
                         Value value, Break breakBetween) {
    std::set<double> gapStarts;
    for (const auto& [from, to] : e.coverage.uncovered) gapStarts.insert(from);
    std::string s = "$" + name + " << EOD\n";
    const size_t stride = strideFor(e.errors.size());
    const common::PoseError* written = nullptr;
    bool pendingBreak = false;
    for (size_t k = 0; k < e.errors.size(); ++k) {
        const auto& p = e.errors[k];
        const bool afterGap = k > 0 && gapStarts.count(e.errors[k - 1].t);
        pendingBreak = pendingBreak || afterGap;
        // a gap's edges are never thinned away
        const bool keep =
            k % stride == 0 || k + 1 == e.errors.size() || gapStarts.count(p.t) || afterGap;
        if (!keep) continue;
        if (written && (pendingBreak || breakBetween(*written, p))) s += "\n";
        s += mrpt::format("%.6f %.9g\n", p.t - t0, value(p));
        written = &p;
        pendingBreak = false;
    }
    return s + "EOD\n";
}

std::string errorBlock(const std::string& name, const common::Evaluation& e, double t0) {
    return coveredBlock(
        name, e, t0, [](const common::PoseError& p) { return p.translation; },
        [](const common::PoseError&, const common::PoseError&) { return false; });
}

/** gnuplot objects shading each of `spans` (behind the curves), the longest kMaxShaded. */
std::string shadingOf(std::vector<std::pair<double, double>> spans, double t0) {
    if (spans.size() > kMaxShaded) {
        std::nth_element(
            spans.begin(), spans.begin() + kMaxShaded, spans.end(),
            [](const auto& a, const auto& b) { return a.second - a.first > b.second - b.first; });
        spans.resize(kMaxShaded);
    }
    std::string s;
    for (const auto& [from, to] : spans)
        s += mrpt::format(
            "set object rect from %.6f, graph 0 to %.6f, graph 1 fc rgb %s fs solid 0.6 "
            "noborder behind\n",
            from - t0, std::max(to - t0, from - t0 + 1e-6), kShade);
    return s;
}

/** gnuplot objects shading each uncovered stretch of the tracks (behind the curves). */
std::string shading(const std::vector<const common::Evaluation*>& evaluations, double t0) {
    std::vector<std::pair<double, double>> spans;
    for (const auto* e : evaluations)
        spans.insert(spans.end(), e->coverage.uncovered.begin(), e->coverage.uncovered.end());
    return shadingOf(std::move(spans), t0);
}

/** The stretches where no track is covered: the intersection of their uncovered spans
 *  (each list in time order, as Coverage keeps them). */
std::vector<std::pair<double, double>> noneCovered(const std::vector<EvaluatedTrack>& tracks) {
    if (tracks.empty()) return {};
    std::vector<std::pair<double, double>> common = tracks.front().estimate.coverage.uncovered;
    for (size_t k = 1; k < tracks.size() && !common.empty(); ++k) {
        const auto& other = tracks[k].estimate.coverage.uncovered;
        std::vector<std::pair<double, double>> both;
        size_t i = 0, j = 0;
        while (i < common.size() && j < other.size()) {
            const double from = std::max(common[i].first, other[j].first);
            const double to = std::min(common[i].second, other[j].second);
            if (from < to) both.emplace_back(from, to);
            (common[i].second < other[j].second ? i : j)++;
        }
        common = std::move(both);
    }
    return common;
}

std::string shadingKey(bool any) {
    return any ? std::string(", NaN with boxes fs solid 0.6 noborder lc rgb ") + kShade +
                     " title 'not covered (no estimate)'"
               : "";
}

bool anyUncovered(const std::vector<const common::Evaluation*>& evaluations) {
    for (const auto* e : evaluations)
        if (!e->coverage.uncovered.empty()) return true;
    return false;
}

std::string truthBlock(const std::string& name, const common::Trajectory& truth, double t0,
                       int column) {
    std::string s = "$" + name + " << EOD\n";
    const size_t stride = strideFor(truth.size());
    double previousHeading = NAN;
    for (size_t k = 0; k < truth.size(); k += stride) {
        const auto& p = truth[k].pose;
        const double heading = mrpt::RAD2DEG(p.yaw());
        if (column == 2 && std::abs(heading - previousHeading) > 180) s += "\n";
        previousHeading = heading;
        s += mrpt::format("%.6f %.9g\n", truth[k].t - t0,
                          column == 0   ? p.x()
                          : column == 1 ? p.y()
                                        : heading);
    }
    return s + "EOD\n";
}

/** Where the key goes and the canvas' size: beside the plot for a robot or two, below it
 *  (in columns, the canvas taller by its rows) for more, so that it never takes half the
 *  picture. `entries` counts the key's lines. */
std::pair<std::string, std::string> keyAndSize(size_t robots, size_t entries) {
    if (robots <= 2) return {"", "1000,500"};
    const size_t rows = (entries + 2) / 3;
    return {"set key outside below center horizontal maxcols 3\n",
            mrpt::format("1000,%zu", 500 + 20 * rows)};
}

/** Robots beyond the palette's seven colours are not keyed one by one: a key of a hundred
 *  names would be taller than the plot (omnivision_swarm100 measured 1,760 px of key above
 *  83 px of data). Their curves share the colours in turn and the key says what a line is. */
constexpr size_t kKeyedRobots = 7;

/** The title of the `k`-th curve (from 0) of a kind: the robot's own name when every robot
 *  is keyed, else one entry for the kind (`together`) on its first curve and none after. */
std::string curveTitle(size_t robots, size_t k, const std::string& own,
                       const std::string& together) {
    if (robots <= kKeyedRobots) return " title " + gnuplotString(own);
    return k == 0 ? " title " + gnuplotString(together) : " notitle";
}

/** The one key entry of every estimate's curve, and of every odometry's, past kKeyedRobots. */
std::string eachRobotTitle(size_t robots) {
    return mrpt::format("each line a robot (%zu robots)", robots);
}
constexpr const char* kEachOdometryTitle = "dashed: that robot's odometry alone";

}  // namespace

std::optional<Ellipse> twoSigmaEllipse(const mrpt::math::CMatrixDouble33& cov) {
    Eigen::Matrix2d c;
    c << cov(0, 0), cov(0, 1), cov(1, 0), cov(1, 1);
    if (!c.allFinite() || c(0, 0) < 0 || c(1, 1) < 0) return std::nullopt;
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(c);
    if (eig.info() != Eigen::Success || eig.eigenvalues()(0) < -1e-12) return std::nullopt;
    const double minor = std::sqrt(std::max(0.0, eig.eigenvalues()(0)));
    const double major = std::sqrt(std::max(0.0, eig.eigenvalues()(1)));
    const Eigen::Vector2d axis = eig.eigenvectors().col(1);
    // 2 sigma each side: full axes of 4 sigma
    return Ellipse{4 * major, 4 * minor, mrpt::RAD2DEG(std::atan2(axis.y(), axis.x()))};
}

/** Each track's uncovered stretches as a band in its colour along the bottom of the plot,
 *  one band per track (several robots: a full-height shade of one would hide the others). */
std::string bands(const std::vector<EvaluatedTrack>& tracks, double t0) {
    std::string s;
    const double height = std::min(0.03, 0.25 / double(tracks.size()));
    int i = 0;
    for (const auto& tr : tracks) {
        ++i;
        auto spans = tr.estimate.coverage.uncovered;
        if (spans.size() > kMaxShaded) spans.resize(kMaxShaded);  // in time order: the first
        for (const auto& [from, to] : spans)
            s += mrpt::format(
                "set object rect from %.6f, graph %.4f to %.6f, graph %.4f fc lt %d fs solid "
                "0.8 noborder front\n",
                from - t0, height * (i - 1), std::max(to - t0, from - t0 + 1e-6), height * i, i);
    }
    return s;
}

void plotTruthTimelineError(const std::vector<EvaluatedTrack>& tracks, const std::string& pngPath) {
    const double t0 = originOf(tracks);
    std::string body, plot;
    std::vector<const common::Evaluation*> shaded;
    const size_t n = tracks.size();
    const std::string each = eachRobotTitle(n);
    int i = 0;
    size_t estimates = 0, odometries = 0;
    for (const auto& tr : tracks) {
        ++i;
        if (!tr.estimate.errors.empty()) {
            body += errorBlock("e" + std::to_string(i), tr.estimate, t0);
            plot += std::string(plot.empty() ? "" : ", ") + "$e" + std::to_string(i) +
                    " using 1:2 with lines lw 1.5 lc " + std::to_string(i) +
                    curveTitle(n, estimates++, tr.name, each);
        }
        shaded.push_back(&tr.estimate);
        if (tr.odometry && !tr.odometry->errors.empty()) {
            body += errorBlock("o" + std::to_string(i), *tr.odometry, t0);
            plot += std::string(plot.empty() ? "" : ", ") + "$o" + std::to_string(i) +
                    " using 1:2 with lines dt 2 lw 1.2 lc " + std::to_string(i) +
                    curveTitle(n, odometries++, tr.name + ": odometry alone", kEachOdometryTitle);
        }
    }
    if (plot.empty()) throw Error("no covered truth stamp to plot for " + pngPath);
    const bool one = tracks.size() == 1, keyed = n <= kKeyedRobots;
    // one robot: its uncovered stretches shaded; up to seven: a band of each robot's colour
    // along the bottom; more: shaded where no robot is covered (a band per robot would be a
    // striped block a quarter of the plot high)
    const auto none = keyed ? std::vector<std::pair<double, double>>() : noneCovered(tracks);
    const std::string key =
        !anyUncovered(shaded) ? ""
        : one                 ? shadingKey(true)
        : keyed               ? ", NaN with boxes fs solid 0.8 noborder lc rgb pal_grey title "
                                "'band at the bottom: that robot not covered'"
        : none.empty()        ? ""
                       : std::string(", NaN with boxes fs solid 0.6 noborder lc rgb ") + kShade +
                             " title 'no robot covered (no estimate)'";
    const std::string uncovered = one     ? shading(shaded, t0)
                                  : keyed ? bands(tracks, t0)
                                          : shadingOf(none, t0);
    const auto [keyPlace, size] = keyAndSize(n, n <= kKeyedRobots ? 2 * n + 1 : 3);
    runGnuplot(body + uncovered + keyPlace +
                   "set xlabel 'time since the truth''s first stamp (s)'\n"
                   "set ylabel 'position error at the truth''s stamps (m)'\nset yrange [0:*]\n"
                   "plot " +
                   plot + key + "\n",
               pngPath, size);
}

void plotTruthTimelineCdf(const std::vector<EvaluatedTrack>& tracks, const std::string& pngPath) {
    std::string body, plot;
    const size_t n = tracks.size();
    size_t estimates = 0, odometries = 0;
    const auto curve = [&](const common::Evaluation& e, const std::string& name, int colour,
                           const std::string& title, bool odometry) {
        if (e.errors.empty()) return;
        std::vector<double> v;
        for (const auto& p : e.errors) v.push_back(p.translation);
        std::sort(v.begin(), v.end());
        std::vector<std::pair<double, double>> xy;
        const size_t stride = strideFor(v.size());
        for (size_t k = 0; k < v.size(); k += stride)
            xy.emplace_back(v[k], double(k + 1) / double(v.size()));
        xy.emplace_back(v.back(), 1.0);
        body += dataBlock(name, xy);
        plot += std::string(plot.empty() ? "plot " : ", ") + "$" + name +
                " using 1:2 with steps lw 1.5 " + (odometry ? "dt 2" : "") + " lc " +
                std::to_string(colour) +
                (odometry ? curveTitle(n, odometries++, title, kEachOdometryTitle)
                          : curveTitle(n, estimates++, title, eachRobotTitle(n)));
    };
    int i = 0;
    for (const auto& tr : tracks) {
        ++i;
        curve(tr.estimate, "c" + std::to_string(i), i, tr.name, false);
        if (tr.odometry)
            curve(*tr.odometry, "d" + std::to_string(i), i, tr.name + ": odometry alone", true);
    }
    if (plot.empty()) throw Error("no covered truth stamp to plot for " + pngPath);
    const auto [keyPlace, size] = keyAndSize(n, n <= kKeyedRobots ? 2 * n : 2);
    runGnuplot(body + keyPlace +
                   "set xlabel 'position error (m)'\n"
                   "set ylabel 'share of the covered truth stamps'\nset yrange [0:1.02]\n"
                   "set xrange [0:*]\n" +
                   plot + "\n",
               pngPath, size);
}

void plotPoseOverTime(const EvaluatedTrack& tr, const std::string& pngPath) {
    if (tr.estimate.errors.empty()) throw Error("no covered truth stamp to plot for " + pngPath);
    const double t0 = originOf({tr});
    const auto noBreak = [](const common::PoseError&, const common::PoseError&) { return false; };
    std::string body =
        truthBlock("tx", tr.truth, t0, 0) + truthBlock("ty", tr.truth, t0, 1) +
        truthBlock("th", tr.truth, t0, 2) +
        coveredBlock(
            "ex", tr.estimate, t0, [](const common::PoseError& p) { return p.estimate.x(); },
            noBreak) +
        coveredBlock(
            "ey", tr.estimate, t0, [](const common::PoseError& p) { return p.estimate.y(); },
            noBreak) +
        coveredBlock(
            "eh", tr.estimate, t0,
            [](const common::PoseError& p) { return mrpt::RAD2DEG(p.estimate.phi()); },
            [](const common::PoseError& a, const common::PoseError& b) {
                return std::abs(a.estimate.phi() - b.estimate.phi()) > M_PI;  // across +-180
            });
    const std::string shade = shading({&tr.estimate}, t0);
    const std::string key = shadingKey(!tr.estimate.coverage.uncovered.empty());
    // one margin for the three panels, whatever their keys, so that their time axes line up
    std::string panels = "set lmargin 10\nset rmargin 36\nset multiplot layout 3,1 title " +
                         gnuplotString(tr.name + ": truth and estimate against time") + "\n";
    const char* names[] = {"x (m)", "y (m)", "heading (deg)"};
    const char* truthBlocks[] = {"$tx", "$ty", "$th"};
    const char* estimateBlocks[] = {"$ex", "$ey", "$eh"};
    for (int k = 0; k < 3; ++k) {
        panels += shade + "set ylabel '" + std::string(names[k]) + "'\n";
        panels += k == 2 ? "set xlabel 'time since the truth''s first stamp (s)'\n"
                           "set yrange [-180:180]\nset ytics 90\n"
                         : "unset xlabel\n";
        panels += "plot " + std::string(truthBlocks[k]) +
                  " using 1:2 with lines lw 5 lc rgb pal_lightgrey title 'truth', " +
                  estimateBlocks[k] + " using 1:2 with lines lw 1.2 lc 1 title 'estimate'" +
                  (k == 0 ? key : "") + "\nunset object\n";
    }
    runGnuplot(body + panels + "unset multiplot\n", pngPath, "1000,800");
}

void plotErrorTopView(const EvaluatedTrack& tr, const std::string& pngPath) {
    if (tr.estimate.errors.empty()) throw Error("no covered truth stamp to plot for " + pngPath);
    std::string body = "$truth << EOD\n";
    for (size_t k = 0, s = strideFor(tr.truth.size()); k < tr.truth.size(); k += s)
        body += mrpt::format("%.6f %.6f\n", tr.truth[k].pose.x(), tr.truth[k].pose.y());
    body += "EOD\n";
    // the estimate as "x y error" at the covered stamps, thinned, broken where a stretch is
    // not covered: the error is the colour
    body += "$path << EOD\n";
    std::set<double> gapStarts;
    for (const auto& [from, to] : tr.estimate.coverage.uncovered) gapStarts.insert(from);
    bool broken = false;
    for (size_t k = 0, s = strideFor(tr.estimate.errors.size()); k < tr.estimate.errors.size();
         ++k) {
        const auto& p = tr.estimate.errors[k];
        if (gapStarts.count(p.t)) broken = true;
        if (k % s != 0 && k + 1 != tr.estimate.errors.size()) continue;
        body += mrpt::format("%.6f %.6f %.6f\n", p.estimate.x(), p.estimate.y(), p.translation);
        if (broken) body += "\n", broken = false;
    }
    body += "EOD\n";
    // ellipses at the covered estimate nearest each covariance's stamp, a few spread evenly
    std::string ellipses = "$ell << EOD\n";
    size_t drawn = 0;
    const auto& errors = tr.estimate.errors;
    const size_t every = std::max<size_t>(1, tr.covariances.size() / 40);
    for (size_t k = 0; k < tr.covariances.size() && !errors.empty(); k += every) {
        const auto& c = tr.covariances[k];
        const auto at =
            std::lower_bound(errors.begin(), errors.end(), c.t,
                             [](const common::PoseError& p, double t) { return p.t < t; });
        if (at == errors.end() || std::abs(at->t - c.t) > tr.estimate.coverage.maxGap) continue;
        const auto e = twoSigmaEllipse(c.cov);
        if (!e) continue;
        ellipses +=
            mrpt::format("%.6f %.6f %.6f %.6f %.3f\n", at->estimate.x(), at->estimate.y(), e->major,
                         e->minor, e->angleDeg + mrpt::RAD2DEG(tr.estimate.alignment.phi()));
        ++drawn;
    }
    ellipses += "EOD\n";
    // a long, thin path drawn to scale would be a line: each side is at least 40 % of the
    // longer one, so the picture keeps a readable height with its scale still true
    double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
    const auto extend = [&](const auto& p) {  // a CPose2D or CPose3D
        x0 = std::min(x0, p.x()), x1 = std::max(x1, p.x());
        y0 = std::min(y0, p.y()), y1 = std::max(y1, p.y());
    };
    for (const auto& p : tr.truth) extend(p.pose);
    for (const auto& p : errors) extend(p.estimate);
    const double side = std::max({x1 - x0, y1 - y0, 0.1}) * 1.1;
    const auto drawnSpan = [&](double lo, double hi) {  // the width drawn for [lo, hi]
        return std::max(hi - lo + 0.05 * side, 0.4 * side);
    };
    const auto range = [&](double lo, double hi) {
        const double half = drawnSpan(lo, hi) / 2, mid = (lo + hi) / 2;
        return mrpt::format("[%.6f:%.6f]", mid - half, mid + half);
    };
    // the canvas's height follows the drawn aspect (plot about 700 px wide, title, axis and
    // key about 200 px), so a wide path leaves no empty band above and below it
    const double aspect = drawnSpan(y0, y1) / drawnSpan(x0, x1);
    const int height = static_cast<int>(std::clamp(200 + 700 * aspect, 450.0, 950.0));
    std::string plot =
        "plot $truth using 1:2 with lines lw 6 lc rgb pal_lightgrey title 'truth', "
        "$path using 1:2:3 with lines lw 2.5 lc palette title 'estimate (colour: its error)'";
    if (drawn)
        plot +=
            ", $ell using 1:2:3:4:5 with ellipses lw 1 lc rgb pal_black title "
            "'2-sigma position covariance'";
    runGnuplot(body + ellipses +
                   "set size ratio -1\nset xlabel 'x (m)'\nset ylabel 'y (m)'\n"
                   "set xrange " +
                   range(x0, x1) + "\nset yrange " + range(y0, y1) +
                   "\n"
                   "set cblabel 'position error (m)'\nset cbrange [0:*]\n" +
                   palette::gnuplotValueScale() + "set title " +
                   gnuplotString(tr.name + ": path from above, coloured by the error") + "\n" +
                   "set key outside bottom center horizontal\n" + plot + "\n",
               pngPath, mrpt::format("900,%d", height));
}

}  // namespace mrloc::report
