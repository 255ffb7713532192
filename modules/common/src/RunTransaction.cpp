#include <dirent.h>
#include <fcntl.h>
#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/FolderLock.h>
#include <mrloc/common/Metrics.h>
#include <mrloc/common/RunTransaction.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <boost/uuid/detail/sha1.hpp>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>

namespace fs = std::filesystem;

namespace mrloc::common {

namespace {

// ---------------------------------------------------------------------------------------
// What a signal handler removes: the staging folder and lock file of each live transaction.
// A handler may only call async-signal-safe functions, so the paths live in a few fixed
// slots (one per transaction open at once, not per file).
struct LiveTransaction {
    std::atomic<int> state{0};  // 0 free, 1 being filled, 2 live
    char staging[4096];
    char lock[4096];
    char folder[4096];  // as the user named it, for the "interrupted" line
};
constexpr int kLiveSlots = 8;
LiveTransaction g_live[kLiveSlots];

/** Removes `name` under `dirFd` and, if it is a folder, everything in it, with system calls
 *  a signal handler may make (no allocation, no stdio; symbolic links are removed, never
 *  followed). */
void removeTreeAt(int dirFd, const char* name, int depth) {
    if (::unlinkat(dirFd, name, 0) == 0 || errno == ENOENT) return;
    if (depth > 32) return;
    const int fd = ::openat(dirFd, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0) return;
    alignas(8) char buf[8192];
    for (bool removedSome = true; removedSome;) {  // entries removed while listing: list again
        removedSome = false;
        ::lseek(fd, 0, SEEK_SET);
        for (;;) {
            const long n = ::syscall(SYS_getdents64, fd, buf, sizeof buf);
            if (n <= 0) break;
            for (long off = 0; off < n;) {
                struct Entry {
                    uint64_t ino;
                    int64_t off;
                    unsigned short reclen;
                    unsigned char type;
                    char name[1];
                };
                const auto* e = reinterpret_cast<const Entry*>(buf + off);
                off += e->reclen;
                if (!std::strcmp(e->name, ".") || !std::strcmp(e->name, "..")) continue;
                removeTreeAt(fd, e->name, depth + 1);
                removedSome = true;
            }
        }
    }
    ::close(fd);
    ::unlinkat(dirFd, name, AT_REMOVEDIR);
}

void removeTree(const char* path) { removeTreeAt(AT_FDCWD, path, 0); }

/** The temporaries held by holdTemporaryOnSignal, in fixed slots for the same reason. */
struct LiveTemporary {
    std::atomic<int> state{0};  // 0 free, 1 being filled, 2 live
    char path[4096];
};
LiveTemporary g_temporaries[kTemporarySlots];

/** write(2) of a C string: what a signal handler may print. */
void say(const char* text) {
    size_t n = 0;
    while (text[n]) ++n;
    while (n > 0) {
        const ssize_t w = ::write(STDERR_FILENO, text, n);
        if (w <= 0) return;
        text += w;
        n -= size_t(w);
    }
}

extern "C" void removeStagingAndExit(int sig) {
    // one line that says the run stopped and what is left: "mrloc: interrupted: out/x is
    // left as it was" (its previous run, or nothing); on a line of its own after a progress bar
    say(sig == SIGINT ? "\nmrloc: interrupted" : "\nmrloc: terminated");
    bool first = true;
    for (auto& t : g_live)
        if (t.state.load() == 2) {
            removeTree(t.staging);
            ::unlink(t.lock);
            say(first ? ": " : ", ");
            say(t.folder);
            first = false;
        }
    say(first ? "\n" : " left as it was\n");
    for (auto& t : g_temporaries)
        if (t.state.load() == 2) removeTree(t.path);
    _exit(128 + sig);
}

int claimLiveSlot(const std::string& staging, const std::string& lock, const std::string& folder) {
    if (staging.size() >= sizeof g_live[0].staging || lock.size() >= sizeof g_live[0].lock ||
        folder.size() >= sizeof g_live[0].folder)
        throw Error("run folder " + staging + ": the path is too long");
    for (int i = 0; i < kLiveSlots; ++i) {
        int expected = 0;
        if (g_live[i].state.compare_exchange_strong(expected, 1)) {
            std::memcpy(g_live[i].staging, staging.c_str(), staging.size() + 1);
            std::memcpy(g_live[i].lock, lock.c_str(), lock.size() + 1);
            std::memcpy(g_live[i].folder, folder.c_str(), folder.size() + 1);
            g_live[i].state.store(2);
            return i;
        }
    }
    throw Error("more than " + std::to_string(kLiveSlots) +
                " run folders open at once in one process");
}

void releaseLiveSlot(int slot) {
    if (slot >= 0) g_live[slot].state.store(0);
}

// ---------------------------------------------------------------------------------------

bool hasControlCharacter(const std::string& s) {
    for (const unsigned char c : s)
        if (c < 0x20 || c == 0x7f) return true;
    return false;
}

/** A name provenance.json may list as an output: a file right in the run folder. */
bool plainFileName(const std::string& name) {
    return !name.empty() && name.size() < 256 && name.find('/') == std::string::npos &&
           name != "." && name != ".." && !hasControlCharacter(name);
}

/** lstat: what the entry itself is, a link not followed. */
std::optional<struct stat> entryStatus(const std::string& path) {
    struct stat st {};
    if (::lstat(path.c_str(), &st) != 0) return std::nullopt;
    return st;
}

}  // namespace

int holdTemporaryOnSignal(const std::string& path) {
    const std::string abs = fs::absolute(path).string();  // the handler runs in any folder
    if (abs.size() >= sizeof g_temporaries[0].path) return -1;
    for (int i = 0; i < kTemporarySlots; ++i) {
        int expected = 0;
        if (g_temporaries[i].state.compare_exchange_strong(expected, 1)) {
            std::memcpy(g_temporaries[i].path, abs.c_str(), abs.size() + 1);
            g_temporaries[i].state.store(2);
            return i;
        }
    }
    return -1;
}

void releaseTemporaryOnSignal(int slot) {
    if (slot >= 0 && slot < kTemporarySlots) g_temporaries[slot].state.store(0);
}

void installSignalCleanup() {
    struct sigaction action {};
    action.sa_handler = removeStagingAndExit;
    sigemptyset(&action.sa_mask);
    sigaddset(&action.sa_mask, SIGINT);
    sigaddset(&action.sa_mask, SIGTERM);
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
}

std::string sha1OfFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error("cannot read " + path);
    boost::uuids::detail::sha1 h;
    std::array<char, 1 << 16> buf;
    while (in) {
        in.read(buf.data(), buf.size());
        if (in.gcount() > 0) h.process_bytes(buf.data(), size_t(in.gcount()));
    }
    if (in.bad()) throw Error("cannot read " + path);
    boost::uuids::detail::sha1::digest_type d;
    h.get_digest(d);
    char hex[41];
    for (int i = 0; i < 5; ++i) std::snprintf(hex + 8 * i, 9, "%08x", d[i]);
    return hex;
}

