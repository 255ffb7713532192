#include <mrloc/common/Error.h>
#include <mrloc/method/Work.h>
#include <mrpt/core/format.h>

#include <algorithm>

namespace mrloc::method {

namespace {

double itemWall(const WorkItem& w, unsigned cores) {
    return w.parallel ? w.seconds / double(std::max(1u, cores)) : w.seconds;
}

}  // namespace

double wallSeconds(const std::vector<WorkItem>& items, unsigned cores) {
    double total = 0;
    for (const auto& w : items) total += itemWall(w, cores);
    return total;
}

std::string durationText(double seconds) {
    if (seconds < 60) return mrpt::format("%.0f s", seconds);
    if (seconds < 3600) return mrpt::format("%.1f min", seconds / 60);
    return mrpt::format("%.1f h", seconds / 3600);
}

std::optional<std::string> checkWork(const std::vector<WorkItem>& items, unsigned cores) {
    if (items.empty()) return std::nullopt;
    const double wall = wallSeconds(items, cores);
    double bytes = 0;
    for (const auto& w : items) bytes += w.bytes;
    const auto heaviest = [&](auto weight) {
        return *std::max_element(items.begin(), items.end(), [&](const auto& a, const auto& b) {
            return weight(a) < weight(b);
        });
    };
    for (const auto& w : items)
        if (w.memory > WorkBudget::kMemory)
            throw Error(mrpt::format(
                "%s: %s would hold about %.1f GB at once, beyond the %.0f "
                "GB one part may (doc/errors.md, \"Work\")",
                w.keys.c_str(), w.what.c_str(), w.memory / 1e9, WorkBudget::kMemory / 1e9));
    if (bytes > WorkBudget::kBytes) {
        const auto& w = heaviest([](const WorkItem& x) { return x.bytes; });
        throw Error(
            mrpt::format("%s: %s would write about %.1f GB, beyond the %.0f GB a run may "
                         "write (doc/errors.md, \"Work\")",
                         w.keys.c_str(), w.what.c_str(), w.bytes / 1e9, WorkBudget::kBytes / 1e9));
    }
    if (wall > WorkBudget::kSeconds) {
        const auto& w = heaviest([&](const WorkItem& x) { return itemWall(x, cores); });
        throw Error(
            mrpt::format("%s: %s would take about %s on %u cores, beyond the %s a run "
                         "may take (doc/errors.md, \"Work\")",
                         w.keys.c_str(), w.what.c_str(), durationText(itemWall(w, cores)).c_str(),
                         cores, durationText(WorkBudget::kSeconds).c_str()));
    }
    if (wall <= WorkBudget::kAnnounceSeconds) return std::nullopt;
    const auto& w = heaviest([&](const WorkItem& x) { return itemWall(x, cores); });
    return mrpt::format("this run: about %s on %u cores, most of it %s (%s)",
                        durationText(wall).c_str(), cores, w.what.c_str(), w.keys.c_str());
}

}  // namespace mrloc::method
