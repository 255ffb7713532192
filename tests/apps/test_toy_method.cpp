// A toy method registered from tests/ alone: its payload steers a robot to a waypoint and
// senses its position, its localizer turns that into estimates, and its report section reads
// the file the localizer wrote. Nothing outside tests/ knows it: the proof that a method
// plugs in through the registry alone (doc/architecture.md, "How to add a method").
#include <gtest/gtest.h>
#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/DataFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/IniSection.h>
#include <mrloc/common/Metrics.h>
#include <mrloc/common/Rawlog.h>
#include <mrloc/common/Trajectory.h>
#include <mrpt/obs/CObservationRange.h>

#include <filesystem>
#include <fstream>

#include "CommandTable.h"
#include "Commands.h"
#include "MrlocCli.h"

using namespace mrloc;
namespace fs = std::filesystem;

namespace {

/** [toy]: where the robot is sent and how often it senses its position. */
struct ToyOptions {
    double goalX = 2, goalY = 1, rate = 2;
    void load(const mrpt::config::CConfigFileBase& ini) {
        common::IniSection s(ini, "toy");
        const auto goal = s.reals("goal", {2, 1}, 2);
        goalX = goal[0], goalY = goal[1];
        rate = s.real("rate", 2, 0.1, 100);
        s.finish();
    }
    void save(mrpt::config::CConfigFileBase& t) const {
        t.write("toy", "goal", std::to_string(goalX) + " " + std::to_string(goalY));
        t.write("toy", "rate", rate);
    }
};

/** The file between the toy localizer and its report section: one number. */
struct ToyFile {
    size_t fixes = 0;
    static std::string path(const std::string& dir) { return dir + "/toy.txt"; }
    void write(const std::string& dir) const {
        common::writeFileAtomically(path(dir), "# toy fixes\n" + std::to_string(fixes) + "\n");
    }
    static ToyFile read(const std::string& dir) {
        const auto lines = common::readDataLines(path(dir));
        if (lines.size() != 1) throw Error(path(dir) + ": expected one line");
        return {size_t(lines[0].number(0))};
    }
};

class ToyPayload : public sim::Payload {
 public:
    explicit ToyPayload(ToyOptions o) : o_(o) {}
    void command(sim::Step& step) override {
        if (step.index == 0) step.fleet.robot(0).setWaypoints({{o_.goalX, o_.goalY}}, false);
    }
    void sense(sim::Step& step) override {
        const long every = std::lround(1.0 / (o_.rate * step.dt));
        if (step.index % every != 0) return;
        const auto& robot = step.fleet.robot(0);
        auto obs = mrpt::obs::CObservationRange::Create();
        obs->sensorLabel = robot.options().name + ".toy";
        obs->timestamp = step.stamp;
        for (double v : {robot.pose().x(), robot.pose().y()}) {
            mrpt::obs::CObservationRange::TMeasurement m;
            m.sensedDistance = float(v);
            obs->sensedData.push_back(m);
        }
        step.emit(obs);
    }
    void onObservation(const mrpt::obs::CObservation::Ptr&) override { ++seenOnBoard; }
    size_t seenOnBoard = 0;

 private:
    ToyOptions o_;
};

class ToyLocalizer : public common::Localizer {
 public:
    void configure(const mrpt::config::CConfigFileBase& ini) override { o_.load(ini); }
    void saveConfig(mrpt::config::CConfigFileBase& t) const override { o_.save(t); }
    void process(const mrpt::obs::CObservation::Ptr& obs) override {
        const auto r = std::dynamic_pointer_cast<mrpt::obs::CObservationRange>(obs);
        if (!r || r->sensedData.size() != 2) return;
        traj_[common::robotOfLabel(r->sensorLabel)].push_back(
            {mrpt::Clock::toDouble(r->timestamp),
             mrpt::poses::CPose3D(r->sensedData[0].sensedDistance, r->sensedData[1].sensedDistance,
                                  0, 0, 0, 0)});
    }
    common::Trajectories estimates() const override { return traj_; }
    common::ObservationUse observationUse() const override {
        size_t n = 0;
        for (const auto& [robot, t] : traj_) n += t.size();
        return {"toy ranges (CObservationRange)", n, n, {}};
    }
    const ToyOptions& options() const { return o_; }
    void writeOutputs(const std::string& dir, const common::Trajectories&) const override {
        ToyFile{traj_.empty() ? 0 : traj_.begin()->second.size()}.write(dir);
    }

 private:
    ToyOptions o_;
    common::Trajectories traj_;
};

void registerToy(method::Registry& registry) {
    method::MethodUnit<ToyLocalizer> m;
    m.name = "toy";
    m.sections = {"toy"};
    m.scenario = [](const mrpt::config::CConfigFileBase& ini, const ToyLocalizer& localizer) {
        method::Scenario s;
        s.config = sim::ScenarioConfig::load(ini);
        s.payload = std::make_unique<ToyPayload>(localizer.options());
        return s;
    };
    m.headline = [](const method::HeadlineOf<ToyLocalizer>& in) {
        common::Headline h;
        h.status = "at the toy goal";
        h.figures = common::trajectoryFigures(in.metrics);
        return h;
    };
    // What the experiment is handed of the resolved run, written down for the tests: the
    // seed, the scenario's (nullptr for a log recorded elsewhere) and the localizer's goal.
    m.experiment = [](const method::ExperimentOf<ToyLocalizer>& in) {
        const std::string path = in.outDir + "/toy.experiment.txt";
        common::writeFileAtomically(
            path, std::to_string(in.seed) + " " +
                      (in.scenario ? std::to_string(in.scenario->scenario.seed) : "none") + " " +
                      std::to_string(in.localizer.options().goalX) + "\n");
        return std::vector<std::string>{path};
    };
    m.report.html = [](const report::RunView& run) {
        return report::heading(2, "Toy section") +
               report::paragraph("toy fixes: " + std::to_string(ToyFile::read(run.dir).fixes));
    };
    m.report.topView = [](const report::RunView&, report::TopViewContent& v) {
        v.landmarks.push_back({2, 1, 0});
        v.landmarksName = "toy goal";
    };
    registry.add(std::move(m));
}

int runMrloc(const method::Registry& registry, std::vector<std::string> args) {
    args.insert(args.begin(), "mrloc");
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    return app::main(registry, int(argv.size()), argv.data());
}

const char* kIni = R"([scenario]
name = toy
method = toy
duration = 12
robots = r1
[world]
size = 3 3 2
[robot.r1]
start = 0.5 0.5 0
speed = 0.4
[toy]
goal = 2 1
rate = 2
)";

}  // namespace

