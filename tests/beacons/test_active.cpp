// Seed 001's active system in closed loop: the RF beacon's scheduling, the channel timing,
// section handover, and the paper's fixed-versus-active experiment.
#include <gtest/gtest.h>
#include <mrloc/beacons/BeaconLocalizer.h>
#include <mrloc/beacons/BeaconPayload.h>
#include <mrloc/beacons/BeaconsMethod.h>
#include <mrloc/beacons/RfBeacon.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/Metrics.h>
#include <mrloc/sim/Simulator.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <array>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>

#include "TestPaths.h"

using namespace mrloc;

namespace {

/** A config/ INI with some keys changed: {section, key, value}. */
std::unique_ptr<mrpt::config::CConfigFileMemory> shippedIni(
    const std::string& name, const std::vector<std::array<std::string, 3>>& changes = {}) {
    std::ifstream in(std::string(MRLOC_SOURCE_DIR) + "/config/" + name);
    std::stringstream text;
    text << in.rdbuf();
    auto ini = std::make_unique<mrpt::config::CConfigFileMemory>(text.str());
    for (const auto& [section, key, value] : changes) ini->write(section, key, value);
    return ini;
}

struct ClosedLoopRun {
    sim::SimulationResult result;
    beacons::ShotLog shots;
    nlohmann::json metrics;  // the on-board localizer's
    std::map<std::string, common::ErrorStats> errors;
};

ClosedLoopRun runClosedLoop(const mrpt::config::CConfigFileBase& ini, const std::string& tag) {
    auto scenario = beacons::loadScenario(ini);
    const auto& payload = dynamic_cast<const beacons::BeaconPayload&>(*scenario.payload);
    common::RawlogWriter out(testing::TempDir() + "/active_" + tag + ".rawlog");
    sim::Simulator simulator(scenario.config);
    ClosedLoopRun run;
    run.result = simulator.run(out, scenario.payload.get());
    run.shots = payload.shots();
    const auto& localizer = payload.onboard().localizer;
    run.metrics = localizer.methodMetrics();
    for (const auto& [robot, traj] : localizer.estimates()) {
        std::vector<double> e;
        for (const auto& te : common::positionErrors(traj, run.result.groundTruth.at(robot)))
            e.push_back(te.error);
        run.errors[robot] = common::computeStats(e);
    }
    return run;
}

double receptionRate(const beacons::ShotLog& log, const std::string& robot, int beacon) {
    size_t shots = 0, heard = 0;
    for (const auto& s : log)
        if (s.robot == robot && s.beacon == beacon) ++shots, heard += s.detected;
    return shots ? double(heard) / double(shots) : -1;
}

}  // namespace

TEST(ShotScheduler, PriorityServesInProportionToSpeedRoundRobinTakesTurns) {
    for (const auto policy : {beacons::Scheduling::Priority, beacons::Scheduling::RoundRobin}) {
        beacons::ShotScheduler scheduler(policy, 0.05);
        std::vector<beacons::RobotReport> robots(2);
        robots[0].robot = "slow", robots[0].speed = 0.1;
        robots[1].robot = "fast", robots[1].speed = 0.8;
        std::map<std::string, int> slots;
        for (int k = 0; k < 900; ++k) {
            const double t = 0.1 * k;
            const auto& r = robots[scheduler.pick(t, robots)];
            scheduler.served(r.robot, t);
            ++slots[r.robot];
        }
        if (policy == beacons::Scheduling::Priority)
            EXPECT_NEAR(double(slots["fast"]) / slots["slow"], 8.0, 1.0);  // 0.8 / 0.1, in slots
        else
            EXPECT_EQ(slots["fast"], slots["slow"]);
    }
}

TEST(ActiveBeacons, NoTwoShotsOverlapInTimeAcrossRobotsAndSections) {
    const auto ini = shippedIni("beacons_multi_robot.ini", {{"scenario", "duration", "20"}});
    const auto run = runClosedLoop(*ini, "overlap");
    const auto& shots = run.shots;
    ASSERT_GT(shots.size(), 250u);
    std::set<std::string> sections, robots;
    for (size_t k = 0; k < shots.size(); ++k) {
        sections.insert(shots[k].section);
        robots.insert(shots[k].robot);
        EXPECT_NEAR(shots[k].end - shots[k].start, 0.03, 1e-12);
        if (k > 0) {
            ASSERT_GE(shots[k].start, shots[k - 1].end - 1e-9) << "shot " << k;
        }
    }
    EXPECT_EQ(sections.size(), 2u);
    EXPECT_EQ(robots.size(), 4u);
}

