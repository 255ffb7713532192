#pragma once
// effective.ini's promise for a method's options: what saveToConfigFile writes loads back
// (no key refused) and saves to the same text. Returns the reloaded options for further
// comparison.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <string>
#include <utility>

#include "TestPaths.h"

namespace mrloc::testing_options {

template <class Options>
std::pair<Options, Options> roundTrip(const std::string& configName, const std::string& section) {
    mrpt::config::CConfigFile ini(std::string(MRLOC_SOURCE_DIR) + "/config/" + configName + ".ini");
    Options first;
    first.loadFromConfigFile(ini, section);
    mrpt::config::CConfigFileMemory saved;
    first.saveToConfigFile(saved, section);
    Options second;
    second.loadFromConfigFile(saved, section);
    mrpt::config::CConfigFileMemory again;
    second.saveToConfigFile(again, section);
    EXPECT_EQ(saved.getContent(), again.getContent()) << configName;
    return {first, second};
}

}  // namespace mrloc::testing_options
