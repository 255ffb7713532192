#pragma once
// The folders mrloc writes in place of a user's name: a run folder (RunTransaction) and a
// batch folder (`mrloc batch`). Each is held by one mrloc process at a time through
// `.<name>.lock` beside it (flock, never waited for: the kernel frees it on any exit), and
// nothing in it is followed through a symbolic link (a link planted in a batch folder would
// make parallel's job log or a trial's record land anywhere).
#include <string>

namespace mrloc::common {

/** `.<name>.lock` in the folder's parent; `absFolder` absolute, without a trailing '/'. */
std::string folderLockPath(const std::string& absFolder);

/** Takes the lock file at `lockPath` without waiting and returns its descriptor; throws
 *  mrloc::Error naming `folder` when another process holds it. */
int takeFolderLock(const std::string& lockPath, const std::string& folder);

/** A folder's lock for the lifetime of this object (the folder's parent is made if missing;
 *  the folder itself need not exist). Released and its file removed on destruction. */
class FolderLock {
 public:
    explicit FolderLock(const std::string& folder);
    ~FolderLock();
    FolderLock(const FolderLock&) = delete;
    FolderLock& operator=(const FolderLock&) = delete;

 private:
    std::string path_;
    int fd_ = -1;
};

/** Throws mrloc::Error naming the entry unless `folder` itself and every entry of
 *  `relative` below it (a/b/c.json) that exists is no symbolic link, and each but the last
 *  is a folder: what is written or read there stays in the folder. */
void checkNoLinkInPath(const std::string& folder, const std::string& relative);

/** Throws mrloc::Error naming the first symbolic link, FIFO, socket or device anywhere in
 *  `folder` (`what` says which folder: "batch folder"), or when it holds more than
 *  `maxEntries` entries. */
void checkFolderHoldsNoLink(const std::string& folder, const std::string& what,
                            size_t maxEntries);

}  // namespace mrloc::common
