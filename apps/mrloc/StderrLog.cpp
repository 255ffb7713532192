#include "StderrLog.h"

#include <unistd.h>

#include <cstdio>

namespace mrloc::app {

StderrLog::StderrLog(bool quiet) : quiet_(quiet), terminal_(isatty(fileno(stderr)) != 0) {}

void StderrLog::warning(const std::string& line) const {
    if (quiet_) return;  // --quiet: errors only (a run's warnings stay in metrics.json)
    std::fprintf(stderr, "warning: %s\n", line.c_str());
}

void StderrLog::progress(const std::string& text) const {
    if (quiet_) return;
    if (terminal_)
        std::fprintf(stderr, "\r\033[K%s", text.c_str());
    else
        std::fprintf(stderr, "mrloc: %s\n", text.c_str());
    std::fflush(stderr);
}

void StderrLog::clearProgress() const {
    if (terminal_) std::fprintf(stderr, "\r\033[K");
}

}  // namespace mrloc::app
