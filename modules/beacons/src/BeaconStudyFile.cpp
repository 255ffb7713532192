#include <mrloc/beacons/BeaconStudyFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/JsonFile.h>
#include <mrloc/common/Progress.h>
#include <mrloc/common/Seeds.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>

#include <fstream>
#include <nlohmann/json.hpp>

namespace mrloc::beacons {

using nlohmann::json;

namespace {

json pointsJson(const std::vector<PointStats>& points) {
    json out = json::array();
    for (const auto& p : points)
        out.push_back({{"x", p.at.x},
                       {"y", p.at.y},
                       {"trials", p.trials},
                       {"fixes", p.fixes},
                       {"mean_error_m", p.meanError},
                       {"max_error_m", p.maxError}});
    return out;
}

std::vector<PointStats> pointsOf(const json& j) {
    std::vector<PointStats> out;
    for (const auto& p : j) {
        PointStats s;
        s.at = {p.at("x").get<double>(), p.at("y").get<double>()};
        s.trials = p.at("trials").get<int>();
        s.fixes = p.at("fixes").get<int>();
        s.meanError = p.at("mean_error_m").get<double>();
        s.maxError = p.at("max_error_m").get<double>();
        out.push_back(s);
    }
    return out;
}

}  // namespace

void BeaconStudyFile::write(const std::string& dir) const {
    json j;
    j["method"] = method;
    j["room_m"] = {roomX, roomY};
    j["trials"] = trials;
    j["choice_trials"] = choiceTrials;
    j["reception_min"] = criteria.reception;
    j["error_bound_m"] = criteria.errorBound;
    j["beacons_per_fix"] = beaconsPerFix;
    j["choices"] = json::array();
    for (const auto& c : choices)
        j["choices"].push_back({{"aiming", c.aiming},
                                {"method", c.method},
                                {"paper", c.paper},
                                {"configured", c.configured},
                                {"points", pointsJson(c.points)}});
    j["grids"] = json::array();
    for (const auto& g : grids)
        j["grids"].push_back({{"part", g.part},
                              {"value", g.value},
                              {"variant", g.variant},
                              {"beacons", g.beacons},
                              {"room_m", {g.roomX, g.roomY}},
                              {"min_reception", g.minReception},
                              {"mean_error_m", g.meanError},
                              {"max_error_m", g.maxError},
                              {"points", g.points},
                              {"points_covered", g.pointsCovered},
                              {"covers", g.covers}});
    j["counts"] = json::array();
    for (const auto& c : counts)
        j["counts"].push_back({{"size_m", c.size},
                               {"aiming", c.aiming},
                               {"fewest", c.fewest},
                               {"min_reception", c.minReception},
                               {"mean_error_m", c.meanError},
                               {"max_error_m", c.maxError}});
    j["agents"] = json::array();
    for (const auto& a : agents)
        j["agents"].push_back({{"agents", a.agents},
                               {"channel", channelName(a.channel)},
                               {"aiming", a.aiming},
                               {"seconds", a.seconds},
                               {"layouts", a.layouts},
                               {"mean_rate_hz", a.meanRate},
                               {"min_rate_hz", a.minRate},
                               {"mean_agents_per_epoch", a.meanAgentsPerEpoch},
                               {"mean_error_m", a.meanError},
                               {"max_error_m", a.maxError},
                               {"fixes", a.fixes},
                               {"shots", a.shots},
                               {"interfered", a.interfered},
                               {"over_bound", a.overBound}});
    std::ofstream f(path(dir));
    f << j.dump(1) << "\n";
    if (!f) throw Error("cannot write " + path(dir));
}

BeaconStudyFile BeaconStudyFile::read(const std::string& dir) {
    const std::string p = path(dir);
    // the study of seed 001's largest grids writes under 1 MB: 16 MiB bounds what a hostile
    // file can make the report hold
    const json j = common::readJsonFile(p, {16u << 20, 16});
    BeaconStudyFile out;
    try {
        out.method = j.at("method").get<std::string>();
        out.roomX = j.at("room_m").at(0).get<double>();
        out.roomY = j.at("room_m").at(1).get<double>();
        out.trials = j.at("trials").get<int>();
        out.choiceTrials = j.at("choice_trials").get<int>();
        out.criteria.reception = j.at("reception_min").get<double>();
        out.criteria.errorBound = j.at("error_bound_m").get<double>();
        out.beaconsPerFix = j.at("beacons_per_fix").get<std::string>();
        for (const auto& c : j.at("choices"))
            out.choices.push_back({c.at("aiming").get<std::string>(),
                                   c.at("method").get<std::string>(), c.at("paper").get<bool>(),
                                   c.at("configured").get<bool>(), pointsOf(c.at("points"))});
        for (const auto& g : j.at("grids")) {
            StudyGridRow r;
            r.part = g.at("part").get<std::string>();
            r.value = g.at("value").get<double>();
            r.variant = g.at("variant").get<std::string>();
            r.beacons = g.at("beacons").get<int>();
            r.roomX = g.at("room_m").at(0).get<double>();
            r.roomY = g.at("room_m").at(1).get<double>();
            r.minReception = g.at("min_reception").get<double>();
            r.meanError = g.at("mean_error_m").get<double>();
            r.maxError = g.at("max_error_m").get<double>();
            r.points = g.at("points").get<int>();
            r.pointsCovered = g.at("points_covered").get<int>();
            r.covers = g.at("covers").get<bool>();
            out.grids.push_back(r);
        }
        for (const auto& c : j.at("counts"))
            out.counts.push_back({c.at("size_m").get<double>(), c.at("aiming").get<std::string>(),
                                  c.at("fewest").get<int>(), c.at("min_reception").get<double>(),
                                  c.at("mean_error_m").get<double>(),
                                  c.at("max_error_m").get<double>()});
        for (const auto& a : j.at("agents")) {
            AgentsResult r;
            r.agents = a.at("agents").get<int>();
            const auto channel = a.at("channel").get<std::string>();
            r.channel = Channel::Shared;
            for (const auto c : {Channel::Simultaneous, Channel::Unchecked})
                if (channel == channelName(c)) r.channel = c;
            if (channel != channelName(r.channel))
                throw Error(p + ": unknown channel '" + channel + "'");
            r.aiming = a.at("aiming").get<std::string>();
            r.seconds = a.at("seconds").get<double>();
            r.layouts = a.at("layouts").get<int>();
            r.meanRate = a.at("mean_rate_hz").get<double>();
            r.minRate = a.at("min_rate_hz").get<double>();
            r.meanAgentsPerEpoch = a.at("mean_agents_per_epoch").get<double>();
            r.meanError = a.at("mean_error_m").get<double>();
            r.maxError = a.at("max_error_m").get<double>();
            r.fixes = a.at("fixes").get<size_t>();
            r.shots = a.at("shots").get<size_t>();
            r.interfered = a.at("interfered").get<size_t>();
            r.overBound = a.at("over_bound").get<size_t>();
            out.agents.push_back(r);
        }
    } catch (const json::exception& e) {
        throw Error(p + ": not a beacon study file (" + oneLine(e.what()) + ")");
    }
    return out;
}

namespace {

const char* kActive = "active (at the receiver)";
const char* kDown = "fixed (each straight down)";
const char* kSectionAim = "fixed (at the section's aim point)";

/** A seed from what an evaluation is (common::seedOf over its description): the same room,
 *  beacons, aiming and method draw the same trials in every part of the study. */
using common::seedOf;

StudyGridRow gridRow(const std::string& part, double value, const std::string& variant,
                     const StudyRoom& room, const CoverageResult& r, const CoverageCriteria& c) {
    StudyGridRow g;
    g.part = part;
    g.value = value;
    g.variant = variant;
    g.beacons = int(room.beacons.size());
    g.roomX = room.sizeX;
    g.roomY = room.sizeY;
    g.minReception = r.minReception();
    g.meanError = r.meanError();
    g.maxError = r.maxError();
    g.points = int(r.points.size());
    g.pointsCovered = int(r.pointsCovered(c));
    g.covers = r.covers(c);
    return g;
}

std::string spreadName(double x, double y, int n, bool active) {
    return mrpt::format("spread %.6g x %.6g, %d beacons, %s", x, y, n, active ? "active" : "down");
}

/** One study: its hardware and method from the run's options, the run's room in its three
 *  aimings, and the five parts, each adding its rows to the file. */
class Study {
 public:
    Study(const StudySetup& setup, const BeaconOptions& run, const sim::ScenarioConfig& scenario,
          uint64_t seed, const common::Log& log)
        : o_(setup.options),
          run_(run),
          scenario_(scenario),
          seed_(seed),
          configured_{run.threeD, run.tracker.fix.residual, run.delayCompensation,
                      run.system.shotsPerBeacon, run.tracker.jitterWeights},
          roomX_(scenario.world.sizeX),
          roomY_(scenario.world.sizeY),
          progress_("beacon study", stepCount(setup.options), log) {
        hw_.ultrasonic = setup.ultrasonic;
        hw_.sensors = setup.sensors;
        hw_.receiverHeight = o_.receiverHeight;
        hw_.shotInterval = run.system.shotInterval;
        hw_.beaconsPerFix = o_.beaconsPerFix;
        hw_.tracker = run.tracker;
        runActive_.sizeX = roomX_;
        runActive_.sizeY = roomY_;
        runActive_.beacons = run.map;
        runActive_.active = true;
        runDown_ = runActive_;
        runDown_.active = false;
        runDown_.fixedAim = straightDown(run.map);
        runSection_ = runDown_;
        for (const auto& section : run.system.sections.sections())
            for (const int id : section.beacons)
                runSection_.fixedAim[id] = {section.aim.x, section.aim.y, section.aim.z};
        out_.method = configured_.describe();
        out_.roomX = roomX_;
        out_.roomY = roomY_;
        out_.trials = o_.trials;
        out_.choiceTrials = o_.choiceTrials;
        out_.criteria = o_.criteria;
        out_.beaconsPerFix = mrpt::format("the %d the link predicts loudest", o_.beaconsPerFix);
    }

