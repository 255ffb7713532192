// `mrloc trial`: one seed, one call, one JSON line (doc/batch.md). A method's own trial
// (Method::trial: one run of its experiment, as the experiment computes it) when it has
// one; otherwise the scenario simulated, localized and its experiment run in a scratch
// folder: the headline `mrloc run --seed` gives. No report; the same INI, keys and seed give
// the same line.
#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/FolderLock.h>
#include <mrloc/common/Metrics.h>
#include <mrloc/common/ParallelFor.h>
#include <mrloc/common/RunTransaction.h>
#include <mrloc/common/Seeds.h>
#include <stdlib.h>
#include <unistd.h>

#include <filesystem>
#include <iostream>

#include "BatchPlan.h"
#include "CommandLine.h"
#include "Commands.h"
#include "RunSetup.h"
#include "RunSteps.h"

namespace mrloc::app {

namespace fs = std::filesystem;

namespace {

/** A scratch folder for one trial's rawlog, removed with everything in it when done. */
class ScratchFolder {
 public:
    /** Under `<batch>/scratch` (a batch folder: nothing is written outside it; a trial
     *  killed by a signal may leave its folder there), else the system's temporary folder;
     *  unique to this process. */
    explicit ScratchFolder(const std::string& batch) {
        if (!batch.empty()) common::checkNoLinkInPath(batch, "scratch");
        const fs::path base =
            batch.empty() ? fs::temp_directory_path() : fs::path(batch) / "scratch";
        common::makeDirectories(base.string());
        std::string pattern = (base / "mrloc-trial-XXXXXX").string();
        if (!mkdtemp(pattern.data()))
            throw Error(common::pathInWords(base.string()) + ": cannot make a scratch folder");
        path_ = pattern;
        slot_ = common::holdTemporaryOnSignal(path_);  // Ctrl-C leaves no scratch folder
    }
    ~ScratchFolder() {
        std::error_code ignored;
        fs::remove_all(path_, ignored);
        common::releaseTemporaryOnSignal(slot_);
    }
    ScratchFolder(const ScratchFolder&) = delete;
    ScratchFolder& operator=(const ScratchFolder&) = delete;
    const std::string& path() const { return path_; }

