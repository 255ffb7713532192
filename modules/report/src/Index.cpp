#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/Metrics.h>
#include <mrloc/common/Names.h>
#include <mrloc/common/Outcome.h>
#include <mrloc/common/RunDirectory.h>
#include <mrloc/report/Html.h>
#include <mrloc/report/Index.h>
#include <mrloc/report/Report.h>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <vector>

namespace mrloc::report {

namespace fs = std::filesystem;

namespace {

/** A run folder's name that is a name (no control character, no hidden file). */
bool isRunName(const std::string& name) {
    try {
        common::checkName(name, "run");
        return true;
    } catch (const Error&) {
        return false;
    }
}

/** The INI a run folder was made from, by its file name (provenance.json), or "". */
std::string iniOf(const std::string& runFolder) {
    const std::string path = common::run_dir::provenance(runFolder);
    if (!fs::is_regular_file(path)) return "";
    const auto p = common::readProvenanceFile(path);  // "ini", when there, a string
    if (!p.contains("ini")) return "";
    return fs::path(p["ini"].get<std::string>()).filename().string();
}

}  // namespace

std::string makeIndex(const std::string& folder, std::string title) {
    std::vector<std::string> runs;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(folder, ec)) {
        // only folders of this folder: a link could point anywhere
        if (!entry.is_directory() || entry.is_symlink()) continue;
        const std::string name = entry.path().filename().string();
        if (isRunName(name) && fs::is_regular_file(common::run_dir::metrics(entry.path().string())))
            runs.push_back(name);
    }
    if (ec) throw Error(folder + ": cannot list: " + ec.message());
    if (runs.empty()) throw Error(folder + ": no run folder in it (none holds a metrics.json)");
    std::sort(runs.begin(), runs.end());

    std::vector<std::string> methods;  // in the order of the runs, each once
    Table t({"run (INI)", "outcome", "figure", "this run", "the paper",
             "how this run differs from the paper's"});
    for (const auto& run : runs) {
        const std::string metricsPath = common::run_dir::metrics(folder + "/" + run);
        const auto metrics = common::readMetricsFile(metricsPath);
        const std::string method = metrics.value("method", "?");
        if (std::find(methods.begin(), methods.end(), method) == methods.end())
            methods.push_back(method);
        const bool hasReport = fs::is_regular_file(common::run_dir::report(folder + "/" + run));
        Html runCell = hasReport ? link(run + "/report.html", run) : Html(run + " (no report)");
        if (method != run) runCell += Html(" (" + method + ")");
        if (const std::string ini = iniOf(folder + "/" + run); !ini.empty())
            runCell += Html(" ") + code(ini);
        if (!metrics.contains("headline")) {
            t.row({runCell, "no headline", "", "", "", ""});
            continue;
        }
        const auto h = common::headlineFromJson(metrics["headline"], metricsPath);
        const Html outcome = h.reached ? Html(h.status) : bold("not reached: " + h.status);
        bool first = true;
        for (const auto& f : h.figures) {
            std::vector<Html> cells{first ? runCell : Html(), first ? outcome : Html()};
            for (auto& c : figureCells(f)) cells.push_back(std::move(c));
            t.row(std::move(cells));
            first = false;
        }
        if (first) t.row({runCell, outcome, "", "", "", ""});
    }
    if (title.empty()) {  // what the folder holds: "mrloc: 3 runs in out (beacons, polymap)"
        std::string names;
        for (const auto& m : methods) names += (names.empty() ? "" : ", ") + m;
        const std::string where =
            fs::path(folder).lexically_normal().filename().empty()
                ? fs::path(folder).lexically_normal().parent_path().filename().string()
                : fs::path(folder).lexically_normal().filename().string();
        title = "mrloc: " + std::to_string(runs.size()) + (runs.size() == 1 ? " run" : " runs") +
                " in " + common::printable(where) + " (" + names + ")";
    }
    const Html body =
        heading(1, title) +
        paragraph(
            "Each run's headline: the method's own figures in bold, the paper's beside "
            "them, baselines (odometry alone, dead reckoning) marked and never averaged "
            "in. The run's name links its report.") +
        t.html();
    const std::string path = folder + "/index.html";
    common::writeFileAtomically(path, htmlPage(title, body));
    return path;
}

}  // namespace mrloc::report
