// [polymap] options: effective.ini's round trip (save, load, save gives the same text).
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/polymap/PolymapOptions.h>
#include <mrpt/config/CConfigFileMemory.h>

#include "OptionsRoundTrip.h"

using namespace mrloc;

TEST(PolymapOptions, EffectiveIniRoundTrips) {
    for (const char* name : {"polymap_steps", "polymap_rooms", "polymap_file", "polymap_steps148",
                             "polymap_steps76"}) {
        const auto [first, second] =
            testing_options::roundTrip<polymap::PolymapOptions>(name, "polymap");
        EXPECT_EQ(second.generator, first.generator) << name;
        EXPECT_EQ(second.mapFile, first.mapFile) << name;
        EXPECT_EQ(second.scanRays, first.scanRays) << name;
        EXPECT_EQ(second.heading, first.heading) << name;
        EXPECT_EQ(second.elimination, first.elimination) << name;
        EXPECT_EQ(second.randomPoints, first.randomPoints) << name;
        EXPECT_EQ(second.clearance, first.clearance) << name;
        // The same map and start come out of it.
        const auto m1 = first.buildMap(), m2 = second.buildMap();
        EXPECT_EQ(m1.polygon.size(), m2.polygon.size()) << name;
        EXPECT_EQ(first.startIn(m1).x, second.startIn(m2).x) << name;
        EXPECT_EQ(first.startIn(m1).y, second.startIn(m2).y) << name;
    }
}

namespace {

/** [polymap] options from these INI lines. */
polymap::PolymapOptions polymapOptionsOf(const std::string& lines) {
    mrpt::config::CConfigFileMemory ini("[polymap]\n" + lines);
    polymap::PolymapOptions o;
    o.loadFromConfigFile(ini, "polymap");
    return o;
}

}  // namespace

TEST(PolymapOptions, EliminationKeys) {
    const auto load = polymapOptionsOf;
    EXPECT_TRUE(load("").elimination.empty());  // none by default
    EXPECT_EQ(load("elimination = all").elimination.size(), 4u);
    EXPECT_EQ(load("elimination = windows cells").elimination,
              (std::vector<polymap::ProbeStrategy>{polymap::ProbeStrategy::Windows,
                                                   polymap::ProbeStrategy::VisibilityCells}));
    EXPECT_EQ(load("random_points = 50").randomPoints, std::vector<int>{50});
    EXPECT_EQ(load("drive = windows").drive, polymap::ProbeStrategy::Windows);
    EXPECT_FALSE(load("").drive);
    for (const char* bad : {"elimination = cell", "elimination = all windows", "random_points = 0",
                            "random_points = 10.5", "clearance = -1", "drive = fast",
                            "drive = cells\nscan_rate = 1", "sweep_steps = 3\nelimination = none",
                            // list keys that multiply the experiment's work are bounded in length
                            "random_points = 1 2 3 4 5 6 7 8 9",
                            "sweep_steps = 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20 "
                            "21\nelimination = cells"}) {
        try {
            load(bad);
            ADD_FAILURE() << bad << ": no error";
        } catch (const Error& e) {
            const std::string key = std::string(bad).substr(0, std::string(bad).find(' '));
            EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
        }
    }
}

TEST(PolymapOptions, RoomsKeys) {
    const auto load = [](const std::string& lines) {
        return polymapOptionsOf("generator = rooms\n" + lines);
    };
    EXPECT_EQ(load("pillar = 0.5").rooms.pillar, 0.5);
    EXPECT_EQ(load("").rooms.pillar, 0.0);                               // none by default
    EXPECT_EQ(load("pillar = 0.5").buildMap().polygon.ringCount(), 5u);  // 4 rooms, 4 pillars
    // a row has no corridor: its keys are refused, not silently ignored
    for (const char* bad : {"room_layout = row\nroom_gap = 2",
                            "room_layout = row\nright_margin = 1", "pillar = -1"}) {
        try {
            load(bad);
            ADD_FAILURE() << bad << ": no error";
        } catch (const Error& e) {
            const std::string key = std::string(bad).substr(
                std::string(bad).rfind('\n') + 1,
                std::string(bad).rfind(" =") - std::string(bad).rfind('\n') - 1);
            EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
        }
    }
    // a pillar too big for the room: the generator names the bound
    try {
        load("pillar = 3").buildMap();
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("pillar 3 m: at most"), std::string::npos) << e.what();
    }
}
