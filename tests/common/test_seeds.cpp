// One seed per run (common/Seeds.h, doc/architecture.md "The seed"): every draw derives from
// [scenario] seed by a purpose name; a sub-seed key overrides it and is then written back.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/Seeds.h>
#include <mrloc/omnivision/OmniOptions.h>
#include <mrloc/polymap/PolymapOptions.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <set>

using namespace mrloc;

TEST(Seeds, TheRuleIsStableAndSeparatesSeedsAndPurposes) {
    // the values are the rule's, computed apart from the code: a change here changes every
    // derived draw (and the beacon study's published figures, which come from the same rule)
    EXPECT_EQ(common::seedOf(0, ""), 1469598103934665603ull);
    EXPECT_EQ(common::seedOf(0, "a"), (1469598103934665603ull ^ 'a') * 1099511628211ull);
    std::set<uint32_t> seen;
    for (const char* purpose : {"polymap elimination", "polymap rooms map", "omnivision swarm"})
        for (uint64_t seed = 0; seed < 1000; ++seed) seen.insert(common::drawSeed(seed, purpose));
    EXPECT_EQ(seen.size(), 3000u);  // no two (seed, purpose) share a generator
    EXPECT_NE(common::streamSeed(7, 0), common::streamSeed(7, 1));
    EXPECT_EQ(common::streamSeed(0, 0), 1447931562u);
    EXPECT_EQ(common::drawSeed(1, "polymap elimination"), 4221795016u);
    EXPECT_EQ(common::drawSeed(2, "polymap elimination"), 403848055u);
}

namespace {
polymap::PolymapOptions polymapOptions(const std::string& ini) {
    mrpt::config::CConfigFileMemory cfg(ini);
    polymap::PolymapOptions o;
    o.loadFromConfigFile(cfg, "polymap");
    return o;
}
omnivision::OmniOptions omniOptions(const std::string& ini) {
    mrpt::config::CConfigFileMemory cfg(ini);
    omnivision::OmniOptions o;
    o.loadFromConfigFile(cfg, "omnivision");
    return o;
}
}  // namespace

TEST(Seeds, SubSeedsFollowTheRunsSeedUnlessTheIniFixesThem) {
    const auto a = polymapOptions("[scenario]\nseed = 1\n[polymap]\ngenerator = rooms\n");
    const auto b = polymapOptions("[scenario]\nseed = 2\n[polymap]\ngenerator = rooms\n");
    EXPECT_FALSE(a.eliminationSeed.given);
    EXPECT_EQ(a.eliminationSeed.value, common::drawSeed(1, "polymap elimination"));
    EXPECT_EQ(b.eliminationSeed.value, common::drawSeed(2, "polymap elimination"));
    EXPECT_NE(a.eliminationSeed.value, b.eliminationSeed.value);
    EXPECT_NE(a.mapSeed.value, b.mapSeed.value);
    // no [scenario] seed: the scenario's default, 1
    EXPECT_EQ(polymapOptions("[polymap]\n").eliminationSeed.value, a.eliminationSeed.value);

    const auto fixed = polymapOptions(
        "[scenario]\nseed = 2\n[polymap]\ngenerator = rooms\nelimination_seed = 5\nmap_seed = 7\n");
    EXPECT_TRUE(fixed.eliminationSeed.given);
    EXPECT_EQ(fixed.eliminationSeed.value, 5u);
    EXPECT_EQ(fixed.mapSeed.value, 7u);

    // effective.ini holds an override, and no key for a seed drawn from the run's
    mrpt::config::CConfigFileMemory out;
    fixed.saveToConfigFile(out, "polymap");
    EXPECT_EQ(out.read_string("polymap", "elimination_seed", "-"), "5");
    mrpt::config::CConfigFileMemory drawn;
    b.saveToConfigFile(drawn, "polymap");
    EXPECT_FALSE(drawn.keyExists("polymap", "elimination_seed"));
    EXPECT_FALSE(drawn.keyExists("polymap", "map_seed"));

    EXPECT_NE(omniOptions("[scenario]\nseed = 1\n").swarmSeed.value,
              omniOptions("[scenario]\nseed = 2\n").swarmSeed.value);
    EXPECT_EQ(omniOptions("[scenario]\nseed = 2\n[omnivision]\nswarm_seed = 3\n").swarmSeed.value,
              3u);
    EXPECT_THROW(omniOptions("[omnivision]\nswarm_seed = -1\n"), Error);
}
