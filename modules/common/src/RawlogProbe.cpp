#include <fcntl.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/Rawlog.h>
#include <mrloc/common/RawlogProbe.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <zlib.h>

#if defined(__SANITIZE_ADDRESS__)
#define MRLOC_HAS_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define MRLOC_HAS_SANITIZER 1
#endif
#endif
#if MRLOC_HAS_SANITIZER
#include <sanitizer/common_interface_defs.h>
#endif

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <new>
#include <thread>
#include <vector>

namespace mrloc::common {

void checkGzipFile(const std::string& path, const std::string& what) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(what + " " + path + ": cannot open");
    unsigned char magic[2] = {0, 0};
    in.read(reinterpret_cast<char*>(magic), 2);
    const bool gzip = in.gcount() == 2 && magic[0] == 0x1f && magic[1] == 0x8b;
    in.clear();
    in.seekg(0);
    if (!gzip) return;

    z_stream z{};
    if (inflateInit2(&z, 16 + MAX_WBITS) != Z_OK) throw Error("zlib: cannot initialise");
    std::vector<unsigned char> inBuf(1 << 16), outBuf(1 << 18);
    size_t consumed = 0, inflated = 0;
    unsigned char head[2] = {0, 0};  // the first inflated bytes
    bool streamEnded = false;        // the last member's trailer was read
    for (;;) {
        in.read(reinterpret_cast<char*>(inBuf.data()), std::streamsize(inBuf.size()));
        const auto got = size_t(in.gcount());
        if (got == 0) break;
        z.next_in = inBuf.data();
        z.avail_in = uInt(got);
        while (z.avail_in > 0) {
            if (streamEnded) {
                // gzread reads concatenated members; anything else after a member is junk.
                if (z.next_in[0] != 0x1f) {
                    inflateEnd(&z);
                    throw Error(what + " " + path +
                                ": bytes after the end of the gzip stream "
                                "at byte " +
                                std::to_string(consumed + (got - z.avail_in)));
                }
                inflateReset(&z);
                streamEnded = false;
            }
            z.next_out = outBuf.data();
            z.avail_out = uInt(outBuf.size());
            const int rc = inflate(&z, Z_NO_FLUSH);
            for (size_t k = 0; k < outBuf.size() - z.avail_out && inflated + k < 2; ++k)
                head[inflated + k] = outBuf[k];
            inflated += outBuf.size() - z.avail_out;
            if (rc == Z_STREAM_END) {
                streamEnded = true;
            } else if (rc != Z_OK && rc != Z_BUF_ERROR) {
                const std::string msg = z.msg ? z.msg : ("zlib error " + std::to_string(rc));
                const size_t at = consumed + (got - z.avail_in);
                inflateEnd(&z);
                throw Error(what + " " + path + ": corrupt gzip stream near byte " +
                            std::to_string(at) + " (" + msg + ")");
            }
        }
        consumed += got;
    }
    inflateEnd(&z);
    if (!streamEnded)
        throw Error(what + " " + path + ": the gzip stream stops at byte " +
                    std::to_string(consumed) + " before its end (truncated file" +
                    (inflated == 0 ? ", no data after the header)" : ")"));
    if (head[0] == 0x1f && head[1] == 0x8b)
        throw Error(what + " " + path +
                    ": a gzip stream inside a gzip stream (compressed "
                    "twice? decompress it once with gunzip and read the result)");
}