TEST(ActiveBeacons, PrioritySchedulingEqualisesTheDistanceBetweenFixes) {
    // Mean distance travelled between two fixes, slowest and fastest robot (0.1, 0.8 m/s).
    const auto spread = [](const nlohmann::json& m) {
        double lo = 1e9, hi = 0;
        for (const auto& [robot, r] : m["robots"].items()) {
            lo = std::min(lo, r["mean_distance_between_fixes_m"].get<double>());
            hi = std::max(hi, r["mean_distance_between_fixes_m"].get<double>());
        }
        return hi / lo;
    };
    const auto priority = runClosedLoop(*shippedIni("beacons_multi_robot.ini"), "priority");
    const auto roundRobin =
        runClosedLoop(*shippedIni("beacons_multi_robot_round_robin.ini"), "round_robin");
    EXPECT_LT(spread(priority.metrics), 1.8) << priority.metrics.dump(1);
    EXPECT_GT(spread(roundRobin.metrics), 5.0) << roundRobin.metrics.dump(1);
    for (const auto& [robot, e] : priority.errors) EXPECT_LT(e.rmse, 0.10) << robot;
}

TEST(ActiveBeacons, HandoverKeepsFixesFlowingAcrossTheSectionBoundary) {
    // One robot drives from the west section into the east one and back.
    const auto ini = [](const std::string& margin) {
        return shippedIni("beacons_multi_robot.ini", {{"scenario", "robots", "fast"},
                                                      {"scenario", "duration", "40"},
                                                      {"beacons", "handover_margin", margin},
                                                      {"beacons", "registration_time", "1.0"}});
    };
    const auto with = runClosedLoop(*ini("0.6"), "handover");
    const auto without = runClosedLoop(*ini("0"), "no_handover");
    const auto gap = [](const ClosedLoopRun& r) {
        return r.metrics["robots"]["fast"]["max_time_between_fixes_s"].get<double>();
    };
    std::set<std::string> sections;
    for (const auto& s : with.shots) sections.insert(s.section);
    EXPECT_EQ(sections.size(), 2u);  // it was ranged by both sections
    // Fixes every 0.1-0.2 s, boundary or not; the east heads' first slew (at most half a turn
    // at 360 deg/s) is the longest pause.
    EXPECT_LT(gap(with), 0.7);
    EXPECT_GE(gap(without), 1.0);  // waits for the east section's table
    EXPECT_LT(with.errors.at("fast").rmse, 0.10);
}

TEST(ActiveBeacons, ActiveAimingKeepsReceptionAndHalvesErrorsAgainstFixed) {
    const auto fixed = runClosedLoop(*shippedIni("beacons_fixed.ini"), "fixed");
    const auto active = runClosedLoop(*shippedIni("beacons_active.ini"), "active");
    // Seed 001 Table 3: beacon 2 is weak at point 4, which the fixed heads are not aimed at.
    EXPECT_LE(receptionRate(fixed.shots, "p4", 2), 0.8);
    // Table 4: aimed at the robot, every beacon is heard at every point.
    for (const char* p : {"p1", "p2", "p3", "p4", "p5"})
        for (int b : {1, 2, 3}) EXPECT_GE(receptionRate(active.shots, p, b), 0.9) << p;
    const auto mean = [](const ClosedLoopRun& r) {
        double s = 0;
        for (const auto& [robot, e] : r.errors) s += e.mean;
        return s / double(r.errors.size());
    };
    EXPECT_LT(mean(active), 0.7 * mean(fixed));
}

