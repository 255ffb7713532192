#include <mrloc/polymap/PolymapLocalizer.h>
#include <mrloc/polymap/ScanReport.h>
#include <mrpt/core/format.h>

#include <cmath>
#include <filesystem>

namespace mrloc::polymap {

namespace {

using nlohmann::json;

std::optional<double> numberOf(const json& j, const char* key) {
    if (j.is_object() && j.contains(key) && j[key].is_number()) return j[key].get<double>();
    return std::nullopt;
}

std::string fixed(const json& j, const char* key, const char* format = "%.3f") {
    const auto v = numberOf(j, key);
    return v ? mrpt::format(format, *v) : std::string("none");
}

const json& robotsOf(const json& polymap) {
    static const json empty = json::object();
    return polymap.is_object() && polymap.contains("robots") && polymap["robots"].is_object()
               ? polymap["robots"]
               : empty;
}

}  // namespace

bool isScanRun(const json& metrics) {
    return metrics.contains("polymap") && metrics["polymap"].is_object() &&
           metrics["polymap"].value("localizer", "") == "scan";
}

common::Headline scanHeadline(const json& polymap) {
    common::Headline h;
    std::string notLocalized;
    double hypotheses = 0;
    std::optional<double> distance, time, reference;
    std::string referenceName;
    for (const auto& [robot, r] : robotsOf(polymap).items()) {
        hypotheses += numberOf(r, "hypotheses").value_or(0);
        const double left = numberOf(r, "left").value_or(0);
        if (left != 1)
            notLocalized += mrpt::format(
                "%srobot '%s': %.0f hypotheses %s", notLocalized.empty() ? "" : "; ", robot.c_str(),
                left,
                numberOf(r, "hypotheses").value_or(0) == 0
                    ? "fit the first scan (is this the robot's map? see min_agreement)"
                    : "left at the log's end (it did not drive far enough to tell them apart)");
        if (numberOf(r, "hypotheses").value_or(0) == 0) h.failed = true;  // not this map
        distance = numberOf(r, "unique_after_m");
        time = numberOf(r, "unique_after_s");
        if (r.contains("reference") && r["reference"].is_object()) {
            reference = numberOf(r["reference"], "mean_m");
            referenceName = r["reference"].value("name", "the reference");
        }
    }
    if (robotsOf(polymap).empty()) notLocalized = "no 2-D scan in the log";
    h.reached = notLocalized.empty();
    h.status = h.reached ? "localized: one hypothesis left" : "not localized: " + notLocalized;
    // seed 002 gives no figure for real scans: its experiments are exact views
    h.figures.push_back({"hypotheses from the first scan", hypotheses, "", "", "", false});
    h.figures.push_back({"odometry travel until one was left", distance, "m", "", "", false});
    h.figures.push_back({"log time until one was left", time, "s", "", "", false});
    if (!referenceName.empty())
        h.figures.push_back(
            {"mean distance to " + referenceName + "'s path", reference, "m", "", "", false});
    return h;
}

report::Html scanSection(const report::RunView& run) {
    const json polymap = run.metrics.value("polymap", json::object());
    report::Html out =
        report::heading(2, "Polygon map from real scans: hypotheses and elimination");
    out += report::paragraph(
        "Paper 002's hypothesis generation and elimination, carried to real laser scans "
        "(doc/polymap.md, \"Real scans\"): every free position and heading scored by the "
        "fraction of beams that agree with the map within the tolerance (shorter beams are "
        "clutter and allowed; beams through a wall count against), the best distinct poses "
        "kept; then each later scan, moved by the odometry, prunes them as the robot drives.");
    if (const json grid = polymap.value("grid", json()); grid.is_object()) {
        out += report::heading(3, "The map, traced from MRPT's occupancy grid");
        out += report::paragraph(
            "Map: " + polymap.value("map", std::string("?")) + ". Grid " +
            fixed(grid, "width", "%.0f") + " x " + fixed(grid, "height", "%.0f") + " cells of " +
            fixed(grid, "resolution_m", "%.3f") + " m; occupied cells traced into " +
            fixed(polymap, "map_rings", "%.0f") + " rings of " +
            fixed(polymap, "map_vertices", "%.0f") + " vertices (" +
            fixed(grid, "contour_points", "%.0f") + " contour points simplified within " +
            fixed(grid, "simplify_m", "%.3f") + " m), " + fixed(grid, "specks_dropped", "%.0f") +
            " specks dropped; the scanner may stand on " + fixed(polymap, "free_cells", "%.0f") +
            " free cells.");
        if (std::filesystem::exists(run.dir + "/" + kTracePicture))
            out += report::Figure{kTracePicture,
                                  "the traced polygon's rings should follow the grid's walls"}
                       .html();
    } else {
        out += report::paragraph("Map: " + polymap.value("map", std::string("?")) + ", " +
                                 fixed(polymap, "map_rings", "%.0f") + " ring(s) of " +
                                 fixed(polymap, "map_vertices", "%.0f") + " vertices.");
    }
    for (const auto& [robot, r] : robotsOf(polymap).items()) {
        out += report::heading(3, "Robot " + robot + ": " + fixed(r, "hypotheses", "%.0f") +
                                      " hypotheses from the first scan, " +
                                      fixed(r, "left", "%.0f") + " left");
        out += report::paragraph(
            "Heading " +
            std::string(r.value("heading_known", false) ? "known" : "unknown (searched)") + "; " +
            fixed(r, "positions_searched", "%.0f") + " positions and " +
            fixed(r, "poses_scored", "%.0f") + " poses scored, " + fixed(r, "refined", "%.0f") +
            " refined; beam tolerance " + fixed(r, "tolerance_m") +
            " m. The best pose not kept agrees with " + fixed(r, "runner_up_agreement", "%.3f") +
            " of the beams.");
        if (std::filesystem::exists(run.dir + "/" + scanPicture(robot)))
            out +=
                report::Figure{scanPicture(robot),
                               "robot " + robot +
                                   "'s hypotheses and paths: the estimate should end on the truth"}
                    .html();
        report::Table table({"#", "x (m)", "y (m)", "heading (deg)", "beams agreeing",
                             "beams through walls", "beams short of a wall (clutter)"});
        if (r.contains("points") && r["points"].is_array())
            for (size_t i = 0; i < r["points"].size(); ++i) {
                const auto& p = r["points"][i];
                if (!p.is_array() || p.size() < 6) continue;
                table.row({std::to_string(i + 1), mrpt::format("%.3f", p[0].get<double>()),
                           mrpt::format("%.3f", p[1].get<double>()),
                           mrpt::format("%.1f", p[2].get<double>() * 180 / M_PI),
                           mrpt::format("%.3f", p[3].get<double>()),
                           mrpt::format("%.3f", p[4].get<double>()),
                           mrpt::format("%.3f", p[5].get<double>())});
            }
        out += table.html();
        const bool localized = r.value("localized", false);
        out += report::paragraph(
            std::string("Passive elimination over ") + fixed(r, "scans", "%.0f") + " scans and " +
            fixed(r, "travelled_m", "%.2f") + " m of odometry: " +
            (localized
                 ? "one hypothesis left after " + fixed(r, "unique_after_m", "%.2f") + " m and " +
                       fixed(r, "unique_after_s", "%.2f") +
                       " s (0: from the first scan); it was #" + fixed(r, "survivor_rank", "%.0f") +
                       " of the first scan's, and is tracked at every scan after."
                 : fixed(r, "left", "%.0f") + " hypotheses left: not localized."));
        if (r.contains("reference") && r["reference"].is_object()) {
            const json& c = r["reference"];
            const std::string name = c.value("name", std::string("the reference"));
            out += report::heading(3, "Beside " + name);
            out += report::paragraph(
                "The log has no ground truth: " + name + "'s path (" +
                c.value("file", std::string("?")) +
                ") is the reference, not the truth; its own errors are in these figures.");
            if (c.contains("notes") && c["notes"].is_array()) {
                std::vector<report::Html> notes;
                for (const auto& n : c["notes"])
                    if (n.is_string()) notes.push_back(report::Html(n.get<std::string>()));
                if (!notes.empty()) out += report::bulletList(notes);
            }
            report::Table t({"estimates compared", "from (s after the first scan)", "mean (m)",
                             "median (m)", "max (m)", "last (m)", "heading mean (deg)",
                             "heading max (deg)"});
            t.row({fixed(c, "compared", "%.0f"), fixed(c, "from_s", "%.2f"), fixed(c, "mean_m"),
                   fixed(c, "median_m"), fixed(c, "max_m"), fixed(c, "last_m"),
                   fixed(c, "heading_mean_deg", "%.2f"), fixed(c, "heading_max_deg", "%.2f")});
            out += t.html();
        }
    }
    return out;
}

}  // namespace mrloc::polymap