namespace {

/** What the child reports through shared memory. */
struct ProbeState {
    volatile size_t entriesDone;  // entries deserialized and classified without error
    volatile int finished;        // 1: read to the end; 2: stopped with `message`
    char message[1024];
};

size_t currentAddressSpace() {
    std::ifstream statm("/proc/self/statm");
    size_t pages = 0;
    statm >> pages;
    return pages * size_t(sysconf(_SC_PAGESIZE));
}

size_t memoryLimitOf(const RawlogProbeLimits& limits) {
    if (const char* mb = std::getenv("MRLOC_RAWLOG_MEMORY_MB")) {
        char* end = nullptr;
        const unsigned long long v = std::strtoull(mb, &end, 10);
        if (end && *end == '\0' && v > 0 && v < (1ull << 24)) return size_t(v) << 20;
        throw Error("MRLOC_RAWLOG_MEMORY_MB=" + std::string(mb) +
                    ": expected a positive number of MiB");
    }
    return limits.memoryBytes;
}

/** The child's work: reads and throws; sets state->entriesDone as it goes. */
using ChildWork = std::function<void(ProbeState*)>;

[[noreturn]] void runChild(const std::string& path, const std::string& what, size_t memoryLimit,
                           double cpuSeconds, const ChildWork& work, ProbeState* state) {
    // A signal ends the child plainly; the parent, signalled too, removes its own outputs.
    // A crash ends it plainly too: no handler inherited from the parent (a sanitizer's or a
    // fuzzer's, which would report the crash of MRPT's code as the parent's) runs here.
    for (int sig : {SIGINT, SIGTERM, SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT})
        signal(sig, SIG_DFL);
#if MRLOC_HAS_SANITIZER
    __sanitizer_set_death_callback(nullptr);
#endif
    // MRPT and the sanitizers print what they find on stderr; the parent reports it in one
    // line instead.
    if (!std::getenv("MRLOC_PROBE_VERBOSE")) {
        const int devnull = open("/dev/null", O_WRONLY);
        if (devnull >= 0) dup2(devnull, STDERR_FILENO);
    }
    rlimit as{};
    if (getrlimit(RLIMIT_AS, &as) == 0) {
        const rlim_t want = rlim_t(currentAddressSpace() + memoryLimit);
        if (as.rlim_max == RLIM_INFINITY || want < as.rlim_max) as.rlim_cur = want;
        setrlimit(RLIMIT_AS, &as);
    }
    rlimit cpu{rlim_t(cpuSeconds), rlim_t(cpuSeconds) + 5};
    setrlimit(RLIMIT_CPU, &cpu);
    try {
        work(state);
        state->finished = 1;
        _exit(0);
    } catch (const std::bad_alloc&) {
        std::snprintf(state->message, sizeof state->message,
                      "%s %s: entry %zu needs more than %zu MiB to deserialize (a corrupt "
                      "size?)",
                      what.c_str(), path.c_str(), size_t(state->entriesDone) + 1,
                      memoryLimit >> 20);
    } catch (const std::exception& e) {
        std::snprintf(state->message, sizeof state->message, "%s", e.what());
    }
    state->finished = 2;
    _exit(1);
}

}  // namespace

