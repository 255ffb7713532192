#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/DataFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/omnivision/OmniFiles.h>
#include <mrloc/report/Plots.h>
#include <mrpt/core/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace mrloc::omnivision {

using common::formatNumber;

void LayoutFile::write(const std::string& dir) const {
    std::ostringstream out;
    out << "# layout in the paper's frame (a at the origin, b on the x axis)\n"
        << "t " << formatNumber(time) << "\nframe " << a << " " << b << "\n"
        << "# robot x_paper y_paper x_refined y_refined cov_xx cov_xy cov_yy x_true y_true "
           "phi_paper phi_refined cov_phiphi phi_true (m, m^2, rad, rad^2; nan: unknown)\n";
    for (const auto& p : points) {
        out << p.robot;
        for (double v : {p.paperX, p.paperY, p.refinedX, p.refinedY, p.cxx, p.cxy, p.cyy, p.trueX,
                         p.trueY, p.paperPhi, p.refinedPhi, p.cphiphi, p.truePhi})
            out << " " << formatNumber(v);
        out << "\n";
    }
    common::writeFileAtomically(path(dir), out.str());
}

LayoutFile LayoutFile::read(const std::string& dir) {
    LayoutFile f;
    for (const auto& line : common::readDataLines(path(dir))) {
        if (line.fields[0] == "t") {
            line.expectFields(2);
            f.time = line.number(1);
        } else if (line.fields[0] == "frame") {
            line.expectFields(3);
            f.a = line.fields[1], f.b = line.fields[2];
        } else {
            // Runs before headings were estimated have the first 10 fields only.
            if (line.fields.size() != 10) line.expectFields(14);
            LayoutPoint p{line.fields[0], 0, 0, 0, 0, 0, 0, 0, 0, 0};
            double* v[] = {&p.paperX,     &p.paperY,  &p.refinedX, &p.refinedY, &p.cxx,
                           &p.cxy,        &p.cyy,     &p.trueX,    &p.trueY,    &p.paperPhi,
                           &p.refinedPhi, &p.cphiphi, &p.truePhi};
            for (size_t i = 0; i + 1 < line.fields.size(); ++i) *v[i] = line.number(i + 1);
            f.points.push_back(p);
        }
    }
    return f;
}

void AccuracyFile::write(const std::string& dir) const {
    std::ostringstream out;
    out << "# Monte Carlo accuracy sweep on the run's true layout\n"
        << "noise_on " << distanceName << "\n"
        << "# axis angle_sigma_deg distance_sigma_rel median_rel_error_paper "
           "median_rel_error_refined trials failures\n";
    for (const auto& p : points)
        out << p.axis << " " << formatNumber(p.angleSigmaDeg) << " "
            << formatNumber(p.distanceSigma) << " " << formatNumber(p.paper) << " "
            << formatNumber(p.refined) << " " << p.trials << " " << p.failures << "\n";
    common::writeFileAtomically(path(dir), out.str());
}

AccuracyFile AccuracyFile::read(const std::string& dir) {
    AccuracyFile f;
    for (const auto& line : common::readDataLines(path(dir))) {
        if (line.fields[0] == "noise_on") {
            line.expectFields(2);
            f.distanceName = line.fields[1];
            continue;
        }
        line.expectFields(7);
        if (line.fields[0] != "angle" && line.fields[0] != "distance")
            throw Error(line.where + ": the axis must be 'angle' or 'distance'");
        AccuracyPoint p;
        p.axis = line.fields[0];
        p.angleSigmaDeg = line.number(1);
        p.distanceSigma = line.number(2);
        p.paper = line.number(3);
        p.refined = line.number(4);
        p.trials = int(line.number(5));
        p.failures = int(line.number(6));
        f.points.push_back(p);
    }
    return f;
}