    BeaconStudyFile run() {
        if (o_.choiceTrials > 0 && !run_.map.empty()) methodChoices();
        coverage();
        beaconCounts();
        sweeps();
        agents();
        return std::move(out_);
    }

 private:
    static size_t stepCount(const StudyOptions& o) {
        return (o.choiceTrials > 0 ? 2 : 0) + 2 * o.coverageSizes.size() + 2 * o.countSizes.size() +
               o.beamAngles.size() + o.beaconCounts.size() + o.speeds.size() + o.agents.size();
    }
    void step() { progress_.update(++done_); }

    /** Each evaluation's seed comes from what it evaluates: adding a part leaves the others'
     *  draws alone, and one configuration gives one verdict wherever it appears. */
    uint64_t seedFor(const std::string& what, const StudyHardware& h, const StudyMethod& m) const {
        return seedOf(seed_,
                      what + "|" + m.describe() +
                          mrpt::format("|beam %.6g|speed %.6g", h.ultrasonic.beamAngle, h.speed));
    }

    StudyRoom spread(double x, double y, int n, bool active) const {
        return spreadRoom(x, y, o_.ceiling, n, active);
    }

    /** 1. the method-choice table at the run's own test points (its robots' starts) */
    void methodChoices() {
        std::vector<mrpt::math::TPoint2D> points;
        for (const auto& r : scenario_.robots) points.push_back({r.start.x(), r.start.y()});
        StudyHardware all = hw_;  // the section fires all its beacons, as in the run
        all.beaconsPerFix = int(run_.map.size());
        const auto shots = std::max(2, configured_.shotsPerBeacon);
        std::vector<std::pair<std::string, StudyMethod>> variants{
            {"paper 001's fix (eq. 4-10)", StudyMethod::paper()},
            {"alone: the height known (2-D)", {false, Residual::SquaredRange, false, 1, false}},
            {"alone: range residual", {true, Residual::Range, false, 1, false}},
            {"alone: delay compensation", {true, Residual::SquaredRange, true, 1, false}},
            {mrpt::format("alone: %d shots per beacon", shots),
             {true, Residual::SquaredRange, false, shots, false}},
            {"height + range residual", {false, Residual::Range, false, 1, false}},
            {"+ delay compensation", {false, Residual::Range, true, 1, false}},
            {"+ jitter weights", {false, Residual::Range, true, 1, true}}};
        for (int n = 2; n <= shots; ++n)
            variants.push_back({mrpt::format("+ %d shots per beacon", n),
                                {false, Residual::Range, true, n, true}});
        if (std::none_of(variants.begin(), variants.end(),
                         [&](const auto& v) { return v.second == configured_; }))
            variants.push_back({"this run's method", configured_});
        // every choice on the same draws (common random numbers): the differences between
        // rows are the choices', not the draws'
        const auto add = [&](const StudyRoom& room, const std::string& aiming,
                             const std::string& name, const StudyMethod& m) {
            const auto r = evaluateCoverage(room, all, m, points, o_.choiceTrials,
                                            seedOf(seed_, "choices|" + aiming), o_.criteria);
            out_.choices.push_back(
                {aiming, name, m == StudyMethod::paper(), m == configured_, r.points});
        };
        for (const auto& [name, m] : variants) add(runActive_, kActive, name, m);
        step();
        for (const auto* room : {&runSection_, &runDown_})
            for (const auto& m : {StudyMethod::paper(), configured_})
                add(*room, room == &runSection_ ? kSectionAim : kDown,
                    m == StudyMethod::paper() ? "paper 001's fix (eq. 4-10)" : "this run's method",
                    m);
        step();
    }

