// [omnivision] options: effective.ini's round trip (save, load, save gives the same text).
#include <gtest/gtest.h>
#include <mrloc/omnivision/OmniOptions.h>

#include "OptionsRoundTrip.h"

using namespace mrloc;

TEST(OmniOptions, EffectiveIniRoundTrips) {
    for (const char* name : {"omnivision_5robots", "omnivision_swarm"}) {
        const auto [first, second] =
            testing_options::roundTrip<omnivision::OmniOptions>(name, "omnivision");
        EXPECT_EQ(second.pairs, first.pairs) << name;
        EXPECT_EQ(second.snapshotTimes(), first.snapshotTimes()) << name;
        EXPECT_EQ(second.swarm, first.swarm) << name;
        EXPECT_EQ(second.accuracyTrials, first.accuracyTrials) << name;
        EXPECT_EQ(second.render, first.render) << name;
    }
}