void plotLayout(const LayoutFile& layout, const std::string& pngPath) {
    const auto& points = layout.points;
    // Past 30 robots their names overlap: only the frame's pair is named.
    constexpr size_t kMaxNamed = 30;
    const bool nameAll = points.size() <= kMaxNamed;
    const std::string title = "layout at the last snapshot: " + layout.a + " at the origin, " +
                              layout.b + " on the x axis" +
                              (nameAll ? "" : " (only these two named)");
    std::string truth = "$truth << EOD\n", paper = "$paper << EOD\n", refined = "$refined << EOD\n",
                ellipses = "$ellipses << EOD\n", names = "$names << EOD\n";
    char line[256];
    for (const auto& p : points) {
        if (std::isfinite(p.trueX)) {
            std::snprintf(line, sizeof line, "%.6f %.6f %s\n", p.trueX, p.trueY,
                          report::gnuplotDataWord(p.robot).c_str());
            truth += line;
            if (nameAll || p.robot == layout.a || p.robot == layout.b) names += line;
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
    std::string plot = truth + "EOD\n" + names + "EOD\n" + paper + "EOD\n" + refined + "EOD\n" +
                       ellipses + "EOD\n";
    plot +=
        "set title " + report::gnuplotString(title) +
        "\nset size ratio -1\nset xlabel 'x (m)'\nset ylabel 'y (m)'\n"
        "set key outside below center horizontal maxcols 2\n"
        "plot $ellipses using 1:2:3:4:5 with ellipses lc rgb pal_sky title 'refined, 3 sigma', "
        "$truth using 1:2 with points pt 6 ps 2 lc rgb pal_green title 'truth', "
        "$names using 1:2:3 with labels offset 1.2,1.2 notitle, "
        "$paper using 1:2 with points pt 2 ps 1.5 lc rgb pal_vermillion title 'paper (eq. 8, sine "
        "rule)', "
        "$refined using 1:2 with points pt 1 ps 1.5 lc rgb pal_blue title 'least squares'\n";
    // the canvas in the layout's shape (the axes share one scale): a tall layout beside a
    // key took 29 % of a 900 x 700 picture (omnivision_swarm), the key below now
    double x0 = 0, x1 = 0, y0 = 0, y1 = 0;
    for (const auto& p : points)
        for (const auto& [x, y] : {std::pair{p.trueX, p.trueY}, std::pair{p.refinedX, p.refinedY}})
            x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    const double shape = (y1 - y0 + 1) / (x1 - x0 + 1);  // 1 m of margin each way
    const int height = int(std::clamp(760 * shape + 190, 450.0, 1200.0));
    report::runGnuplot(plot, pngPath, mrpt::format("900,%d", height));
}

void plotAccuracy(const AccuracyFile& sweep, const std::string& pngPath) {
    const auto& rows = sweep.points;
    const auto& distanceName = sweep.distanceName;
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
    std::string body = report::dataBlock("ap", ap) + report::dataBlock("ar", ar) +
                       report::dataBlock("dp", dp) + report::dataBlock("dr", dr);
    body +=
        "set multiplot layout 1,2\nset logscale y\nset ylabel 'median relative distance error "
        "(%)'\nset xlabel 'bearing noise sigma (deg)'\nset logscale x\n"
        "plot $ap using 1:2 with linespoints lw 2 title 'paper', $ar using 1:2 with "
        "linespoints lw 2 title 'least squares'\nunset logscale x\nset xlabel '" +
        distanceName +
        " noise sigma (% of the distance)'\n"
        "plot $dp using 1:2 with linespoints lw 2 title 'paper', $dr using 1:2 with "
        "linespoints lw 2 title 'least squares'\nunset multiplot\n";
    report::runGnuplot(body, pngPath, "1100,450");
}

/** The refined position's error weighed by its covariance, per coordinate the gauge leaves
 *  free (B's y is fixed by the frame): e' P^-1 e / dof; nothing for A or without truth. */
std::optional<double> normalisedSquaredError(const LayoutPoint& p) {
    if (!std::isfinite(p.cxx) || !std::isfinite(p.trueX) || !std::isfinite(p.refinedX))
        return std::nullopt;
    const double ex = p.refinedX - p.trueX, ey = p.refinedY - p.trueY;
    if (p.cxx <= 0 && p.cyy <= 0) return std::nullopt;  // A: the frame's origin
    if (p.cyy <= 0) return ex * ex / p.cxx;             // B: on the x axis
    const double det = p.cxx * p.cyy - p.cxy * p.cxy;
    if (!(det > 0)) return std::nullopt;
    return (p.cyy * ex * ex - 2 * p.cxy * ex * ey + p.cxx * ey * ey) / det / 2;
}

}  // namespace mrloc::omnivision
