// Fuzzes the INI reader as `simulate`, `localize` and `run` use it before writing anything:
// the line checks, MRPT's parser, every registered method's options, the scenario (world,
// robots, maps) and effective.ini. Any input must be accepted or refused with mrloc::Error,
// in bounded time and memory.
// fuzz-seeds: config/*.ini tests/data/bad-inputs/*.ini /usr/share/mrpt/config_files/*/*.ini
// fuzz-max-len: 16384
#include <mrloc/common/Error.h>

#include "AllMethods.h"
#include "FuzzInput.h"
#include "RunSetup.h"

namespace {
const mrloc::method::Registry& registry() {
    static const mrloc::method::Registry r = [] {
        mrloc::method::Registry r;
        mrloc::app::registerAllMethods(r);
        return r;
    }();
    return r;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string& path = mrloc::fuzz::writeInput(data, size, ".ini");
    try {
        mrloc::app::checkIni(registry(), path);
    } catch (const mrloc::Error&) {
    }
    return 0;
}