namespace {

/** Runs `work` on `path` in a child process (see probeRawlog); `what` names the file's kind
 *  in errors. */
void probeInChild(const std::string& path, const std::string& what, const ChildWork& work,
                  const RawlogProbeLimits& limits) {
    const size_t memoryLimit = memoryLimitOf(limits);
    std::error_code ec;
    const double cpuSeconds =
        limits.cpuSecondsBase + double(std::filesystem::file_size(path, ec)) / double(1 << 20);

    void* shared = mmap(nullptr, sizeof(ProbeState), PROT_READ | PROT_WRITE,
                        MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (shared == MAP_FAILED) throw Error(what + " " + path + ": cannot map shared memory");
    auto* state = new (shared) ProbeState{};
    struct Unmap {
        void* p;
        ~Unmap() { munmap(p, sizeof(ProbeState)); }
    } unmap{shared};

    std::fflush(nullptr);  // the child must not inherit unwritten output
    const pid_t pid = fork();
    if (pid < 0) throw Error(what + " " + path + ": cannot fork to check it");
    if (pid == 0) runChild(path, what, memoryLimit, cpuSeconds, work, state);

    // The gzip stream is checked meanwhile, on a second thread (after the fork: a child
    // forked from a threaded process inherits only the forking thread). Its error comes first:
    // a corrupt stream also makes the child's entries look truncated.
    std::exception_ptr gzipError;
    std::atomic<bool> gzipFailed{false};
    std::thread gzipCheck([&] {
        try {
            checkGzipFile(path, what);
        } catch (...) {
            gzipError = std::current_exception();
            gzipFailed.store(true);
        }
    });
    struct Join {
        std::thread& t;
        ~Join() {
            if (t.joinable()) t.join();
        }
    } join{gzipCheck};

    // The address-space cap turns a huge allocation into bad_alloc with glibc's allocator;
    // AddressSanitizer's allocator serves from space reserved up front, which the cap does
    // not see. So the parent also watches the child's resident memory and stops it there.
    int status = 0;
    bool overMemory = false;
    const std::string statm = "/proc/" + std::to_string(pid) + "/statm";
    const size_t pageSize = size_t(sysconf(_SC_PAGESIZE));
    for (;;) {
        const pid_t done = waitpid(pid, &status, WNOHANG);
        if (done == pid) break;
        if (done < 0 && errno != EINTR)
            throw Error(what + " " + path + ": lost the checking process");
        if (gzipFailed.load()) {  // the child's verdict no longer matters
            kill(pid, SIGKILL);
            waitpid(pid, &status, 0);
            break;
        }
        size_t pages = 0, resident = 0;
        std::ifstream(statm) >> pages >> resident;
        if (resident * pageSize > memoryLimit) {
            overMemory = true;
            kill(pid, SIGKILL);
            waitpid(pid, &status, 0);
            break;
        }
        usleep(2000);
    }
    gzipCheck.join();
    if (gzipError) std::rethrow_exception(gzipError);
    if (state->finished == 1 && WIFEXITED(status) && WEXITSTATUS(status) == 0) return;
    if (state->finished == 2) throw Error(std::string(state->message));

    const std::string entry = "entry " + std::to_string(state->entriesDone + 1);
    if (overMemory)
        throw Error(what + " " + path + ": " + entry + " needs more than " +
                    std::to_string(memoryLimit >> 20) + " MiB to deserialize (a corrupt size?)");
    if (WIFSIGNALED(status) && WTERMSIG(status) == SIGXCPU)
        throw Error(what + " " + path + ": " + entry + " takes more than " +
                    std::to_string(int(cpuSeconds)) + " s of CPU to deserialize (corrupt?)");
    const std::string how = WIFSIGNALED(status)
                                ? std::string("crashed with ") + strsignal(WTERMSIG(status))
                                : "failed (exit " + std::to_string(WEXITSTATUS(status)) + ")";
    throw Error(what + " " + path + ": " + entry + " is corrupt: MRPT's deserializer " + how +
                " reading it (or it needs more than " + std::to_string(memoryLimit >> 20) +
                " MiB)");
}

}  // namespace

void probeRawlog(const std::string& path, const RawlogProbeLimits& limits) {
    probeInChild(
        path, "rawlog",
        [&path](ProbeState* state) {
            RawlogReader reader(path, RawlogReader::kUnchecked);
            for (mrpt::obs::CObservation::Ptr obs; reader.next(obs);)
                state->entriesDone = reader.entriesRead();
            state->entriesDone = reader.entriesRead();
        },
        limits);
}

void probeFile(const std::string& path, const std::string& what, const std::function<void()>& read,
               const RawlogProbeLimits& limits) {
    probeInChild(
        path, what,
        [&](ProbeState*) {
            try {
                read();
            } catch (const std::bad_alloc&) {
                throw;
            } catch (const Error&) {
                throw;
            } catch (const std::exception& e) {  // MRPT's own words, without the file
                throw Error(what + " " + path + ": cannot be read: " + oneLine(e.what()));
            }
        },
        limits);
}

}  // namespace mrloc::common
