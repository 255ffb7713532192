#include <mrloc/common/Progress.h>
#include <mrpt/core/format.h>

#include <algorithm>
#include <cmath>

namespace mrloc::common {

using Clock = std::chrono::steady_clock;

namespace {
/** A terminal is redrawn 10 times a second; a log gets a line every 10 s. */
constexpr auto kTerminalPeriod = std::chrono::milliseconds(100);
constexpr auto kLogPeriod = std::chrono::seconds(10);
}  // namespace

std::string durationText(double s) {
    if (!(s >= 0)) s = 0;
    const long t = std::lround(s);
    if (t < 60) return mrpt::format("%ld s", t);
    if (t < 3600) return mrpt::format("%ld min %02ld s", t / 60, t % 60);
    return mrpt::format("%ld h %02ld min", t / 3600, (t % 3600) / 60);
}

std::string progressText(const std::string& label, double fraction, size_t done, size_t total,
                         double elapsed) {
    std::string text = label + ": ";
    if (fraction >= 0) {
        fraction = std::min(1.0, fraction);
        text += mrpt::format("%d %%", int(fraction * 100));
        if (total > 0) text += mrpt::format(" (%zu of %zu)", done, total);
    } else {
        text += mrpt::format("%zu so far", done);
    }
    text += ", " + durationText(elapsed) + " so far";
    // too early a rate is mostly start-up: no estimate before 2 % of the work
    if (fraction >= 0.02 && fraction < 1)
        text += ", about " + durationText(elapsed * (1 - fraction) / fraction) + " left";
    return text;
}

Progress::Progress(std::string label, size_t total, const Log& log)
    : label_(std::move(label)),
      log_(log),
      total_(total),
      enabled_(log.showsProgress()),
      terminal_(log.redraws()),
      start_(Clock::now()),
      lastDraw_(start_) {}

Progress::~Progress() { finish(); }

void Progress::update(size_t done) {
    show(total_ > 0 ? double(done) / double(total_) : -1.0, done, total_);
}

void Progress::updateFraction(double fraction, size_t items) {
    show(std::clamp(fraction, 0.0, 1.0), items, 0);  // the items are counted, not their total
}

void Progress::show(double fraction, size_t done, size_t total) {
    if (!enabled_) return;
    const auto now = Clock::now();
    // Only work that has already taken a second is shown at all.
    if (now - start_ < std::chrono::seconds(1)) return;
    if (now - lastDraw_ < (terminal_ ? Clock::duration(kTerminalPeriod) : kLogPeriod)) return;
    lastDraw_ = now;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const std::string text = progressText(label_, fraction, done, total, elapsed);
    if (!terminal_) {
        log_.progress(text);
        return;
    }
    shown_ = true;
    if (fraction >= 0) {
        const int width = 30;
        const int fill = int(std::min(1.0, fraction) * width);
        log_.progress("[" + std::string(size_t(fill), '#') +
                      std::string(size_t(width - fill), ' ') + "] " + text);
    } else {
        log_.progress(text);
    }
}

void Progress::finish() {
    if (shown_) log_.clearProgress();
    shown_ = false;
}

}  // namespace mrloc::common
