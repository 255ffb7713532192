// [polymap] options: effective.ini's round trip (save, load, save gives the same text).
#include <gtest/gtest.h>
#include <mrloc/polymap/PolymapOptions.h>

#include "OptionsRoundTrip.h"

using namespace mrloc;

TEST(PolymapOptions, EffectiveIniRoundTrips) {
    for (const char* name : {"polymap_steps", "polymap_rooms", "polymap_file"}) {
        const auto [first, second] =
            testing_options::roundTrip<polymap::PolymapOptions>(name, "polymap");
        EXPECT_EQ(second.generator, first.generator) << name;
        EXPECT_EQ(second.mapFile, first.mapFile) << name;
        EXPECT_EQ(second.scanRays, first.scanRays) << name;
        EXPECT_EQ(second.heading, first.heading) << name;
        // The same map and start come out of it.
        const auto m1 = first.buildMap(), m2 = second.buildMap();
        EXPECT_EQ(m1.polygon.size(), m2.polygon.size()) << name;
        EXPECT_EQ(first.startIn(m1).x, second.startIn(m2).x) << name;
        EXPECT_EQ(first.startIn(m1).y, second.startIn(m2).y) << name;
    }
}