void checkRunFolderPath(const std::string& folder, const std::string& what) {
    if (folder.empty()) throw Error(what + ": the run folder's name is empty");
    if (hasControlCharacter(folder))
        throw Error(what + ": the run folder's name holds a control character (a newline?)");
    const fs::path p = fs::path(folder).lexically_normal();
    const std::string last =
        p.filename().empty() ? p.parent_path().filename().string() : p.filename().string();
    if (last.empty() || last == "." || last == ".." || p == "/" || p.filename() == "..")
        throw Error(what + ": '" + folder + "' is not a folder a run can be written to");
    std::error_code ec;
    if (fs::exists(fs::symlink_status(p, ec)) && !fs::is_directory(fs::status(p, ec)))
        throw Error(what + ": '" + pathInWords(folder) +
                    "' is a file, not a folder (a run folder is a folder mrloc writes into: give "
                    "a new name or an earlier run's folder)");
    const fs::path abs = fs::absolute(p, ec);
    const fs::path cwd = fs::current_path(ec);
    if (!ec) {
        // the folder is replaced whole on commit: never the one the user stands in
        const auto rel = cwd.lexically_relative(abs.lexically_normal());
        if (!rel.empty() && *rel.begin() != "..")
            throw Error(what + ": '" + folder +
                        "' is the current folder or one of its parents; run mrloc from outside "
                        "the run folder");
    }
}

