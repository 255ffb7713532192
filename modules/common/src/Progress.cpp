#include <mrloc/common/Progress.h>
#include <unistd.h>

#include <cstdio>

namespace mrloc::common {

using Clock = std::chrono::steady_clock;

Progress::Progress(std::string label, size_t total, bool quiet)
    : label_(std::move(label)),
      total_(total),
      enabled_(!quiet && isatty(fileno(stderr))),
      start_(Clock::now()),
      lastDraw_(start_) {}

Progress::~Progress() { finish(); }

void Progress::update(size_t done) {
    if (!enabled_) return;
    const auto now = Clock::now();
    // Only work that has already taken a second gets a bar; redraw at most 10 times a second.
    if (now - start_ < std::chrono::seconds(1) || now - lastDraw_ < std::chrono::milliseconds(100))
        return;
    lastDraw_ = now;
    shown_ = true;
    if (total_ > 0) {
        const int width = 30;
        const double f = std::min(1.0, double(done) / double(total_));
        const int fill = int(f * width);
        std::fprintf(stderr, "\r%s [%.*s%*s] %3d%%", label_.c_str(), fill,
                     "##############################", width - fill, "", int(f * 100));
    } else {
        std::fprintf(stderr, "\r%s %zu", label_.c_str(), done);
    }
    std::fflush(stderr);
}

void Progress::finish() {
    if (shown_) std::fprintf(stderr, "\r\033[K");
    shown_ = false;
}

}  // namespace mrloc::common
