#pragma once
// A command's writes into a run folder, as one transaction.
//
// The step writes into a staging folder beside the run folder (`.<name>.staging.<pid>`), which
// starts as a copy of the folder's regular files (a `localize` after a `simulate` finds the
// rawlog; the user's notes are carried along). Only commit() replaces the folder, in one
// rename (renameat2 RENAME_EXCHANGE): until then the previous run is untouched, whatever
// happens to this one (an error, a full disk, SIGINT, SIGTERM or SIGKILL). A folder is held
// by one mrloc process at a time (`.<name>.lock`, flock: the kernel releases it on any exit).
//
// What a step deletes is only what it wrote itself: provenance.json records each step's
// outputs with their SHA-1, and a stale output (a robot fewer) is removed from the staging copy
// only when its name is a plain file name and its content is still what mrloc wrote. Nothing
// is ever followed through a symbolic link: links are not carried into the staging copy.
#include <mrloc/common/Log.h>

#include <map>
#include <string>
#include <vector>

namespace mrloc::common {

/** A run folder name a user or a file may give: refused (mrloc::Error naming `what`) when it
 *  is empty, `.`, `..`, or holds a control character; the folder may not be the current
 *  working folder or one of its parents (the transaction replaces the folder). */
void checkRunFolderPath(const std::string& folder, const std::string& what);

class RunTransaction {
 public:
    /** Locks `folder` for `step` ("simulate", "localize", "report", "run"), removes what an
     *  earlier killed run left beside it, and stages a copy of its regular files. Throws
     *  mrloc::Error (naming the folder) when another mrloc holds it, when it is a
     *  non-empty folder that no mrloc run wrote (no provenance.json), or when it is too large
     *  to stage (over kMaxEntries entries). Links and special files are left out of the new
     *  run, with a warning to `log`. */
    RunTransaction(const std::string& folder, const std::string& step,
                   const Log& log = silentLog());
    /** Without commit(): the staging folder is removed and the folder left as it was. */
    ~RunTransaction();
    RunTransaction(const RunTransaction&) = delete;
    RunTransaction& operator=(const RunTransaction&) = delete;

    /** Where the step writes (an absolute path). */
    const std::string& staging() const { return staging_; }
    /** The run folder the step's outputs go to on commit(), as given. */
    const std::string& folder() const { return folder_; }
    /** `message` with the staging folder's path written as the run folder's (for errors:
     *  the user knows the folder, not where it was staged). */
    std::string inFolderTerms(const std::string& message) const;
    /** The names of the files this step wrote so far (new, or replaced since it began). */
    std::vector<std::string> written() const;
    /** Records the outputs in provenance.json (if the step wrote one), removes the stale
     *  outputs of the same step's previous run, and puts the staging folder in place. */
    void commit();

    static constexpr size_t kMaxEntries = 100000;  ///< files a run folder may hold

 private:
    void stageCopyOfFolder(const Log& log);
    void recordOutputs();

    std::string folder_, step_, absFolder_, staging_, lockPath_;
    int lockFd_ = -1;
    int slot_ = -1;
    std::map<std::string, unsigned long> carried_;  ///< name -> inode of the staged copy
    std::vector<int> carriedFds_;  ///< the staged copies, open: their inodes stay theirs
};

/** Installs SIGINT and SIGTERM handlers that remove every live transaction's staging folder
 *  and lock file, then exit with 128 + the signal (130, 143). */
void installSignalCleanup();

/** Registers a temporary path (a file, or a folder with what it holds) that the SIGINT /
 *  SIGTERM handler removes while it is held: what an interrupted import or trial would
 *  otherwise leave (x.rawlog.tmp, a trial's scratch folder). Returns the slot for
 *  releaseTemporaryOnSignal, or -1 when all kTemporarySlots are held (then the path is left
 *  to its owner's destructor, as before). */
int holdTemporaryOnSignal(const std::string& path);
void releaseTemporaryOnSignal(int slot);
inline constexpr int kTemporarySlots = 64;

/** SHA-1 of a file's bytes, in hex (provenance's record of what mrloc wrote). */
std::string sha1OfFile(const std::string& path);

}  // namespace mrloc::common
