// common::parallelFor, the one pool (issue 52): every item once, on the process's thread
// count, the caller among the threads, each thread's own state, the first failure rethrown.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/ParallelFor.h>

#include <atomic>
#include <mutex>
#include <set>
#include <thread>
#include <vector>

using namespace mrloc;

namespace {
/** Sets the thread count for one test and puts back the default. */
struct Threads {
    explicit Threads(unsigned n) { common::setThreadCount(n); }
    ~Threads() { common::setThreadCount(0); }
};
}  // namespace

TEST(ParallelFor, EveryItemOnceOnTheSetThreadsTheCallerAmongThem) {
    for (const unsigned threads : {1u, 3u}) {
        Threads set(threads);
        EXPECT_EQ(common::threadCount(), threads);
        std::vector<int> seen(1000, 0);
        std::mutex lock;
        std::set<std::thread::id> ids;
        size_t afterCaller = 0;
        const auto caller = std::this_thread::get_id();
        common::parallelFor(
            seen.size(),
            [&](size_t i) {
                ++seen[i];
                std::lock_guard<std::mutex> l(lock);
                ids.insert(std::this_thread::get_id());
                // a little work, so that the other threads take items too
                std::this_thread::sleep_for(std::chrono::microseconds(20));
            },
            [&] {
                EXPECT_EQ(std::this_thread::get_id(), caller);
                ++afterCaller;
            });
        for (const int n : seen) ASSERT_EQ(n, 1);
        EXPECT_LE(ids.size(), threads);
        EXPECT_TRUE(ids.count(caller));
        EXPECT_GE(afterCaller, 1u);
        EXPECT_LE(afterCaller, seen.size());
    }
    common::setThreadCount(0);
    EXPECT_EQ(common::threadCount(), std::max(1u, std::thread::hardware_concurrency()));
}

TEST(ParallelFor, EachThreadMakesItsOwnWorkerAndTheFirstFailureIsRethrown) {
    Threads set(4);
    std::atomic<int> workers{0};
    std::atomic<int> items{0};
    common::parallelForWorkers(100, [&] {
        ++workers;
        return [&](size_t) { ++items; };
    });
    EXPECT_EQ(items, 100);
    EXPECT_GE(workers, 1);
    EXPECT_LE(workers, 4);
    // fewer items than threads: no idle thread is started
    workers = 0;
    common::parallelForWorkers(2, [&] {
        ++workers;
        return [](size_t) {};
    });
    EXPECT_LE(workers, 2);

    // on one thread the order is fixed: item 5 fails and no item after it runs (with more
    // threads the others stop at their next item, how many that is depends on the scheduler)
    common::setThreadCount(1);
    std::atomic<int> ran{0};
    EXPECT_THROW(common::parallelFor(10000,
                                     [&](size_t i) {
                                         ++ran;
                                         if (i == 5) throw Error("item 5");
                                     }),
                 Error);
    EXPECT_EQ(ran, 6);
    common::setThreadCount(4);
    EXPECT_THROW(common::parallelFor(100, [](size_t i) {
                     if (i == 50) throw Error("item 50");
                 }),
                 Error);
    // a worker that cannot be made fails the call the same way
    EXPECT_THROW(common::parallelForWorkers(
                     3, []() -> std::function<void(size_t)> { throw Error("no camera"); }),
                 Error);
}