TEST(ToyMethod, PlugsInThroughTheRegistryAlone) {
    method::Registry registry;
    registerToy(registry);
    const std::string dir = testing_cli::tmp("toy");
    fs::create_directories(dir);
    std::ofstream(dir + "/toy.ini") << kIni;
    ASSERT_EQ(runMrloc(registry, {"run", dir + "/toy.ini", "--out", dir + "/run", "-q"}), 0);

    // Localized: the sensed positions are the truth at the same instants.
    const auto m = common::readJsonFile(dir + "/run/metrics.json");
    EXPECT_EQ(m["method"], "toy");
    EXPECT_EQ(m["robots"]["r1"]["estimates"], 25);  // 12 s at 2 Hz, both ends
    EXPECT_LT(m["max_m"].get<double>(), 1e-6);      // float storage of the readings
    // Steered by the payload to the goal (1.58 m away at 0.4 m/s: there by 12 s).
    const auto est = common::loadTum(dir + "/run/estimates.r1.txt");
    ASSERT_FALSE(est.empty());
    EXPECT_NEAR(est.back().pose.x(), 2.0, 0.05);
    EXPECT_NEAR(est.back().pose.y(), 1.0, 0.05);
    // Its report section read its own file; its section is in effective.ini.
    const std::string page = testing_cli::slurp(dir + "/run/report.html");
    EXPECT_NE(page.find("<h2>Toy section</h2>\n<p>toy fixes: 25</p>"), std::string::npos);
    EXPECT_NE(testing_cli::slurp(dir + "/run/effective.ini").find("[toy]"), std::string::npos);
    EXPECT_TRUE(fs::exists(dir + "/run/topview.png"));

    // An unknown section is still refused, and the registry lists the toy's.
    std::ofstream(dir + "/bad.ini") << std::string(kIni) + "[tyo]\nx = 1\n";
    EXPECT_EQ(runMrloc(registry, {"run", dir + "/bad.ini", "--out", dir + "/bad", "-q"}), 1);
    EXPECT_FALSE(fs::exists(dir + "/bad"));
}

TEST(ToyMethod, RegistryRefusesDuplicatesAndSectionsOwnedByOthers) {
    method::Registry registry;
    registerToy(registry);
    EXPECT_THROW(registerToy(registry), Error);
    method::Method thief;
    thief.name = "thief";
    thief.sections = {"toy"};
    thief.localizer = [] { return std::make_unique<ToyLocalizer>(); };
    thief.scenario = [](const mrpt::config::CConfigFileBase&, const common::Localizer&) {
        return method::Scenario{};
    };
    thief.headline = [](const method::HeadlineInput&) { return common::Headline{}; };
    EXPECT_THROW(registry.add(thief), Error);
    thief.sections = {"world"};
    EXPECT_THROW(registry.add(thief), Error);
    EXPECT_THROW(registry.get("nope"), Error);
    // A unit's functions take only the localizer it was registered with.
    const auto& toy = registry.get("toy");
    sim::ScenarioConfig none;
    common::Trajectories truth;
    struct Other : ToyLocalizer {};
    const Other other;
    EXPECT_THROW(toy.experiment({other, &none, truth, testing_cli::tmp("toy_other"), 1}), Error);
    const auto mine = toy.localizer();
    EXPECT_NO_THROW(toy.experiment({*mine, nullptr, truth, testing_cli::tmp("toy_other"), 1}));
}

TEST(ToyMethod, TheExperimentGetsTheResolvedRunNotTheIni) {
    method::Registry registry;
    registerToy(registry);
    const std::string dir = testing_cli::tmp("toy_resolved");
    fs::create_directories(dir);
    std::ofstream(dir + "/toy.ini") << kIni;
    // --seed reaches the experiment and the scenario it is handed, as effective.ini says
    ASSERT_EQ(
        runMrloc(registry, {"run", dir + "/toy.ini", "--seed", "7", "--out", dir + "/run", "-q"}),
        0);
    EXPECT_EQ(testing_cli::slurp(dir + "/run/toy.experiment.txt"), "7 7 2.000000\n");
    EXPECT_NE(testing_cli::slurp(dir + "/run/effective.ini").find("seed = 7"), std::string::npos);
    // a log localized without a simulation: no scenario, the INI's seed
    std::ofstream(dir + "/replay.ini") << "[scenario]\nmethod = toy\nseed = 3\n[toy]\ngoal = 1 1\n";
    ASSERT_EQ(runMrloc(registry, {"localize", dir + "/replay.ini", dir + "/run/toy.rawlog", "--out",
                                  dir + "/replay", "-q"}),
              0);
    EXPECT_EQ(testing_cli::slurp(dir + "/replay/toy.experiment.txt"), "3 none 1.000000\n");
}
