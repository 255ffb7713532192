#pragma once
// One seed per run, every random draw derived from it (doc/architecture.md, "The seed").
//
// The run's seed is [scenario] seed (or --seed, which RunSetup writes there). The simulation
// draws from it directly; run r of an experiment that repeats the scenario (framesync's
// seeds, formation's Table 1) is the run of seed + r, so `mrloc batch --seeds` gives the same
// trials; every other draw (polymap's randomized probes and rooms, omnivision's swarm, the
// beacon study's evaluations, formation's experiments) takes a generator seeded by
// drawSeed(seed, purpose), a purpose being a fixed name. A key that fixes a sub-seed
// (`elimination_seed`, `map_seed`, `swarm_seed`, `experiment_seed`) is an override: absent,
// the draw follows the run's seed; given, it is written to effective.ini and the report
// names it.
#include <mrloc/common/IniSection.h>
#include <mrpt/config/CConfigFileBase.h>

#include <cstdint>
#include <optional>
#include <string_view>

namespace mrloc::common {

/** [scenario] seed of a configuration (1 when absent), bounded as the scenario reads it. */
unsigned long runSeed(const mrpt::config::CConfigFileBase& cfg);

/** FNV-1a over `purpose`, started from the seed: a different 64-bit seed per purpose. */
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

}  // namespace mrloc::common
