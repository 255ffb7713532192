#pragma once
// Progress of work that can take more than a second, told to a Log (the app's: stderr). On a
// terminal a bar with the time so far and the time left, redrawn in place; otherwise (CI, a
// pipe, a log file) one line every 10 s, so that long work is never silent. Nothing when the
// log shows no progress (-q).
#include <mrloc/common/Log.h>

#include <chrono>
#include <string>

namespace mrloc::common {

class Progress {
 public:
    /** total = 0: unknown total, a counter is shown instead of a bar and no time left. */
    Progress(std::string label, size_t total, const Log& log);
    ~Progress();
    void update(size_t done);
    /** Progress as a fraction in [0, 1] where the work is not counted in items (the bytes
     *  of a rawlog read so far); shown as a percentage with the time left. */
    void updateFraction(double fraction, size_t items);
    void finish();

 private:
    /** `total` 0: the items done are shown without a total. */
    void show(double fraction, size_t done, size_t total);

    std::string label_;
    const Log& log_;
    const size_t total_;
    bool enabled_;
    bool terminal_;
    bool shown_ = false;
    std::chrono::steady_clock::time_point start_, lastDraw_;
};

/** The words of one progress report: "localizing: 45 % (1234 of 2742), 12 s so far, about
 *  15 s left". `fraction` < 0: unknown, only the count and the time so far. The time left is
 *  extrapolated from the rate so far, and given only once 2 % of the work is done. */
std::string progressText(const std::string& label, double fraction, size_t done, size_t total,
                         double elapsedSeconds);

/** A duration as people read it: "8 s", "2 min 05 s", "1 h 02 min". */
std::string durationText(double seconds);

}  // namespace mrloc::common
