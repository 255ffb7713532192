// Every INI shipped in config/ is valid as the app reads it before a run (checkIni: every
// method's options, the scenario, effective.ini), so that a user's first run of any of them
// does not stop at a key.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>

#include <filesystem>

#include "AllMethods.h"
#include "Commands.h"

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
