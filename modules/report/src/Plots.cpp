#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/report/Plots.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace mrloc::report {

namespace {

/** Runs a gnuplot script whose data blocks are inline; output to pngPath atomically. */
void runGnuplot(const std::string& body, const std::string& pngPath,
                const std::string& size = "900,500") {
    common::PendingFile out(pngPath);
    const std::string script = out.tempPath() + ".gp";
    {
        std::ofstream s(script);
        s << "set terminal pngcairo size " << size << " font 'Sans,11'\n"
          << "set output '" << out.tempPath() << "'\n"
          << "set grid\nset key top left\n"
          << body;
    }
    const std::string cmd = "gnuplot '" + script + "' 2>'" + script + ".err'";
    const int rc = std::system(cmd.c_str());
    std::string err;
    {
        std::ifstream e(script + ".err");
        std::getline(e, err, '\0');
    }
    std::filesystem::remove(script);
    std::filesystem::remove(script + ".err");
    if (rc != 0)
        throw Error("gnuplot failed for " + pngPath + " (is gnuplot-nox installed?): " + err);
    out.commit();
}

std::string dataBlock(const std::string& name, const std::vector<std::pair<double, double>>& xy) {
    std::string s = "$" + name + " << EOD\n";
    char line[64];
    for (const auto& [x, y] : xy) {
        std::snprintf(line, sizeof line, "%.6f %.6f\n", x, y);
        s += line;
    }
    return s + "EOD\n";
}

}  // namespace

void plotErrorOverTime(const RobotErrors& errors, const std::string& pngPath) {
    std::string body, plot;
    int i = 0;
    for (const auto& [robot, e] : errors) {
        if (e.empty()) continue;
        std::vector<std::pair<double, double>> xy;
        for (const auto& te : e) xy.emplace_back(te.t - e.front().t, te.error);
        body += dataBlock("d" + std::to_string(i), xy);
        plot += std::string(plot.empty() ? "plot " : ", ") + "$d" + std::to_string(i) +
                " using 1:2 with lines lw 1.5 title '" + robot + "'";
        ++i;
    }
    if (plot.empty()) throw Error("no errors to plot for " + pngPath);
    runGnuplot(body + "set xlabel 'time (s)'\nset ylabel 'position error (m)'\n" + plot + "\n",
               pngPath);
}

void plotErrorCdf(const RobotErrors& errors, const std::string& pngPath) {
    std::string body, plot;
    int i = 0;
    for (const auto& [robot, e] : errors) {
        if (e.empty()) continue;
        std::vector<double> v;
        for (const auto& te : e) v.push_back(te.error);
        std::sort(v.begin(), v.end());
        std::vector<std::pair<double, double>> xy;
        for (size_t k = 0; k < v.size(); ++k)
            xy.emplace_back(v[k], double(k + 1) / double(v.size()));
        body += dataBlock("c" + std::to_string(i), xy);
        plot += std::string(plot.empty() ? "plot " : ", ") + "$c" + std::to_string(i) +
                " using 1:2 with steps lw 1.5 title '" + robot + "'";
        ++i;
    }
    if (plot.empty()) throw Error("no errors to plot for " + pngPath);
    runGnuplot(body +
                   "set xlabel 'position error (m)'\nset ylabel 'fraction of estimates'\n"
                   "set yrange [0:1]\nset key bottom right\n" +
                   plot + "\n",
               pngPath);
}

