// Every INI shipped in config/ is valid as the app reads it before a run (checkIni: every
// method's options, the scenario, effective.ini), so that a user's first run of any of them
// does not stop at a key.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>

#include <filesystem>
#include <fstream>

#include "AllMethods.h"
#include "RunSetup.h"
#include "TestPaths.h"

TEST(ShippedConfigs, EveryConfigPassesTheAppsChecks) {
    mrloc::method::Registry registry;
    mrloc::app::registerAllMethods(registry);
    size_t checked = 0;
    for (const auto& e :
         std::filesystem::directory_iterator(std::string(MRLOC_SOURCE_DIR) + "/config")) {
        if (e.path().extension() != ".ini") continue;
        EXPECT_NO_THROW({
            try {
                mrloc::app::checkIni(registry, e.path().string());
            } catch (const mrloc::Error& err) {
                ADD_FAILURE() << e.path() << ": " << err.what();
                throw;
            }
        }) << e.path();
        ++checked;
    }
    EXPECT_GE(checked, 18u);  // 14 before formation, 4 formation configs
}

// No method is the default: an INI that names none and holds no method's section is refused
// with the registered methods listed (the list taken from the registry, not written here).
TEST(ShippedConfigs, AnIniThatNamesNoMethodListsTheRegisteredOnes) {
    mrloc::method::Registry registry;
    mrloc::app::registerAllMethods(registry);
    const std::string ini = testing::TempDir() + "/no_method.ini";
    std::ofstream(ini) << "[scenario]\nname = nothing\nrobots = r1\n[robot.r1]\nstart = 1 1 0\n";
    try {
        mrloc::app::checkIni(registry, ini);
        FAIL() << "an INI without a method was taken";
    } catch (const mrloc::Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("[scenario] method: required key is missing"), std::string::npos)
            << what;
        for (const auto& name : registry.names())
            EXPECT_NE(what.find(name), std::string::npos) << name << " not listed: " << what;
    }
}
