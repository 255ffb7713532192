#include <mrloc/common/ParallelFor.h>

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace mrloc::common {

namespace {
std::atomic<unsigned> configuredThreads{0};
}

unsigned threadCount() {
    const unsigned set = configuredThreads.load();
    return set ? set : std::max(1u, std::thread::hardware_concurrency());
}

void setThreadCount(unsigned threads) { configuredThreads = threads; }

void parallelForWorkers(size_t n, const std::function<std::function<void(size_t)>()>& makeWorker,
                        const std::function<void()>& afterCallerItem) {
    std::atomic<size_t> next{0};
    std::exception_ptr failure;
    std::mutex failureLock;
    const auto work = [&](bool caller) {
        try {
            const auto item = makeWorker();
            for (size_t i; (i = next++) < n;) {
                item(i);
                if (caller && afterCallerItem) afterCallerItem();
            }
        } catch (...) {
            std::lock_guard<std::mutex> lock(failureLock);
            if (!failure) failure = std::current_exception();
            next = n;  // the others stop at their next item
        }
    };
    const size_t threads = std::min<size_t>(threadCount(), std::max<size_t>(n, 1));
    std::vector<std::thread> pool;
    for (size_t t = 1; t < threads; ++t) pool.emplace_back(work, false);
    work(true);
    for (auto& t : pool) t.join();
    if (failure) std::rethrow_exception(failure);
}

void parallelFor(size_t n, const std::function<void(size_t)>& item,
                 const std::function<void()>& afterCallerItem) {
    parallelForWorkers(
        n, [&] { return item; }, afterCallerItem);
}

}  // namespace mrloc::common
