#include <mrloc/common/Error.h>
#include <mrloc/common/IniSection.h>
#include <mrloc/polymap/PolygonView.h>
#include <mrloc/polymap/PolymapFiles.h>
#include <mrloc/polymap/PolymapLocalizer.h>
#include <mrloc/polymap/PolymapMethod.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>

#include <cmath>

namespace mrloc::polymap {

void PolymapPayload::sense(sim::Step& step) {
    if (scanEvery_ < 0)
        scanEvery_ = plan_.scanner.rate > 0
                         ? std::max<long>(1, std::lround(1.0 / (plan_.scanner.rate * step.dt)))
                         : 0;
    if (step.index != 0 && (scanEvery_ == 0 || step.index % scanEvery_ != 0)) return;
    for (size_t i = 0; i < step.fleet.size(); ++i) {
        const auto& robot = step.fleet.robot(i);
        auto scan = sim::scanFloorPlan(plan_.polygon, robot.pose(), plan_.scanner, step.rng);
        scan->sensorLabel = robot.options().name + ".scan";
        scan->timestamp = step.stamp;
        step.emit(scan);
    }
}

namespace {

/** One robot at the [polymap] start in the localizer's map (built once, when the localizer
 *  was configured); [robot.<name>] is optional and may not set a start. */
method::Scenario loadScenario(const mrpt::config::CConfigFileBase& ini,
                              const common::Localizer& localizer) {
    const auto& polymap = dynamic_cast<const PolymapLocalizer&>(localizer);
    const PolymapOptions& o = polymap.options();
    const GeneratedMap& map = polymap.generatedMap();
    const auto start = o.startIn(map);
    method::Scenario s;
    s.config = sim::ScenarioConfig::loadWithoutRobots(ini);
    auto& names = s.config.scenario.robots;
    if (names.empty()) names = {"r1"};
    if (names.size() != 1)
        throw Error(common::configOrigin(ini) +
                    ": [scenario] robots: a floor-plan scenario has one robot");
    sim::RobotOptions r;
    r.name = names[0];
    r.startInSection = false;  // [polymap] start has it
    if (ini.sectionExists("robot." + r.name)) r.loadFromConfigFile(ini, "robot." + r.name);
    r.start = mrpt::poses::CPose2D(start.x, start.y, mrpt::DEG2RAD(o.heading));
    if (!map.polygon.contains(start))
        throw Error(
            common::configOrigin(ini) +
            mrpt::format(": the start (%g %g) is outside the floor plan", start.x, start.y));
    s.config.robots.push_back(r);
    s.payload = std::make_unique<PolymapPayload>(
        sim::FloorPlan{map.polygon, {o.scanRays, o.scanRangeSigma, o.scanMaxRange, o.scanRate}});
    return s;
}

std::string polymapSection(const report::RunView& run) {
    std::string out =
        "<h2>Polygon map: hypotheses</h2>\n<p>The map P; the sensed visibility polygon V at "
        "the true start; V placed at each hypothesis; the hypotheses (seed 002, hypothesis "
        "generation). Colours are in the picture's legend.</p>\n";
    const auto P = common::Polygon::load(mapFilePath(run.dir));
    for (const auto& [robot, r] : run.metrics["robots"].items()) {
        const auto file = HypothesesFile::read(run.dir, robot);
        PolygonViewContent view;
        view.map = P;
        view.sensed = file.sensed;
        for (const auto& h : file.hypotheses) view.hypotheses.push_back(h.point);
        if (const auto gt = run.truth.find(robot); gt != run.truth.end())
            if (const auto p = common::interpolate(gt->second, file.time))
                view.truth = common::TPoint2D{p->x(), p->y()};
        const std::string png = "polymap." + robot + ".png";
        renderPolygonView(view, run.dir + "/" + png);
        out += "<h3>Robot " + report::html(robot) + ": " + std::to_string(file.hypotheses.size()) +
               " hypotheses</h3>\n<img src='" + png + "' alt='map, V and hypotheses'>\n";
        out +=
            "<table><tr><th>#</th><th>x (m)</th><th>y (m)</th><th>translation (m)</th>"
            "<th>mismatch (m)</th><th>distance to truth (m)</th></tr>\n";
        for (size_t i = 0; i < file.hypotheses.size(); ++i) {
            const auto& h = file.hypotheses[i];
            const std::string d =
                view.truth ? mrpt::format("%.3f", (h.point - *view.truth).norm()) : "none";
            out += mrpt::format(
                "<tr><td>%zu</td><td>%.3f</td><td>%.3f</td><td>%.3f %.3f</td>"
                "<td>%.4f</td><td>%s</td></tr>\n",
                i + 1, h.point.x, h.point.y, h.translation.x, h.translation.y, h.mismatch,
                d.c_str());
        }
        out += "</table>\n";
    }
    return out;
}

}  // namespace

void registerMethod(method::Registry& registry) {
    method::Method m;
    m.name = "polymap";
    m.sections = {"polymap"};
    m.localizer = [] { return std::make_unique<PolymapLocalizer>(); };
    m.scenario = loadScenario;
    m.report.html = polymapSection;  // its own picture: no world top view
    registry.add(std::move(m));
}

}  // namespace mrloc::polymap
