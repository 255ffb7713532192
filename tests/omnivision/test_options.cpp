// [omnivision] options: effective.ini's round trip (save, load, save gives the same text).
#include <gtest/gtest.h>
#include <mrloc/omnivision/OmniOptions.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>

using namespace mrloc;

TEST(OmniOptions, EffectiveIniRoundTrips) {
    for (const char* name : {"omnivision_5robots", "omnivision_swarm"}) {
        mrpt::config::CConfigFile ini(std::string(MRLOC_SOURCE_DIR) + "/config/" + name + ".ini");
        omnivision::OmniOptions first;
        first.loadFromConfigFile(ini, "omnivision");
        mrpt::config::CConfigFileMemory saved;
        first.saveToConfigFile(saved, "omnivision");
        omnivision::OmniOptions second;
        second.loadFromConfigFile(saved, "omnivision");
        mrpt::config::CConfigFileMemory again;
        second.saveToConfigFile(again, "omnivision");
        EXPECT_EQ(saved.getContent(), again.getContent()) << name;
        EXPECT_EQ(second.pairs, first.pairs) << name;
        EXPECT_EQ(second.snapshotTimes(), first.snapshotTimes()) << name;
        EXPECT_EQ(second.swarm, first.swarm) << name;
        EXPECT_EQ(second.accuracyTrials, first.accuracyTrials) << name;
        EXPECT_EQ(second.render, first.render) << name;
    }
}