TEST(Sections, BadSectionKeysAreErrorsNamingTheKey) {
    const std::string base =
        "[beacons]\nbeacon_1 = 0 0 2.5\nbeacon_2 = 3 0 2.5\nbeacon_3 = 0 3 2.5\n";
    for (const char* bad :
         {"section_a = 0 0 3 3\nsection_a_beacons = 1 7\n", "section_a = 0 0 3 3\n",
          "section_a = 3 0 0 3\nsection_a_beacons = 1\n", "section_b_beacons = 1 2\n",
          "section_a = 0 0 3 3\nsection_a_beacons = 1\nsection_a_aim = 1 1\n"}) {
        mrpt::config::CConfigFileMemory ini(base + bad);
        beacons::BeaconLocalizer loc;
        try {
            loc.configure(ini);
            ADD_FAILURE() << "accepted " << bad;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("section_"), std::string::npos) << e.what();
        }
    }
}

// Seed 001's own room (4 x 5.7 m, three active beacons, 5 points x 10 trials, the link
// model as calibrated on Table 3): the paper's fix (config/beacons_active_large.ini) against
// mrloc's (config/beacons_paper_room.ini: height known, range residual, delay compensation,
// four shots per beacon). Measured on seed 1: the paper's method mean 62.8 mm, max 179 mm;
// mrloc's mean 10.6 mm, max 31.5 mm (the paper's next goal: max under 50 mm; over 10 seeds
// in doc/beacons.md the maxima are 22.6-39.7 mm). Bounds: 14 and 40 mm, about 1.3 times
// what seed 1 measured.
TEST(ActiveBeacons, ThePapersRoomMeetsItsNextGoalWithMrlocsFix) {
    const auto paper = runClosedLoop(*shippedIni("beacons_active_large.ini"), "paper_room_paper");
    const auto ours = runClosedLoop(*shippedIni("beacons_paper_room.ini"), "paper_room_mrloc");
    const auto pooled = [](const ClosedLoopRun& r) {
        double sum = 0, worst = 0;
        size_t n = 0;
        for (const auto& [robot, e] : r.errors) {
            sum += e.mean * double(e.n), n += e.n;
            worst = std::max(worst, e.max);
        }
        return std::make_tuple(sum / double(n), worst, n);
    };
    const auto [paperMean, paperMax, paperN] = pooled(paper);
    const auto [mean, max, n] = pooled(ours);
    EXPECT_EQ(n, 50u);  // every trial of every point gave a fix
    EXPECT_LT(mean, 0.014);
    EXPECT_LT(max, 0.040);
    EXPECT_GT(paperMean, 4 * mean);  // measured 5.9 times
    EXPECT_GT(paperMax, 4 * max);    // 5.7 times
    for (const char* p : {"p1", "p2", "p3", "p4", "p5"})
        for (int b : {1, 2, 3}) EXPECT_GE(receptionRate(ours.shots, p, b), 0.9) << p;
    std::cout << "paper's fix: mean " << paperMean << " max " << paperMax << " m; mrloc's: mean "
              << mean << " max " << max << " m\n";
}

TEST(RfBeacon, ShotsPerBeaconRepeatTheSectionAndAgeEachBeaconByItsMeanShot) {
    // three beacons fired twice, 30 ms apart: beacon 1's shots are the 1st and 4th of 6, so
    // they were read 150 and 60 ms before the epoch's end: 105 ms on average
    mrpt::config::CConfigFileMemory ini(
        "[beacons]\nbeacon_1 = 0 0 2.5\nbeacon_2 = 3 0 2.5\nbeacon_3 = 0 3 2.5\n"
        "shots_per_beacon = 2\n");
    beacons::BeaconLocalizer loc;
    loc.configure(ini);
    EXPECT_NEAR(loc.options().system.shotAge(1), 0.105, 1e-12);
    EXPECT_NEAR(loc.options().system.shotAge(3), 0.045, 1e-12);  // shots 3 and 6: 90 and 0 ms
    beacons::RfBeacon rf(loc.options().system);
    beacons::RobotReport r;
    r.robot = "a";
    const auto e = rf.nextEpoch(0, {r});
    ASSERT_TRUE(e);
    EXPECT_EQ(e->beacons, (std::vector<int>{1, 2, 3, 1, 2, 3}));
    EXPECT_EQ(e->aimPoints.size(), 6u);
}
