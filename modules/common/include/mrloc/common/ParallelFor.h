#pragma once
// The one way mrloc spreads work over cores (framesync's and formation's experiments, the
// beacon study, the scan localizer's candidates). The thread count is the process's: every
// core unless `--threads` sets it, and the work estimate (method/Work.h) divides by the same
// number, so what it announces is what runs.
#include <cstddef>
#include <functional>

namespace mrloc::common {

/** The threads parallelFor uses: setThreadCount's, or every core (at least 1). */
unsigned threadCount();
/** 0: every core. Set once, by the app, before any work starts. */
void setThreadCount(unsigned threads);

/** item(0) .. item(n - 1) on min(threadCount(), n) threads, the calling thread one of them.
 *  Items are handed out in order from a shared counter; an item writes only its own result.
 *  `afterCallerItem` runs on the calling thread after each of its items (a progress bar is
 *  drawn by one thread). The first exception stops the other threads at their next item and
 *  is rethrown once all have stopped. */
void parallelFor(size_t n, const std::function<void(size_t)>& item,
                 const std::function<void()>& afterCallerItem = {});

/** As parallelFor, for items that need a state of their thread's own (a camera: an EGL
 *  context is current on one thread): each thread calls makeWorker() once and runs its
 *  items through the function it returns. */
void parallelForWorkers(size_t n, const std::function<std::function<void(size_t)>()>& makeWorker,
                        const std::function<void()>& afterCallerItem = {});

}  // namespace mrloc::common
