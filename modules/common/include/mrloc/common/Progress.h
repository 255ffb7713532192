#pragma once
// A progress bar on stderr for work that takes over a second. Silent when stderr is not a
// terminal (CI, pipes) or when quiet.
#include <chrono>
#include <string>

namespace mrloc::common {

class Progress {
 public:
    /** total = 0: unknown total, a counter is shown instead of a bar. */
    Progress(std::string label, size_t total, bool quiet);
    ~Progress();
    void update(size_t done);
    void finish();

 private:
    std::string label_;
    size_t total_;
    bool enabled_;
    bool shown_ = false;
    std::chrono::steady_clock::time_point start_, lastDraw_;
};

}  // namespace mrloc::common
