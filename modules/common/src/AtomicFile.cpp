#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <vector>

namespace fs = std::filesystem;

namespace mrloc::common {

namespace {

// Paths a signal handler removes. The handler may only call async-signal-safe functions
// (unlink, rmdir, _exit), so the paths live in fixed slots claimed with atomics.
enum class SlotKind : int { Free, Claimed, Temporary, RunFile, RunDirectory };
struct CleanupSlot {
    std::atomic<int> kind{int(SlotKind::Free)};
    char path[4096];
};
constexpr int kSlots = 1024;
CleanupSlot g_slots[kSlots];
std::atomic<int> g_runDepth{0};

int claimSlot(const std::string& path, SlotKind kind) {
    if (path.size() >= sizeof g_slots[0].path) return -1;  // not removed on a signal
    for (int i = 0; i < kSlots; ++i) {
        int expected = int(SlotKind::Free);
        if (g_slots[i].kind.compare_exchange_strong(expected, int(SlotKind::Claimed))) {
            std::memcpy(g_slots[i].path, path.c_str(), path.size() + 1);
            g_slots[i].kind.store(int(kind));
            return i;
        }
    }
    return -1;
}

void releaseSlot(int slot) {
    if (slot >= 0) g_slots[slot].kind.store(int(SlotKind::Free));
}

void releaseRunSlots() {
    for (auto& slot : g_slots) {
        const int kind = slot.kind.load();
        if (kind == int(SlotKind::RunFile) || kind == int(SlotKind::RunDirectory))
            slot.kind.store(int(SlotKind::Free));
    }
}

extern "C" void removeOutputsAndExit(int sig) {
    for (auto& slot : g_slots) {
        const int kind = slot.kind.load();
        if (kind == int(SlotKind::Temporary) || kind == int(SlotKind::RunFile)) ::unlink(slot.path);
    }
    for (auto& slot : g_slots)
        if (slot.kind.load() == int(SlotKind::RunDirectory)) ::rmdir(slot.path);
    _exit(128 + sig);
}

}  // namespace

void installSignalCleanup() {
    struct sigaction action {};
    action.sa_handler = removeOutputsAndExit;
    sigemptyset(&action.sa_mask);
    sigaddset(&action.sa_mask, SIGINT);
    sigaddset(&action.sa_mask, SIGTERM);
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
}

namespace {
std::mutex g_committedLock;
std::vector<std::string> g_committed;  ///< files committed while a RunOutputs lives
}  // namespace

RunOutputs::RunOutputs(const std::string& createdDir) {
    {
        std::lock_guard<std::mutex> lock(g_committedLock);
        first_ = g_committed.size();
    }
    ++g_runDepth;
    if (!createdDir.empty()) claimSlot(createdDir, SlotKind::RunDirectory);
}

RunOutputs::~RunOutputs() {
    if (--g_runDepth == 0) {
        releaseRunSlots();
        std::lock_guard<std::mutex> lock(g_committedLock);
        g_committed.clear();
    }
}

std::vector<std::string> RunOutputs::committed() const {
    std::lock_guard<std::mutex> lock(g_committedLock);
    return {g_committed.begin() + long(std::min(first_, g_committed.size())), g_committed.end()};
}

PendingFile::PendingFile(std::string finalPath, const std::string& tempSuffix)
    : final_(std::move(finalPath)), temp_(final_ + tempSuffix) {
    const auto parent = fs::path(final_).parent_path();
    if (!parent.empty()) makeDirectories(parent.string());
    slot_ = claimSlot(temp_, SlotKind::Temporary);
}

PendingFile::~PendingFile() {
    releaseSlot(slot_);
    if (!committed_) {
        std::error_code ec;
        fs::remove(temp_, ec);
    }
}

void PendingFile::commit() {
    std::error_code ec;
    fs::rename(temp_, final_, ec);
    if (ec) throw Error("cannot rename " + temp_ + " to " + final_ + ": " + ec.message());
    committed_ = true;
    releaseSlot(slot_);
    slot_ = -1;
    if (g_runDepth > 0) {
        claimSlot(final_, SlotKind::RunFile);  // released by RunOutputs
        std::lock_guard<std::mutex> lock(g_committedLock);
        g_committed.push_back(final_);
    }
}

void writeFileAtomically(const std::string& path, const std::string& content) {
    PendingFile file(path);
    {
        std::ofstream out(file.tempPath(), std::ios::binary);
        if (!out) throw Error("cannot write " + file.tempPath());
        out << content;
        out.close();
        if (!out) throw Error("error while writing " + file.tempPath());
    }
    file.commit();
}

void makeDirectories(const std::string& dir) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw Error("cannot create directory " + dir + ": " + ec.message());
}

}  // namespace mrloc::common
