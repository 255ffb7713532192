#pragma once
// A run's work as a whole, estimated from its resolved configuration before anything runs
// (doc/errors.md, "Work"). Each key is bounded where it is read; their product is bounded
// here: the simulation and each method name the parts their keys multiply, with the cost of
// each on one core of the reference machine (a 2-core CI runner; the calibration is in
// doc/errors.md). A run beyond the budget is refused with one line naming the keys that
// drive it; a long one is announced with its estimate before it starts.
#include <optional>
#include <string>
#include <vector>

namespace mrloc::method {

struct WorkItem {
    std::string what;    ///< "the experiment's marches"
    std::string keys;    ///< "[formation] runs x experiment_speeds x experiment_routes"
    double seconds = 0;  ///< estimated on one core
    double bytes = 0;    ///< written to the run folder
    double memory = 0;   ///< bytes held at once
    /** The part runs on every core (an experiment's pool of seeds): its wall time is
     *  seconds / cores. */
    bool parallel = false;
    /** Done by `simulate` (sensing), not by `localize` (an experiment, the localizer). */
    bool simulation = false;
};

struct WorkBudget {
    static constexpr double kSeconds = 6 * 3600;  ///< wall time refused beyond
    static constexpr double kBytes = 4e9;         ///< output refused beyond
    /** One item's memory refused beyond: a rawlog entry must stay under the 2 GiB the
     *  rawlog check lets one entry take (RawlogProbe), with room for a copy. */
    static constexpr double kMemory = 1e9;
    static constexpr double kAnnounceSeconds = 30;  ///< wall time announced beyond
};

/** The estimated wall time on `cores` cores. */
double wallSeconds(const std::vector<WorkItem>& items, unsigned cores);

/** Throws mrloc::Error naming the part that weighs most (its keys and estimate) when the
 *  work is beyond WorkBudget; returns the line to announce when it is long, else nothing. */
std::optional<std::string> checkWork(const std::vector<WorkItem>& items, unsigned cores);

/** "3 s", "4.2 min", "1.5 h". */
std::string durationText(double seconds);

}  // namespace mrloc::method