void plotLayout(const std::vector<LayoutPoint>& points, const std::string& title,
                const std::string& pngPath) {
    std::string truth = "$truth << EOD\n", paper = "$paper << EOD\n", refined = "$refined << EOD\n",
                ellipses = "$ellipses << EOD\n";
    char line[256];
    for (const auto& p : points) {
        if (std::isfinite(p.trueX)) {
            std::snprintf(line, sizeof line, "%.6f %.6f %s\n", p.trueX, p.trueY, p.robot.c_str());
            truth += line;
        }
        if (std::isfinite(p.paperX)) {
            std::snprintf(line, sizeof line, "%.6f %.6f\n", p.paperX, p.paperY);
            paper += line;
        }
        if (std::isfinite(p.refinedX)) {
            std::snprintf(line, sizeof line, "%.6f %.6f\n", p.refinedX, p.refinedY);
            refined += line;
            // 3-sigma ellipse: eigen-decomposition of the 2x2 covariance.
            const double tr = p.cxx + p.cyy, det = p.cxx * p.cyy - p.cxy * p.cxy;
            const double disc = std::sqrt(std::max(0.0, tr * tr / 4 - det));
            const double l1 = tr / 2 + disc, l2 = std::max(0.0, tr / 2 - disc);
            const double angle = std::atan2(l1 - p.cxx, p.cxy) * 180 / M_PI;
            if (std::isfinite(l1) && l1 > 0) {
                std::snprintf(line, sizeof line, "%.6f %.6f %.6f %.6f %.3f\n", p.refinedX,
                              p.refinedY, 6 * std::sqrt(l1), 6 * std::sqrt(l2),
                              std::abs(p.cxy) < 1e-300 ? (p.cxx >= p.cyy ? 0.0 : 90.0) : angle);
                ellipses += line;
            }
        }
    }
    std::string plot = truth + "EOD\n" + paper + "EOD\n" + refined + "EOD\n" + ellipses + "EOD\n";
    plot +=
        "set title '" + title +
        "'\nset size ratio -1\nset xlabel 'x (m)'\nset ylabel 'y (m)'\n"
        "set key outside right\n"
        "plot $ellipses using 1:2:3:4:5 with ellipses lc rgb '#9999ff' title 'refined, 3 sigma', "
        "$truth using 1:2 with points pt 6 ps 2 lc rgb '#008000' title 'truth', "
        "$truth using 1:2:3 with labels offset 1.2,1.2 notitle, "
        "$paper using 1:2 with points pt 2 ps 1.5 lc rgb '#d00000' title 'paper (eq. 8, sine "
        "rule)', "
        "$refined using 1:2 with points pt 1 ps 1.5 lc rgb '#0000d0' title 'least squares'\n";
    runGnuplot(plot, pngPath, "900,700");
}

void plotAccuracy(const std::vector<AccuracyRow>& rows, const std::string& distanceName,
                  const std::string& pngPath) {
    std::vector<std::pair<double, double>> ap, ar, dp, dr;
    for (const auto& r : rows) {
        if (r.axis == "angle") {
            ap.emplace_back(r.angleSigmaDeg, 100 * r.paper);
            ar.emplace_back(r.angleSigmaDeg, 100 * r.refined);
        } else {
            dp.emplace_back(100 * r.distanceSigma, 100 * r.paper);
            dr.emplace_back(100 * r.distanceSigma, 100 * r.refined);
        }
    }
    if (ap.empty() || dp.empty()) throw Error("no accuracy sweep to plot for " + pngPath);
    std::string body =
        dataBlock("ap", ap) + dataBlock("ar", ar) + dataBlock("dp", dp) + dataBlock("dr", dr);
    body +=
        "set multiplot layout 1,2\nset logscale y\nset ylabel 'median relative distance error "
        "(%)'\nset xlabel 'bearing noise sigma (deg)'\nset logscale x\n"
        "plot $ap using 1:2 with linespoints lw 2 title 'paper', $ar using 1:2 with "
        "linespoints lw 2 title 'least squares'\nunset logscale x\nset xlabel '" +
        distanceName +
        " noise sigma (% of the distance)'\n"
        "plot $dp using 1:2 with linespoints lw 2 title 'paper', $dr using 1:2 with "
        "linespoints lw 2 title 'least squares'\nunset multiplot\n";
    runGnuplot(body, pngPath, "1100,450");
}

}  // namespace mrloc::report
