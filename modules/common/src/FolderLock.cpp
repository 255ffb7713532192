#include <fcntl.h>
#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/FolderLock.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

namespace fs = std::filesystem;

namespace mrloc::common {

std::string folderLockPath(const std::string& absFolder) {
    const fs::path abs(absFolder);
    return (abs.parent_path() / ("." + abs.filename().string() + ".lock")).string();
}

int takeFolderLock(const std::string& path, const std::string& folder) {
    for (int attempt = 0; attempt < 8; ++attempt) {
        const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0644);
        if (fd < 0)
            throw Error("folder " + folder + ": cannot create its lock " + path + ": " +
                        std::strerror(errno));
        if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
            ::close(fd);
            throw Error("folder " + folder + ": in use by another mrloc process (its lock " +
                        path + " is held); wait for it or choose another --out");
        }
        // the file is checked to be the one at `path` after locking: a holder that just
        // finished unlinks it
        struct stat held {
        }, now{};
        if (::fstat(fd, &held) == 0 && ::lstat(path.c_str(), &now) == 0 &&
            held.st_ino == now.st_ino && held.st_dev == now.st_dev)
            return fd;
        ::close(fd);  // unlinked by its last holder meanwhile: take the new one
    }
    throw Error("folder " + folder + ": cannot take its lock " + path);
}

FolderLock::FolderLock(const std::string& folder) {
    fs::path abs = fs::absolute(fs::path(folder).lexically_normal());
    if (abs.filename().empty()) abs = abs.parent_path();
    makeDirectories(abs.parent_path().string());
    path_ = folderLockPath(abs.string());
    fd_ = takeFolderLock(path_, folder);
}

FolderLock::~FolderLock() {
    ::unlink(path_.c_str());
    ::close(fd_);
}

namespace {

const char* kindOf(mode_t mode) {
    if (S_ISLNK(mode)) return "a symbolic link";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISSOCK(mode)) return "a socket";
    return "a device";
}

}  // namespace

void checkNoLinkInPath(const std::string& folder, const std::string& relative) {
    fs::path at(folder);
    struct stat st {};
    if (::lstat(folder.c_str(), &st) == 0 && !S_ISDIR(st.st_mode))
        throw Error(folder + ": " + (S_ISLNK(st.st_mode) ? "a symbolic link" : "not a folder") +
                    " (mrloc writes into the folder itself, never through a link)");
    const fs::path rel(relative);
    for (auto part = rel.begin(); part != rel.end(); ++part) {
        at /= *part;
        if (::lstat(at.c_str(), &st) != 0) return;  // missing: made by the writer
        const bool last = std::next(part) == rel.end();
        if (S_ISLNK(st.st_mode) || (!last && !S_ISDIR(st.st_mode)))
            throw Error(at.string() + ": " +
                        (S_ISLNK(st.st_mode) ? "a symbolic link" : "not a folder") +
                        " in the folder mrloc writes (mrloc follows no link out of it)");
    }
}

void checkFolderHoldsNoLink(const std::string& folder, const std::string& what,
                            size_t maxEntries) {
    checkNoLinkInPath(folder, "");
    std::error_code ec;
    size_t entries = 0;
    // the iterator does not follow links into folders (no follow_directory_symlink)
    for (auto it = fs::recursive_directory_iterator(folder, ec);
         !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
        if (++entries > maxEntries)
            throw Error(what + " " + folder + ": holds more than " + std::to_string(maxEntries) +
                        " entries");
        struct stat st {};
        if (::lstat(it->path().c_str(), &st) != 0) continue;
        if (!S_ISDIR(st.st_mode) && !S_ISREG(st.st_mode))
            throw Error(it->path().string() + ": " + kindOf(st.st_mode) + " in the " + what +
                        " (it holds mrloc's files only; remove it)");
    }
    if (ec) throw Error(what + " " + folder + ": cannot list: " + ec.message());
}

}  // namespace mrloc::common
