#pragma once
// A batch of trials (`mrloc batch`, doc/batch.md): an INI, a range of seeds and a grid of
// keys, and the folder that holds them. The folder is the batch's whole state, so that GNU
// parallel, ssh hosts sharing it or a Slurm array can each run any trial of it:
//   batch.ini    the INI as given, copied (the user's file may change while trials run)
//   batch.json   this plan: the seeds, the --set keys, the grid and its points
//   jobs.txt     one job per line, "<point> <first seed> <last seed>": `chunk` seeds of one
//                point run by one process (mrloc's start-up is most of a short trial's
//                time); parallel's input, Slurm's array
//   joblog.txt   GNU parallel's job log (--resume)
//   trials/p<point>/s<seed>.json   each trial's line, written atomically by the trial
//   summary.json, summary.txt      `mrloc batch --collect`; report.html `mrloc report`
#include <mrloc/common/Outcome.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "RunSetup.h"

namespace mrloc::app {

/** One key of the grid and the values it takes. */
struct GridAxis {
    std::string section, key;
    std::vector<std::string> values;
    std::string name() const { return section + "." + key; }
};

struct BatchPlan {
    /** Bounds (doc/batch.md): a batch's trials, a grid's values per key and its points. */
    static constexpr unsigned long kMaxTrials = 1000000;
    static constexpr size_t kMaxValues = 1000;
    static constexpr size_t kMaxPoints = 10000;

    std::string ini;  ///< the INI as the user named it (the trials read batch.ini)
    unsigned long firstSeed = 1, lastSeed = 1;
    /** Seeds per job (--chunk): one process runs them in a row, each its own trial with
     *  its own record. */
    size_t chunk = 10;
    std::vector<KeyOverride> sets;  ///< --set: every trial's
    std::vector<GridAxis> grid;     ///< --grid: the points are their product

    size_t seedCount() const { return size_t(lastSeed - firstSeed + 1); }
    size_t pointCount() const;
    size_t trialCount() const { return seedCount() * pointCount(); }
    size_t chunksPerPoint() const { return (seedCount() + chunk - 1) / chunk; }
    size_t jobCount() const { return chunksPerPoint() * pointCount(); }
    /** The job (jobs.txt's line, from 1: parallel's Seq, Slurm's task + 1) that runs it. */
    size_t jobOf(size_t point, unsigned long seed) const {
        return point * chunksPerPoint() + size_t(seed - firstSeed) / chunk + 1;
    }
    /** Point p's keys: the grid's values, the first axis varying slowest. */
    std::vector<KeyOverride> pointKeys(size_t p) const;
    /** Every trial's keys at point p: --set's, then the grid's. */
    std::vector<KeyOverride> trialKeys(size_t p) const;
    /** "framesync.sonar_sigma=0.02 scenario.odometry_error_scale=2"; "all" without a grid. */
    std::string pointName(size_t p) const;
};

/** "A..B" (or one seed "A"), both in [0, 2^32 - 1], A <= B; throws mrloc::Error. */
std::pair<unsigned long, unsigned long> parseSeeds(const std::string& text);
/** "section.key=v1,v2,...": throws mrloc::Error naming --grid. */
GridAxis parseGridAxis(const std::string& text);

/** A whole number of a batch's file: checked before nlohmann's get<size_t>, which casts 2e19
 *  or -1 with undefined behaviour (found by fuzz_json_readers); throws mrloc::Error. */
size_t wholeNumber(const nlohmann::json& v);

nlohmann::json toJson(const BatchPlan& plan);
/** batch.json read back; throws mrloc::Error naming `where` for anything malformed. */
BatchPlan planFromJson(const nlohmann::json& j, const std::string& where);

namespace batch_dir {
std::string ini(const std::string& dir);
std::string plan(const std::string& dir);
std::string jobs(const std::string& dir);
std::string joblog(const std::string& dir);
std::string record(const std::string& dir, size_t point, unsigned long seed);
std::string summary(const std::string& dir);
std::string summaryText(const std::string& dir);
/** The folder holds a batch (its batch.json). */
bool isBatch(const std::string& dir);
/** Refuses a batch folder that is a link or holds one (or a FIFO, socket or device), or
 *  holds more entries than a batch of kMaxTrials can: every file of it is then written and
 *  read where it seems (doc/batch.md). */
void checkFolder(const std::string& dir);
/** batch.json of `dir`, read and checked. */
BatchPlan readPlan(const std::string& dir);
}  // namespace batch_dir

/** A trial's line (`mrloc trial`): the seed, the keys, the point, the method's figures. */
nlohmann::json trialLine(const std::string& method, unsigned long seed,
                         const std::vector<KeyOverride>& keys, const common::Headline& h);

}  // namespace mrloc::app
