#pragma once
// One seed per run, every random draw derived from it (doc/architecture.md, "The seed").
//
// The run's seed is [scenario] seed (or --seed, which RunSetup writes there). The simulation
// draws from it directly; run r of an experiment that repeats the scenario (framesync's
// seeds, formation's Table 1) is the run of seed + r, so `mrloc batch --seeds` gives the same
// trials; polymap's randomized probes and rooms and omnivision's swarm take a generator seeded
// by drawSeed(seed, purpose), a purpose being a fixed name, and the beacon study one per
// evaluation (streamSeed(seedOf(seed, its description), point)), formation's pixel table one
// per march (streamSeed(seedOf(experiment seed, "formation pixel table"), march)) and its
// fig. 15 and fig. 11 one (drawSeed(experiment seed, "formation fig. 15 and fig. 11")).
// A key that fixes a sub-seed (`elimination_seed`, `map_seed`, `swarm_seed`,
// `experiment_seed`) is an override: absent, the draw follows the run's seed; given, it is
// written to effective.ini and the report names it.
#include <mrloc/common/IniSection.h>
#include <mrpt/config/CConfigFileBase.h>

#include <cstdint>
#include <string_view>

namespace mrloc::common {

/** The largest seed ([scenario] seed, --seed, a sub-seed): MRPT's generators take 32 bits. */
constexpr unsigned long kMaxSeed = 4294967295UL;

/** [scenario] seed of a configuration (1 when absent), bounded as the scenario reads it. */
unsigned long runSeed(const mrpt::config::CConfigFileBase& cfg);

/** FNV-1a's step (its 64-bit prime) over `purpose`, started from 1469598103934665603 ^ seed:
 *  a different 64-bit seed per purpose. The start is not FNV's standard offset basis; it is
 *  kept because the beacon study's published draws come from it. */
uint64_t seedOf(uint64_t seed, std::string_view purpose);

/** splitmix64's finalizer over (seed, index): a generator's seed for the index-th stream
 *  of one purpose (a study's point, a layout), whatever thread draws it. */
uint32_t streamSeed(uint64_t seed, uint64_t index);

/** The seed of the generator for `purpose` in a run of seed `runSeed`. */
inline uint32_t drawSeed(uint64_t runSeed, std::string_view purpose) {
    return streamSeed(seedOf(runSeed, purpose), 0);
}

/** A sub-seed key: its value when the section gives it, otherwise drawSeed(run's seed,
 *  purpose). `given` tells which (effective.ini writes the key only when given). */
struct SubSeed {
    unsigned long value = 0;
    bool given = false;
};
SubSeed subSeed(IniSection& section, const std::string& key, unsigned long runSeed,
                std::string_view purpose);
/** A sub-seed that, absent, is the run's seed itself: an experiment whose run r is the run of
 *  seed + r (formation's experiment_seed). */
SubSeed subSeed(IniSection& section, const std::string& key, unsigned long runSeed);

}  // namespace mrloc::common
