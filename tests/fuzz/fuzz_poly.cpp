// Fuzzes the .poly reader and the polygon validation behind it: any input must give a valid
// simple polygon or mrloc::Error. A polygon that loads must have positive area and
// counter-clockwise vertices, which the target checks.
#include <mrloc/common/Error.h>
#include <mrloc/common/Polygon.h>

#include <cstdlib>

#include "FuzzInput.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string& path = mrloc::fuzz::writeInput(data, size, ".poly");
    try {
        const auto P = mrloc::common::Polygon::load(path);
        if (!(P.area() > 0)) std::abort();  // validation let a degenerate polygon through
    } catch (const mrloc::Error&) {
    }
    return 0;
}
