#pragma once
// Helpers of the end-to-end tests: run the mrloc executable, temporary folders, INI edits.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "TestPaths.h"

namespace mrloc::testing_cli {

struct Result {
    int code;            // the exit status, or 128 + the signal that ended the process
    std::string output;  // stdout and stderr
};

inline Result mrlocCmd(const std::string& args) {
    const std::string cmd = std::string(MRLOC_BINARY) + " " + args + " 2>&1";
    FILE* p = popen(cmd.c_str(), "r");
    std::string out;
    std::array<char, 4096> buf;
    while (size_t n = fread(buf.data(), 1, buf.size(), p)) out.append(buf.data(), n);
    const int status = pclose(p);
    // popen's shell reports a child killed by signal s as exit 128 + s.
    return {WIFSIGNALED(status) ? 128 + WTERMSIG(status) : WEXITSTATUS(status), out};
}

/** Starts `mrloc run <ini> --out <out> -q` in the background (its stderr to /dev/null when
 *  `silent`, else to `stderrFile` when given); its pid, for waitStatus. */
inline pid_t startRun(const std::string& ini, const std::string& out, bool silent = false,
                      const std::string& stderrFile = "") {
    const pid_t pid = fork();
    if (pid == 0) {
        if (silent) dup2(::open("/dev/null", O_WRONLY), STDERR_FILENO);
        if (!silent && !stderrFile.empty())
            dup2(::open(stderrFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644), STDERR_FILENO);
        execl(MRLOC_BINARY, "mrloc", "run", ini.c_str(), "--out", out.c_str(), "-q",
              static_cast<char*>(nullptr));
        _exit(127);
    }
    return pid;
}

/** Waits for `pid`: its exit status, or 128 + the signal that ended it. */
inline int waitStatus(pid_t pid) {
    int status = 0;
    waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

/** An empty temporary folder name (removed if it exists). */
inline std::string tmp(const std::string& name) {
    const std::string d = testing::TempDir() + "/apps_" + name;
    std::filesystem::remove_all(d);
    return d;
}

inline std::string slurp(const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

/** config/<name>.ini in the source tree. */
inline std::string config(const std::string& name) {
    return std::string(MRLOC_SOURCE_DIR) + "/config/" + name + ".ini";
}

/** A copy of the INI `base` with the first `from` replaced by `to`, as <TempDir>/<name>.ini. */
inline std::string writeIniFrom(const std::string& base, const std::string& name,
                                const std::string& from, const std::string& to) {
    std::string text = slurp(base);
    const auto pos = text.find(from);
    EXPECT_NE(pos, std::string::npos) << from;
    text.replace(pos, from.size(), to);
    const std::string path = testing::TempDir() + "/" + name + ".ini";
    std::ofstream(path) << text;
    return path;
}

/** config/beacons_paper_room.ini with a short study (4 choice trials a point instead of 100,
 *  2 trials elsewhere instead of 10, a 1 m grid instead of 0.5 m), as `name`.ini: for tests
 *  of what reaches the study or a run's headline, not of the study's figures. */
inline std::string paperRoomWithAShortStudy(const std::string& name) {
    const std::string fewer = writeIniFrom(config("beacons_paper_room"), name + "_choice",
                                           "choice_trials    = 100", "choice_trials = 4");
    const std::string fewerTrials =
        writeIniFrom(fewer, name + "_trials", "trials           = 10", "trials = 2");
    return writeIniFrom(fewerTrials, name, "grid             = 0.5", "grid = 1");
}

}  // namespace mrloc::testing_cli
