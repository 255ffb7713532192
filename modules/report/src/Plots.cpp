#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/report/Plots.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace mrloc::report {

namespace {

/** Runs a gnuplot script whose data blocks are inline; output to pngPath atomically. */
void runGnuplot(const std::string& body, const std::string& pngPath) {
    common::PendingFile out(pngPath);
    const std::string script = out.tempPath() + ".gp";
    {
        std::ofstream s(script);
        s << "set terminal pngcairo size 900,500 font 'Sans,11'\n"
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

}  // namespace mrloc::report
