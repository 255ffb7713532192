#pragma once
// Checks a rawlog before mrloc reads it, so that a corrupt file is a clean error and never a
// crash, a hang or a machine out of memory (doc/errors.md).
//
// MRPT's deserializers trust the sizes and enum values they read: a flipped byte can make
// them dereference a null pointer or allocate gigabytes, and zlib errors inside a .gz stream
// read as a clean end of file. mrloc cannot guard code inside MRPT, so it isolates it:
//  1. a .gz file is inflated once with zlib, and a corrupt or truncated stream is an error;
//  2. every entry is deserialized once in a child process with a capped address space;
//     a crash, an exception or an allocation beyond the cap there is an error naming the
//     entry, and the parent, which reads the file only after this, never sees it.
#include <cstddef>
#include <functional>
#include <string>

namespace mrloc::common {

struct RawlogProbeLimits {
    /** Address space the child may add to its own while deserializing (one entry at a time
     *  is held). MRLOC_RAWLOG_MEMORY_MB overrides it. */
    size_t memoryBytes = size_t(2048) << 20;
    /** CPU seconds of the child: a base plus one second per MiB of file. */
    double cpuSecondsBase = 60.0;
};

/** Throws mrloc::Error naming `path` (and the entry or byte) if the file is not a complete,
 *  readable rawlog. */
void probeRawlog(const std::string& path, const RawlogProbeLimits& limits = {});

/** The same isolation for any file MRPT deserializes (a .gridmap, a .simplemap): `read` runs
 *  in the child, and a crash, an exception or an allocation beyond the cap there is an error
 *  naming `what` and `path`. A .gz file's stream is checked to its end as well. */
void probeFile(const std::string& path, const std::string& what, const std::function<void()>& read,
               const RawlogProbeLimits& limits = {});

/** Checks a gzip stream (all members) to its end; throws mrloc::Error naming `what` and the
 *  compressed byte offset on corruption or truncation. A file without gzip's magic bytes is
 *  left alone. */
void checkGzipFile(const std::string& path, const std::string& what);

}  // namespace mrloc::common
