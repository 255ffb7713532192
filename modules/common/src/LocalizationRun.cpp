#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/LocalizationRun.h>
#include <mrloc/common/Metrics.h>
#include <mrloc/common/Progress.h>
#include <mrloc/common/Rawlog.h>
#include <mrloc/common/RunDirectory.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <chrono>
#include <filesystem>

namespace mrloc::common {

nlohmann::json runLocalization(Localizer& localizer, const LocalizationRunOptions& o,
                               const mrpt::config::CConfigFileBase& effective) {
    RawlogReader reader(o.rawlogPath);
    const auto start = std::chrono::steady_clock::now();
    Progress progress("localizing", 0, o.quiet);
    size_t n = 0;
    for (mrpt::obs::CObservation::Ptr obs; reader.next(obs);) {
        localizer.process(obs);
        progress.update(++n);
    }
    progress.finish();
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const auto estimates = localizer.estimates();
    if (estimates.empty())
        throw Error("rawlog " + o.rawlogPath + ": the method '" + o.methodName +
                    "' produced no estimate (" + std::to_string(n) +
                    " observations read; does the rawlog carry what the method needs?)");

    makeDirectories(o.outDir);
    nlohmann::json metrics;
    metrics["method"] = o.methodName;
    metrics["rawlog"] = o.rawlogPath;
    metrics["observations"] = n;
    metrics["rawlog_format"] = reader.format() == RawlogFormat::ActionsSensoryFrames
                                   ? "actions+sensory-frames"
                                   : "observations-only";
    std::map<std::string, Trajectory> worldTruth;
    for (const auto& [robot, traj] : estimates)
        if (const std::string gtPath = groundTruthPath(o.rawlogPath, robot);
            std::filesystem::exists(gtPath))
            worldTruth[robot] = loadTum(gtPath);
    const auto truth = localizer.truthInEstimateFrame(worldTruth);
    std::vector<double> allErrors;
    for (const auto& [robot, traj] : estimates) {
        saveTum(run_dir::estimates(o.outDir, robot), traj);
        nlohmann::json r;
        r["estimates"] = traj.size();
        if (const auto it = truth.find(robot); it != truth.end()) {
            const auto& gt = it->second;
            saveTum(run_dir::groundTruth(o.outDir, robot), gt);
            std::vector<double> e;
            for (const auto& te : positionErrors(traj, gt)) e.push_back(te.error);
            allErrors.insert(allErrors.end(), e.begin(), e.end());
            r.update(statsToJson(computeStats(e)));
            r.update(localizer.groundTruthMetrics(robot, gt));
        }
        metrics["robots"][robot] = r;
    }
    metrics["ground_truth"] = !allErrors.empty();
    metrics.update(statsToJson(computeStats(allErrors)));
    metrics["wall_s"] = wall;
    metrics[o.methodName] = localizer.methodMetrics();

    mrpt::config::CConfigFileMemory eff;
    std::vector<std::string> sections;
    effective.getAllSections(sections);
    for (const auto& s : sections) {
        std::vector<std::string> keys;
        effective.getAllKeys(s, keys);
        for (const auto& k : keys) eff.write(s, k, effective.read_string(s, k, ""));
    }
    localizer.saveConfig(eff);
    localizer.writeOutputs(o.outDir);
    writeFileAtomically(run_dir::effectiveIni(o.outDir), eff.getContent());
    saveJson(run_dir::metrics(o.outDir), metrics);
    return metrics;
}

}  // namespace mrloc::common
