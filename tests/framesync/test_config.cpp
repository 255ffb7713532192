// [framesync] through effective.ini: what is saved loads back to the same options, and the
// robots' drift keys too.
#include <gtest/gtest.h>
#include <mrloc/framesync/FramesyncConfig.h>
#include <mrloc/sim/Scenario.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>

#include "OptionsRoundTrip.h"
#include "TestPaths.h"

using namespace mrloc;

TEST(FramesyncConfig, EffectiveIniLoadsBackToTheSameOptions) {
    for (const char* name : {"framesync_corridor", "framesync_team"}) {
        const auto [first, second] =
            testing_options::roundTrip<framesync::FramesyncConfig>(name, "framesync");
        EXPECT_EQ(second.rig.mounts.size(), first.rig.mounts.size()) << name;
        EXPECT_EQ(second.team.priority.listed(), first.team.priority.listed()) << name;
        EXPECT_DOUBLE_EQ(second.team.manager.match.maxBearing, first.team.manager.match.maxBearing);
        EXPECT_DOUBLE_EQ(second.rig.aperture, first.rig.aperture);
    }
    mrpt::config::CConfigFile ini(std::string(MRLOC_SOURCE_DIR) + "/config/framesync_team.ini");
    framesync::FramesyncConfig c;
    c.loadFromConfigFile(ini, "framesync");
    EXPECT_EQ(c.team.priority.listed(), (std::vector<std::string>{"r1", "r2", "r3", "r4"}));
    EXPECT_DOUBLE_EQ(c.team.manager.maxAge, 60);
    EXPECT_EQ(c.rig.mounts.size(), 3u);  // the default rig
    EXPECT_EQ(c.sweepSeeds, 0u);
}

TEST(FramesyncConfig, RobotDriftKeysSurviveEffectiveIni) {
    mrpt::config::CConfigFile ini(std::string(MRLOC_SOURCE_DIR) + "/config/framesync_corridor.ini");
    const auto s = sim::ScenarioConfig::load(ini);
    ASSERT_EQ(s.robots.size(), 2u);
    EXPECT_DOUBLE_EQ(s.robots[1].odometryScaleErrorSigma, 0.006);
    EXPECT_NEAR(s.robots[1].odometryHeadingDriftSigma, 0.045 * M_PI / 180, 1e-15);
    mrpt::config::CConfigFileMemory saved;
    s.save(saved);
    const auto again = sim::ScenarioConfig::load(saved);
    EXPECT_DOUBLE_EQ(again.robots[1].odometryHeadingDriftSigma,
                     s.robots[1].odometryHeadingDriftSigma);
    EXPECT_DOUBLE_EQ(again.robots[0].odometryScaleErrorSigma, s.robots[0].odometryScaleErrorSigma);
    ASSERT_EQ(again.world.pillars.size(), 4u);
    EXPECT_DOUBLE_EQ(again.world.pillars[1].radius, s.world.pillars[1].radius);
}
