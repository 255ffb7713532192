#include <mrloc/common/Seeds.h>

namespace mrloc::common {

unsigned long runSeed(const mrpt::config::CConfigFileBase& cfg) {
    // read, not finished: [scenario]'s own reader checks its other keys
    IniSection scenario(cfg, "scenario");
    return (unsigned long)scenario.integer("seed", 1, 0, long(kMaxSeed));
}

uint64_t seedOf(uint64_t seed, std::string_view purpose) {
    uint64_t h = 1469598103934665603ull ^ seed;
    for (const unsigned char c : purpose) h = (h ^ c) * 1099511628211ull;
    return h;
}

uint32_t streamSeed(uint64_t seed, uint64_t index) {
    uint64_t z = seed * 0x9E3779B97F4A7C15ull + index + 0x632BE59BD9B4E019ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return uint32_t((z ^ (z >> 31)) & 0xffffffffu);
}

SubSeed subSeed(IniSection& section, const std::string& key, unsigned long runSeed,
                std::string_view purpose) {
    if (!section.has(key)) return {drawSeed(runSeed, purpose), false};
    return subSeed(section, key, runSeed);
}

SubSeed subSeed(IniSection& section, const std::string& key, unsigned long runSeed) {
    if (!section.has(key)) return {runSeed, false};
    return {(unsigned long)section.integer(key, 0, 0, long(kMaxSeed)), true};
}

}  // namespace mrloc::common