    /** 2. one set of coverage_beacons over square rooms of growing size */
    void coverage() {
        for (const double size : o_.coverageSizes)
            for (const bool active : {false, true}) {
                const auto room = spread(size, size, o_.coverageBeacons, active);
                const auto r = evaluateCoverage(
                    room, hw_, configured_, testGrid(size, size, o_.grid, o_.wallMargin), o_.trials,
                    seedFor(spreadName(size, size, o_.coverageBeacons, active), hw_, configured_),
                    o_.criteria);
                out_.grids.push_back(
                    gridRow("coverage", size, active ? kActive : kDown, room, r, o_.criteria));
                step();
            }
    }

    /** 3. the fewest beacons that cover each room */
    void beaconCounts() {
        for (const double size : o_.countSizes)
            for (const bool active : {false, true}) {
                StudyCountRow c;
                c.size = size;
                c.aiming = active ? kActive : kDown;
                const auto points = testGrid(size, size, o_.grid, o_.wallMargin);
                for (int n = 3; n <= o_.countMax; ++n) {
                    const auto r = evaluateCoverage(
                        spread(size, size, n, active), hw_, configured_, points, o_.trials,
                        seedFor(spreadName(size, size, n, active), hw_, configured_), o_.criteria,
                        true);
                    if (r.covers(o_.criteria)) {
                        c.fewest = n;
                        c.minReception = r.minReception();
                        c.meanError = r.meanError();
                        c.maxError = r.maxError();
                        break;
                    }
                }
                out_.counts.push_back(c);
                step();
            }
    }

