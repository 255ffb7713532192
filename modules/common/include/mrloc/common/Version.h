#pragma once
// mrloc's version, defined once: CMake's project(VERSION) passes it in as MRLOC_VERSION.

namespace mrloc {

#ifndef MRLOC_VERSION
#error "MRLOC_VERSION must be defined by the build (CMakeLists.txt)"
#endif
inline constexpr const char* kVersion = MRLOC_VERSION;

}  // namespace mrloc
