// Every option's default is written once, in its struct: a section with no keys loads to a
// default-constructed struct. Compared through what each writes into effective.ini, so that a
// loader with a default of its own (a literal beside the struct's) fails here by key.
#include <gtest/gtest.h>
#include <mrloc/beacons/BeaconLocalizer.h>
#include <mrloc/beacons/BeaconRanging.h>
#include <mrloc/beacons/Ultrasonic.h>
#include <mrloc/formation/FormationConfig.h>
#include <mrloc/framesync/FramesyncConfig.h>
#include <mrloc/omnivision/OmniOptions.h>
#include <mrloc/polymap/PolymapOptions.h>
#include <mrloc/report/ReportOptions.h>
#include <mrloc/sim/Scenario.h>
#include <mrloc/sim/World.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <string>

using namespace mrloc;

namespace {

/** The keys two saves of a section disagree on, "key: default-constructed / loaded". */
template <class Options>
std::string defaultsDiffer(const std::string& section) {
    const Options constructed;
    Options loaded;
    // loaded twice: the second load must start from the defaults again, not the first's values
    const mrpt::config::CConfigFileMemory empty("[" + section + "]\n");
    loaded.loadFromConfigFile(empty, section);
    loaded.loadFromConfigFile(empty, section);
    mrpt::config::CConfigFileMemory a, b;
    constructed.saveToConfigFile(a, section);
    loaded.saveToConfigFile(b, section);
    std::vector<std::string> keys;
    a.getAllKeys(section, keys);
    std::string out;
    for (const auto& k : keys)
        if (a.read_string(section, k, "") != b.read_string(section, k, "?"))
            out += k + ": " + a.read_string(section, k, "") + " / " +
                   b.read_string(section, k, "?") + "\n";
    return out;
}

}  // namespace

TEST(Defaults, EverySectionWithoutKeysLoadsToItsStructsDefaults) {
    EXPECT_EQ(defaultsDiffer<sim::ScenarioOptions>("scenario"), "");
    EXPECT_EQ(defaultsDiffer<sim::WorldOptions>("world"), "");
    EXPECT_EQ(defaultsDiffer<report::ReportOptions>("report"), "");
    EXPECT_EQ(defaultsDiffer<formation::FormationConfig>("formation"), "");
    EXPECT_EQ(defaultsDiffer<framesync::FramesyncConfig>("framesync"), "");
    EXPECT_EQ(defaultsDiffer<omnivision::OmniOptions>("omnivision"), "");
    EXPECT_EQ(defaultsDiffer<polymap::PolymapOptions>("polymap"), "");
    EXPECT_EQ(defaultsDiffer<beacons::SensorOptions>("sensors"), "");
    EXPECT_EQ(defaultsDiffer<beacons::UltrasonicOptions>("ultrasonic"), "");
}