    /** 4. sweeps in the run's room: beam angle, beacon count, speed */
    void sweeps() {
        const auto runPoints = testGrid(roomX_, roomY_, o_.grid, o_.wallMargin);
        const auto sweep = [&](const std::string& part, double value, const std::string& variant,
                               const StudyRoom& room, const std::string& roomName,
                               const StudyHardware& h, const StudyMethod& m) {
            const auto r = evaluateCoverage(room, h, m, runPoints, o_.trials,
                                            seedFor(roomName, h, m), o_.criteria);
            out_.grids.push_back(gridRow(part, value, variant, room, r, o_.criteria));
        };
        for (const double angle : o_.beamAngles) {
            StudyHardware h = hw_;
            h.ultrasonic.beamAngle = mrpt::DEG2RAD(angle);  // another transducer, its datasheet
            sweep("beam", angle, kDown, runDown_, "run down", h, configured_);
            sweep("beam", angle, kActive, runActive_, "run active", h, configured_);
            step();
        }
        for (const double n : o_.beaconCounts) {
            for (const bool active : {false, true})
                sweep("beacons", n, active ? kActive : kDown,
                      spread(roomX_, roomY_, int(n), active),
                      spreadName(roomX_, roomY_, int(n), active), hw_, configured_);
            step();
        }
        StudyMethod oneShot = configured_;
        oneShot.shotsPerBeacon = 1;
        for (const double v : o_.speeds) {
            StudyHardware h = hw_;
            h.speed = v;
            sweep("speed", v, kDown, runDown_, "run down", h, configured_);
            sweep("speed", v, kActive, runActive_, "run active", h, configured_);
            if (configured_.shotsPerBeacon > 1)
                sweep("speed", v, std::string(kActive) + ", 1 shot per beacon", runActive_,
                      "run active", h, oneShot);
            step();
        }
    }

    /** 5. agents served on one channel or at once */
    void agents() {
        for (const double a : o_.agents) {
            for (const bool active : {false, true}) {
                const auto room = spread(o_.agentsSize, o_.agentsSize, o_.agentsBeacons, active);
                for (const auto channel :
                     {Channel::Shared, Channel::Simultaneous, Channel::Unchecked}) {
                    if (!active && channel == Channel::Unchecked) continue;
                    auto r = serveAgents(
                        room, hw_, configured_, int(a), channel, o_.agentsTime, o_.agentsLayouts,
                        seedOf(seed_, mrpt::format("agents %g", a)), o_.criteria.errorBound);
                    r.aiming = active ? kActive : kDown;
                    out_.agents.push_back(r);
                }
            }
            step();
        }
    }

    const StudyOptions& o_;
    const BeaconOptions& run_;
    const sim::ScenarioConfig& scenario_;
    uint64_t seed_;
    StudyHardware hw_;
    StudyMethod configured_;
    double roomX_, roomY_;
    StudyRoom runActive_, runDown_, runSection_;  ///< the run's room in its three aimings
    common::Progress progress_;
    size_t done_ = 0;
    BeaconStudyFile out_;
};

}  // namespace

BeaconStudyFile runStudy(const StudySetup& setup, const BeaconOptions& run,
                         const sim::ScenarioConfig& scenario, uint64_t seed,
                         const common::Log& log) {
    return Study(setup, run, scenario, seed, log).run();
}

}  // namespace mrloc::beacons
