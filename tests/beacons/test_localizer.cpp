// The beacon localizer on simulated rawlogs: fixes mode, tracker mode, robustness.
#include <gtest/gtest.h>
#include <mrloc/beacons/BeaconLocalizer.h>
#include <mrloc/common/Metrics.h>
#include <mrloc/common/Rawlog.h>
#include <mrloc/sim/Simulator.h>
#include <mrpt/config/CConfigFileMemory.h>

using namespace mrloc;

namespace {

std::string scenarioIni(const std::string& sensors, const std::string& beaconsExtra) {
    return R"(
[scenario]
name = loc
seed = 3
duration = 30
robots = r1
[world]
size = 3 3 2.5
[sensors]
)" + sensors +
           R"(
[robot.r1]
start = 0.5 0.5 0
waypoints = 2.5 0.5, 2.5 2.5, 0.5 2.5, 0.5 0.5
speed = 0.3
receiver = 0 0 0.5
[beacons]
beacon_1 = 0 0 2.5
beacon_2 = 3 0 2.5
beacon_3 = 3 3 2.5
beacon_4 = 0 3 2.5
)" + beaconsExtra;
}

struct Outcome {
    common::ErrorStats stats;
    nlohmann::json metrics;
};

Outcome runOn(const std::string& iniText, const std::string& tag) {
    mrpt::config::CConfigFileMemory ini(iniText);
    const auto cfg = sim::ScenarioConfig::load(ini);
    const std::string rawlog = sim::simulateToFiles(cfg, testing::TempDir() + "/loc_" + tag, true);
    beacons::BeaconLocalizer loc;
    loc.configure(ini);
    common::RawlogReader reader(rawlog);
    for (mrpt::obs::CObservation::Ptr obs; reader.next(obs);) loc.process(obs);
    const auto gt = common::loadTum(common::groundTruthPath(rawlog, "r1"));
    std::vector<double> e;
    for (const auto& te : common::positionErrors(loc.estimates().at("r1"), gt))
        e.push_back(te.error);
    return {common::computeStats(e), loc.methodMetrics()};
}

const char* kClean = "range_sigma = 0\nrange_dropout = 0\nrange_outlier_probability = 0\n";
const char* kNoisy = "range_sigma = 0.01\nrange_dropout = 0.05\nrange_outlier_probability = 0.05\n";

}  // namespace

TEST(BeaconLocalizer, FixesModeIsExactOnNoiseFreeRanges) {
    const auto o = runOn(scenarioIni(kClean, "mode = fixes\n"), "clean_fixes");
    EXPECT_EQ(o.stats.n, 151u);
    // Ranges are stored as float in CObservationBeaconRanges: ~1e-7 relative.
    EXPECT_LT(o.stats.max, 1e-5);
}

TEST(BeaconLocalizer, TrackerFollowsNoisyRangesWithOutliers) {
    const auto o = runOn(scenarioIni(kNoisy, "range_sigma = 0.01\n"), "noisy_tracker");
    EXPECT_LT(o.stats.rmse, 0.03) << o.metrics.dump();
    EXPECT_LT(o.stats.max, 0.10) << o.metrics.dump();
    EXPECT_GT(o.metrics["ranges_gated"].get<int>(), 0);
}
