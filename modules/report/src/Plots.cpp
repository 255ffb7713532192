#include <fcntl.h>
#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/report/Palette.h>
#include <mrloc/report/PictureLayout.h>
#include <mrloc/report/Plots.h>
#include <mrpt/core/format.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace mrloc::report {

namespace {

/** Runs `gnuplot script` with stderr into `errPath`; its exit status. Spawned directly, not
 *  through std::system: no shell to quote paths for, and std::system would ignore SIGINT
 *  while gnuplot runs, so Ctrl-C would not end mrloc. */
int spawnGnuplot(const std::string& folder, const std::string& script, const std::string& errPath) {
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    // gnuplot works in the picture's folder and is given only file names of mrloc's making:
    // no path of the user's (a --out of '|cmd') reaches its `set output`
    posix_spawn_file_actions_addchdir_np(&actions, folder.c_str());
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, errPath.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    std::string program = "gnuplot";
    char* argv[] = {program.data(), const_cast<char*>(script.c_str()), nullptr};
    pid_t pid = 0;
    const int rc = posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv, environ);
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) return -1;
    int status = 0;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR) return -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

std::string gnuplotString(const std::string& text) {
    std::string q = "'";
    for (const char c : text) {
        const auto u = static_cast<unsigned char>(c);
        if (c == '\'')
            q += "''";  // the only escape a single-quoted gnuplot string has
        else if (u < 0x20 || u == 0x7f)
            q += '?';  // a newline would end the command and start another
        else
            q += c;
    }
    return q + "'";
}

std::string gnuplotDataWord(const std::string& text) {
    std::string w;
    for (const char c : text) {
        const auto u = static_cast<unsigned char>(c);
        const bool plain = u > 0x20 && u < 0x7f && c != '"' && c != '\'' && c != '#' && c != '\\' &&
                           c != '$' && c != '`';
        w += plain ? c : '_';
    }
    return w.empty() ? "_" : w;
}

bool isCompletePng(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    char head[8] = {};
    in.read(head, 8);
    if (in.gcount() != 8 || std::memcmp(head, "\x89PNG\r\n\x1a\n", 8) != 0) return false;
    in.seekg(-12, std::ios::end);
    char tail[12] = {};
    in.read(tail, 12);
    return in.gcount() == 12 && std::memcmp(tail + 4, "IEND", 4) == 0;
}

void runGnuplot(const std::string& body, const std::string& pngPath, const std::string& size) {
    namespace fs = std::filesystem;
    common::PendingFile out(pngPath);
    // Temporaries that are never committed: removed when done.
    common::PendingFile script(out.tempPath() + ".gp", ""), err(out.tempPath() + ".err", "");
    const fs::path folder = fs::absolute(fs::path(pngPath)).parent_path();
    {
        std::ofstream s(script.tempPath());
        s << "set terminal pngcairo size " << size << " font 'Sans,11' noenhanced\n"
          << "set output " << gnuplotString(fs::path(out.tempPath()).filename().string()) << "\n"
          << "set grid\nset key outside right top\n"
          << palette::gnuplotDefinitions()
          << body
          // the plot area gnuplot chose, in pixels from the bottom left, for the layout
          << "\nprint sprintf('mrloc-layout %.1f %.1f %.1f %.1f', GPVAL_TERM_XMIN, "
             "GPVAL_TERM_XMAX, GPVAL_TERM_YMIN, GPVAL_TERM_YMAX)\n";
        s.close();
        if (!s) throw Error("cannot write " + script.tempPath() + " (is the disk full?)");
    }
    const int rc = spawnGnuplot(folder.string(), fs::absolute(script.tempPath()).string(),
                                fs::absolute(err.tempPath()).string());
    std::string message;
    {
        std::ifstream e(err.tempPath());
        std::getline(e, message, '\0');
    }
    if (rc != 0)
        throw Error("gnuplot failed for " + pngPath +
                    " (is gnuplot-nox installed?): " + oneLine(message));
    // gnuplot may exit 0 with a truncated picture (a full disk): check it is whole
    if (!isCompletePng(out.tempPath()))
        throw Error("cannot write " + pngPath +
                    ": gnuplot's picture is incomplete (is the disk "
                    "full?)");
    PictureLayout layout;
    std::sscanf(size.c_str(), "%d,%d", &layout.width, &layout.height);
    const size_t at = message.rfind("mrloc-layout ");
    double x0 = 0, x1 = 0, y0 = 0, y1 = 0;
    if (at == std::string::npos ||
        std::sscanf(message.c_str() + at, "mrloc-layout %lf %lf %lf %lf", &x0, &x1, &y0, &y1) != 4)
        throw Error("gnuplot did not say where it drew " + pngPath + ": " + oneLine(message));
    layout.data = {int(std::lround(x0)), layout.height - int(std::lround(y1)), int(std::lround(x1)),
                   layout.height - int(std::lround(y0))};
    layout.key = gnuplotKeyPlacement(body);
    int rows = 1, columns = 1;
    if (const size_t m = body.find("set multiplot layout ");
        m != std::string::npos &&
        std::sscanf(body.c_str() + m, "set multiplot layout %d,%d", &rows, &columns) == 2)
        layout.panels = std::max(1, rows * columns);
    writeLayout(out.tempPath(), layout);
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

bool oneErrorPerRobot(const RobotErrors& errors) {
    return std::all_of(errors.begin(), errors.end(),
                       [](const auto& robotErrors) { return robotErrors.second.size() <= 1; });
}

void plotErrorPerRobot(const RobotErrors& errors, const std::string& pngPath) {
    std::string rows = "$e << EOD\n";
    int i = 0;
    for (const auto& [robot, e] : errors)
        for (const auto& te : e)
            rows += mrpt::format("%d %.6f %s\n", i++, te.error, gnuplotDataWord(robot).c_str());
    if (i == 0) throw Error("no errors to plot for " + pngPath);
    // at most about 25 names under the axis: a swarm's hundred would overlap
    const int every = (i + 24) / 25;
    runGnuplot(rows +
                   "EOD\nset xlabel 'robot'\nset ylabel 'position error (m)'\n"
                   "set xrange [-0.5:" +
                   std::to_string(i) +
                   "-0.5]\nset yrange [0:*]\n"
                   "set xtics rotate by -45\nset key outside right top\n"
                   "plot $e using 1:2:xtic(int(column(1)) % " +
                   std::to_string(every) +
                   " == 0 ? stringcolumn(3) : '') with points pt 7 ps 1.5 lc 1 "
                   "title 'error of the estimate'\n",
               pngPath);
}

}  // namespace mrloc::report