RunTransaction::RunTransaction(const std::string& folder, const std::string& step, const Log& log)
    : folder_(folder), step_(step) {
    checkRunFolderPath(folder, "run folder " + folder);
    fs::path abs = fs::absolute(fs::path(folder).lexically_normal());
    if (abs.filename().empty()) abs = abs.parent_path();
    absFolder_ = abs.string();
    const fs::path parent = abs.parent_path();
    const std::string name = abs.filename().string();
    std::error_code ec;
    fs::create_directories(parent, ec);
    if (ec) throw Error("cannot create folder " + parent.string() + ": " + ec.message());
    lockPath_ = folderLockPath(absFolder_);
    staging_ = (parent / ("." + name + ".staging." + std::to_string(::getpid()))).string();
    lockFd_ = takeFolderLock(lockPath_, folder_);
    try {
        // What an earlier run left when it was killed: its staging folder, or the previous
        // run set aside during a swap (put back when the folder itself is missing).
        const std::string stagingPrefix = "." + name + ".staging.";
        const std::string previousPrefix = "." + name + ".previous.";
        for (const auto& e : fs::directory_iterator(parent, ec)) {
            const std::string n = e.path().filename().string();
            if (n.rfind(stagingPrefix, 0) == 0) fs::remove_all(e.path(), ec);
            if (n.rfind(previousPrefix, 0) == 0) {
                if (!fs::exists(fs::symlink_status(abs)))
                    fs::rename(e.path(), abs, ec);
                else
                    fs::remove_all(e.path(), ec);
            }
        }
        slot_ = claimLiveSlot(staging_, lockPath_, folder_);
        stageCopyOfFolder(log);
    } catch (...) {
        if (slot_ >= 0) fs::remove_all(staging_, ec);
        releaseLiveSlot(slot_);
        ::unlink(lockPath_.c_str());
        ::close(lockFd_);
        throw;
    }
}

void RunTransaction::stageCopyOfFolder(const Log& log) {
    std::error_code ec;
    const auto st = entryStatus(absFolder_);
    if (st && S_ISLNK(st->st_mode))
        throw Error("run folder " + folder_ + ": is a symbolic link; give the folder itself");
    if (st && !S_ISDIR(st->st_mode)) throw Error("run folder " + folder_ + ": not a folder");
    if (!fs::create_directory(staging_, ec) || ec)
        throw Error("cannot create " + staging_ + ": " + (ec ? ec.message() : "it exists"));
    if (!st) return;
    // A non-empty folder that no mrloc run wrote (a home folder given as --out) is refused:
    // it would be copied and then replaced.
    const bool runFolder = fs::is_regular_file(fs::symlink_status(absFolder_ + "/provenance.json"));
    size_t entries = 0, links = 0;
    for (auto it = fs::recursive_directory_iterator(absFolder_, ec);
         !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
        if (!runFolder)
            throw Error("run folder " + folder_ +
                        ": not empty and not written by mrloc (no provenance.json); choose "
                        "another --out");
        if (++entries > kMaxEntries)
            throw Error("run folder " + folder_ + ": holds more than " +
                        std::to_string(kMaxEntries) + " files");
        const fs::path rel = it->path().lexically_relative(absFolder_);
        const fs::path to = fs::path(staging_) / rel;
        const auto s = entryStatus(it->path().string());
        if (!s) continue;
        if (S_ISDIR(s->st_mode)) {
            fs::create_directory(to, ec);
            if (ec) throw Error("cannot create " + to.string() + ": " + ec.message());
        } else if (S_ISREG(s->st_mode)) {
            fs::copy_file(it->path(), to, ec);
            if (ec)
                throw Error("cannot copy " + it->path().string() +
                            " for the new run (is the "
                            "disk full?): " +
                            ec.message());
            if (rel.has_parent_path()) continue;
            if (const auto copied = entryStatus(to.string())) {
                carried_[rel.string()] = (unsigned long)copied->st_ino;
                // held open so that its inode number is not given to a file this step writes
                // after replacing it (metrics.json written twice): that file would read as
                // carried, not written. Bounded: a folder of thousands of files keeps 256.
                if (carriedFds_.size() < 256)
                    if (const int fd = ::open(to.c_str(), O_RDONLY | O_CLOEXEC); fd >= 0)
                        carriedFds_.push_back(fd);
            }
        } else {
            ++links;  // symbolic links, FIFOs, sockets, devices: never followed nor carried
        }
    }
    if (ec) throw Error("run folder " + folder_ + ": cannot list: " + ec.message());
    if (links > 0)
        log.warning("run folder " + folder_ + ": " + std::to_string(links) +
                    " symbolic link(s) or special file(s) left out of the new run (mrloc never "
                    "follows them)");
}

