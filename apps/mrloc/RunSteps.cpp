#include "RunSteps.h"

#include <mrloc/common/LocalizationRun.h>
#include <mrloc/common/Metrics.h>
#include <mrloc/common/ParallelFor.h>
#include <mrloc/common/RunDirectory.h>
#include <mrloc/report/Report.h>
#include <mrloc/sim/Simulator.h>

#include <filesystem>
#include <iostream>

#include "Advice.h"
#include "MrptTruth.h"
#include "StderrLog.h"

namespace mrloc::app {

namespace fs = std::filesystem;

void checkWorkOf(const Setup& s, bool simulating, bool localizing, bool quiet) {
    const auto line = method::checkWork(workOf(s, simulating, localizing), common::threadCount());
    if (line && !quiet) std::cerr << "mrloc: " << *line << "\n";
}

std::string simulateStep(Setup& s, const std::string& dir, const common::Log& log) {
    const auto files =
        sim::simulateToFiles(s.simulation->config, dir, log, s.simulation->payload.get());
    // The payload's on-board parts (formation's camera among them) go now, while their EGL
    // context lives: MRPT's CFBORender terminates the EGL display every renderer shares
    // when it is destroyed, so a camera that outlived the experiment's cameras or the
    // report's renderer threw from its destructor at exit (exit 134, issue 31).
    s.simulation->payload.reset();
    return files.rawlog;
}

common::Headline localizeStep(const method::Registry& registry, Setup& s, const std::string& rawlog,
                              const std::string& dir, const common::Log& log,
                              const std::string& rawlogShownAs) {
    const std::string& name = s.method->name;
    common::LocalizationRunOptions options{name, rawlog, dir, &log, s.scenario.groundTruth};
    if (options.groundTruth.path.empty() && !s.simulation) {
        // a log recorded elsewhere: its truth where MRPT's apps look for it
        std::string note;
        if (const auto found = mrptTruthOf(*s.ini, s.iniPath, rawlog, note)) {
            options.groundTruth = found->source;
            options.groundTruthFrom = found->from;
        }
        if (!note.empty() && log.showsProgress()) std::cerr << "note: " << note << "\n";
    }
    options.rawlogShownAs = rawlogShownAs;
    options.fitHint = [&registry, &name](const std::map<std::string, size_t>& classes) {
        return fitHintOf(registry, name, classes);
    };
    auto result = common::runLocalization(*s.localizer, options);
    const sim::ScenarioConfig* scenario = s.simulation ? &s.simulation->config : nullptr;
    if (s.method->experiment)
        s.method->experiment({*s.localizer, scenario, result.truth, dir, s.scenario.seed, log});
    auto headline = s.method->headline({*s.localizer, scenario, result.metrics, dir});
    if (result.metrics["robots"].empty() && headline.reached) {
        // whatever the method's figures, a run without a single estimate reached nothing
        headline.reached = false;
        headline.status = "no estimate";
    }
    result.metrics["headline"] = common::toJson(headline);
    common::saveJson(common::run_dir::metrics(dir), result.metrics);
    return headline;
}

std::string reportStep(const method::Registry& registry, const std::string& dir) {
    const std::string metricsPath = common::run_dir::metrics(dir);
    if (!fs::exists(metricsPath))
        throw Error(dir + ": not a run directory (no metrics.json; run `mrloc localize` first)");
    const auto metrics = common::readMetricsFile(metricsPath);
    const std::string name = metrics.value("method", "");
    if (!registry.has(name))
        throw Error(metricsPath + ": method '" + name + "' is not one this mrloc knows");
    try {
        return report::makeReport(dir, registry.get(name).report);
    } catch (const nlohmann::json::exception& e) {
        // a method's section reads its own part of metrics.json: a file from elsewhere
        // holding another type there is named, not an "unexpected error"
        throw Error(metricsPath + ": a value of another type than mrloc writes there (" +
                    oneLine(e.what()) + ")");
    }
}

common::Headline simulateAndLocalize(const method::Registry& registry, Setup& s,
                                     const std::string& dir) {
    const StderrLog log(true);  // a trial's warnings, and no progress
    const std::string rawlog = simulateStep(s, dir, log);
    return localizeStep(registry, s, rawlog, dir, log, rawlog);
}

}  // namespace mrloc::app
