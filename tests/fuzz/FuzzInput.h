#pragma once
// A fuzz input as a file: mrloc's readers take paths (as users give them). The file lives in
// memory (/dev/shm when it exists), one per process, overwritten by every input.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

namespace mrloc::fuzz {

inline std::string inputPath(const char* extension) {
    const char* dir = std::filesystem::is_directory("/dev/shm") ? "/dev/shm" : "/tmp";
    return std::string(dir) + "/mrloc_fuzz_" + std::to_string(getpid()) + extension;
}

inline const std::string& writeInput(const uint8_t* data, size_t size, const char* extension) {
    static const std::string path = inputPath(extension);
    if (FILE* f = std::fopen(path.c_str(), "wb")) {
        if (size) std::fwrite(data, 1, size, f);
        std::fclose(f);
    }
    return path;
}

}  // namespace mrloc::fuzz
