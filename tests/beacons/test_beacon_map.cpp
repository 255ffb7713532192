// The beacon map in both INI forms: ours and MRPT's landmarks-map keys.
#include <gtest/gtest.h>
#include <mrloc/beacons/BeaconMap.h>
#include <mrloc/common/Error.h>
#include <mrpt/config/CConfigFileMemory.h>

using namespace mrloc;
using common::IniSection;

TEST(BeaconMap, OurKeysAndMrptLandmarksMapKeys) {
    mrpt::config::CConfigFileMemory ours("[beacons]\nbeacon_3 = 1 2 2.5\nbeacon_10 = 0 0 2.5\n");
    IniSection s(ours, "beacons");
    const auto m = beacons::loadBeaconMap(ours, s);
    ASSERT_EQ(m.size(), 2u);
    EXPECT_DOUBLE_EQ(m.at(3).y, 2.0);
    EXPECT_NO_THROW(s.finish());

    // As written for MRPT's pf-localization / ro-localization.
    mrpt::config::CConfigFileMemory theirs(
        "[MetricMap_landmarksMap_00_creationOpts]\nnBeacons = 2\n"
        "beacon_001_ID = 5\nbeacon_001_x = 1.0\nbeacon_001_y = 2.0\nbeacon_001_z = 2.5\n"
        "beacon_002_ID = 6\nbeacon_002_x = 3.0\nbeacon_002_y = 0.5\nbeacon_002_z = 2.4\n");
    IniSection empty(theirs, "beacons");
    const auto m2 = beacons::loadBeaconMap(theirs, empty);
    ASSERT_EQ(m2.size(), 2u);
    EXPECT_DOUBLE_EQ(m2.at(6).x, 3.0);
    EXPECT_DOUBLE_EQ(m2.at(5).z, 2.5);

    // MRPT would read a missing coordinate as 0; here it is an error.
    mrpt::config::CConfigFileMemory broken(
        "[MetricMap_landmarksMap_00_creationOpts]\nnBeacons = 1\nbeacon_001_ID = 5\nbeacon_001_x = "
        "1\n");
    IniSection e3(broken, "beacons");
    try {
        beacons::loadBeaconMap(broken, e3);
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("beacon_001_y: missing"), std::string::npos)
            << e.what();
    }
    mrpt::config::CConfigFileMemory none("[beacons]\n");
    IniSection e4(none, "beacons");
    EXPECT_THROW(beacons::loadBeaconMap(none, e4), Error);
    mrpt::config::CConfigFileMemory badId("[beacons]\nbeacon_x = 1 2 3\n");
    IniSection e5(badId, "beacons");
    EXPECT_THROW(beacons::loadBeaconMap(badId, e5), Error);
}