 private:
    std::string path_;
    int slot_ = -1;
};

/** The trial itself: its line. `scratchParent`: where a simulated rawlog may go. */
nlohmann::json runTrial(const method::Registry& registry, const std::string& ini,
                        unsigned long seed, const std::vector<KeyOverride>& keys,
                        const std::string& scratchParent) {
    Setup s = loadSetup(registry, ini, long(seed), true, "", keys);
    if (!s.simulation)
        throw Error(ini +
                    ": [scenario] describes no simulation; a trial simulates the scenario "
                    "with its seed");
    method::checkWork(workOf(s, true, !s.method->trial), common::threadCount());
    common::Headline h;
    if (s.method->trial) {
        h = s.method->trial({*s.localizer, s.simulation->config});
    } else {
        ScratchFolder scratch(scratchParent);
        h = simulateAndLocalize(registry, s, scratch.path());
    }
    return trialLine(s.method->name, seed, keys, h);
}

/** A batch's job: the seeds `first` .. `last` of grid point `p`, each its own trial and
 *  record (a record already there without an error is printed, never run again). Returns
 *  the exit code: 1 when a trial failed (its record says why), else 0. */
int runBatchJob(const method::Registry& registry, const std::string& dir, long p,
                unsigned long first, long last) {
    const BatchPlan plan = batch_dir::readPlan(dir);
    if (p < 0 || size_t(p) >= plan.pointCount())
        throw Error("--point " + std::to_string(p) + ": the batch has " +
                    std::to_string(plan.pointCount()) + " points (0 .. " +
                    std::to_string(plan.pointCount() - 1) + ")");
    if (first < plan.firstSeed || last < long(first) || (unsigned long)last > plan.lastSeed)
        throw Error("--seed " + std::to_string(first) + " .. " + std::to_string(last) +
                    ": outside the batch's seeds " + std::to_string(plan.firstSeed) + ".." +
                    std::to_string(plan.lastSeed));
    const auto keys = plan.trialKeys(size_t(p));
    size_t failed = 0;
    for (unsigned long seedNow = first; seedNow <= (unsigned long)last; ++seedNow) {
        const std::string record = batch_dir::record(dir, size_t(p), seedNow);
        // the record's folders are the batch's own, not links out of it (a trial of Slurm
        // or a command list runs without `mrloc batch`'s check of the whole folder)
        common::checkNoLinkInPath(dir, fs::path(record).lexically_relative(dir).string());
        if (fs::is_regular_file(fs::symlink_status(record))) {
            // done already (a job cut short, a job log lost, Slurm's requeue): never run twice
            const auto held = common::readJsonFile(record);
            if (!held.contains("error")) {
                std::cout << held.dump() << std::endl;
                continue;
            }
        }
        common::makeDirectories(fs::path(record).parent_path().string());
        nlohmann::json line;
        try {
            line = runTrial(registry, batch_dir::ini(dir), seedNow, keys, dir);
        } catch (const Error& e) {
            // a trial that failed on its input says why in its record (`--collect` lists
            // it); the job goes on with its next seed
            line = {{"seed", seedNow}, {"error", oneLine(e.what())}};
            std::cerr << "mrloc trial: seed " << seedNow << ": error: " << oneLine(e.what())
                      << "\n";
            ++failed;
        }
        line["point"] = p;
        common::writeFileAtomically(record, line.dump() + "\n");
        std::cout << line.dump() << std::endl;
    }
    return failed ? 1 : 0;
}

}  // namespace

int trial(const method::Registry& registry, int argc, char** argv) {
    CommandLine cmd(
        "mrloc trial: one seed of the INI's experiment (the method's own trial, else the "
        "scenario simulated, localized and its experiment run), printed as one JSON line: the "
        "seed, the --set keys and the headline figures. No report, no pictures; the same INI, "
        "keys and seed give the same line. `mrloc batch` runs many (doc/batch.md).");
    TCLAP::UnlabeledValueArg<std::string> ini("ini", "scenario INI file", false, "", "INI", cmd);
    TCLAP::ValueArg<long> seed("s", "seed", "the trial's seed (overrides [scenario] seed)", true, 0,
                               "N", cmd);
    TCLAP::MultiArg<std::string> set("", "set",
                                     "section.key=value: a key of the INI, read through its "
                                     "checks as if the INI held it (repeatable)",
                                     false, "KEY=VALUE", cmd);
    TCLAP::ValueArg<std::string> batchDir(
        "", "batch",
        "a batch folder (mrloc batch): the INI and keys are its, and the line is also written "
        "to <folder>/trials/p<point>/s<seed>.json",
        false, "", "DIR", cmd);
    TCLAP::ValueArg<long> point("", "point", "the batch's grid point (with --batch)", false, 0, "P",
                                cmd);
    TCLAP::ValueArg<long> lastSeed("", "last-seed",
                                   "with --batch: the seeds --seed .. this, each its own trial and "
                                   "record, in one process (a batch's job)",
                                   false, 0, "M", cmd);
    TCLAP::ValueArg<long> threads("", "threads", ThreadsArg::kHelp, false, 0, "N", cmd);
    if (const auto code = parseArgs(cmd, argc, argv)) return *code;
    ThreadsArg::apply(threads);
    if (seed.getValue() < 0 || seed.getValue() > long(common::kMaxSeed))
        throw Error("--seed must be in [0, " + std::to_string(common::kMaxSeed) + "]");
    const auto n = (unsigned long)seed.getValue();
    if (batchDir.isSet()) {
        if (ini.isSet() || set.isSet())
            throw Error("--batch: the INI and keys are the batch's (batch.ini, batch.json)");
        return runBatchJob(registry, batchDir.getValue(), point.getValue(), n,
                           lastSeed.isSet() ? lastSeed.getValue() : long(n));
    }
    if (!ini.isSet()) throw Error("missing <INI> (mrloc trial <ini> --seed N)");
    if (point.isSet() || lastSeed.isSet())
        throw Error("--point and --last-seed belong to a batch's jobs (with --batch)");
    std::vector<KeyOverride> keys;
    for (const auto& k : set.getValue()) keys.push_back(parseOverride(k, "--set"));
    std::cout << runTrial(registry, ini.getValue(), n, keys, "").dump() << std::endl;
    return 0;
}

}  // namespace mrloc::app