std::string RunTransaction::inFolderTerms(const std::string& message) const {
    std::string out = message;
    for (size_t at = out.find(staging_); at != std::string::npos;
         at = out.find(staging_, at + folder_.size()))
        out.replace(at, staging_.size(), folder_);
    return out;
}

std::vector<std::string> RunTransaction::written() const {
    std::vector<std::string> names;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(staging_, ec)) {
        const std::string n = e.path().filename().string();
        const auto s = entryStatus(e.path().string());
        if (!s || !S_ISREG(s->st_mode)) continue;
        const auto was = carried_.find(n);
        if (was == carried_.end() || was->second != (unsigned long)s->st_ino) names.push_back(n);
    }
    std::sort(names.begin(), names.end());
    return names;
}

void RunTransaction::recordOutputs() {
    const std::string path = staging_ + "/provenance.json";
    if (!fs::is_regular_file(fs::symlink_status(path))) return;
    auto p = readProvenanceFile(path);  // an object, its outputs one if present
    std::map<std::string, std::string> now;
    for (const auto& n : written())
        if (n != "provenance.json") now[n] = sha1OfFile(staging_ + "/" + n);
    // The same step's previous outputs that it did not write again: removed from the new run
    // only if still what mrloc wrote (same name in this folder, same SHA-1).
    const auto old =
        p.contains("outputs") && p["outputs"].contains(step_)
            ? p["outputs"][step_]
            : nlohmann::json();
    if (old.is_object())
        for (const auto& [name, hash] : old.items()) {
            if (now.count(name) || !plainFileName(name) || !hash.is_string()) continue;
            const std::string file = staging_ + "/" + name;
            const auto s = entryStatus(file);
            if (s && S_ISREG(s->st_mode) && sha1OfFile(file) == hash.get<std::string>())
                fs::remove(file);
        }
    if (!p.contains("outputs")) p["outputs"] = nlohmann::json::object();
    p["outputs"][step_] = now;
    saveJson(path, p);
}

void RunTransaction::commit() {
    recordOutputs();
    const fs::path abs(absFolder_);
    std::error_code ec;
    if (fs::exists(fs::symlink_status(abs))) {
        // one atomic swap: the folder is the old run or the new, never a mix or missing
        if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, absFolder_.c_str(),
                        RENAME_EXCHANGE) != 0) {
            if (errno != EINVAL && errno != ENOSYS)
                throw Error("cannot replace run folder " + folder_ + ": " + std::strerror(errno));
            // a file system without the swap: set the old run aside, then put the new in its
            // place; a kill between the two is undone by the next run (the constructor)
            const std::string previous = abs.parent_path().string() + "/." +
                                         abs.filename().string() + ".previous." +
                                         std::to_string(::getpid());
            fs::rename(abs, previous, ec);
            if (ec) throw Error("cannot replace run folder " + folder_ + ": " + ec.message());
            fs::rename(staging_, abs, ec);
            if (ec) {
                fs::rename(previous, abs);
                throw Error("cannot replace run folder " + folder_ + ": " + ec.message());
            }
            fs::rename(previous, staging_, ec);  // removed below with the staging folder
        }
    } else {
        fs::rename(staging_, abs, ec);
        if (ec) throw Error("cannot create run folder " + folder_ + ": " + ec.message());
    }
}

RunTransaction::~RunTransaction() {
    // after commit() the staging path holds the previous run; before, this one's partial
    // outputs: removed either way
    for (const int fd : carriedFds_) ::close(fd);
    removeTree(staging_.c_str());
    releaseLiveSlot(slot_);
    ::unlink(lockPath_.c_str());
    ::close(lockFd_);
}

}  // namespace mrloc::common
