#pragma once
// Outputs are written to "<name>.tmp" and renamed when complete, so that an error or a crash
// never leaves a half-written file under the final name.
#include <string>
#include <vector>

namespace mrloc::common {

/** Writes `content` to `path` atomically (temporary name, then rename). */
void writeFileAtomically(const std::string& path, const std::string& content);

/** Holds a temporary path; commit() renames it to the final path, otherwise the destructor
 *  removes it. */
class PendingFile {
 public:
    /** The temporary name is finalPath + tempSuffix; give it the final extension when the
     *  writer picks the format by extension (e.g. ".tmp.png" for CImage::saveToFile). */
    explicit PendingFile(std::string finalPath, const std::string& tempSuffix = ".tmp");
    ~PendingFile();
    PendingFile(const PendingFile&) = delete;
    PendingFile& operator=(const PendingFile&) = delete;

    const std::string& tempPath() const { return temp_; }
    const std::string& finalPath() const { return final_; }
    void commit();

 private:
    std::string final_, temp_;
    bool committed_ = false;
    int slot_ = -1;  // the signal handler's entry for temp_ (or for final_ inside a run)
};

/** Installs SIGINT and SIGTERM handlers that remove every temporary of a live PendingFile,
 *  the files a guarded run committed so far and the directory it created (RunOutputs), then
 *  exit with 128 + the signal (130, 143). */
void installSignalCleanup();

/** While one of these lives, files committed by PendingFile belong to a command that has
 *  not finished: a signal removes them too. `createdDir`, if not empty, is the command's
 *  output folder, made by it, removed (if empty) after its files on a signal. Removing them
 *  on an error is the caller's job (the app's OutputGuard). */
class RunOutputs {
 public:
    explicit RunOutputs(const std::string& createdDir = "");
    ~RunOutputs();
    RunOutputs(const RunOutputs&) = delete;
    RunOutputs& operator=(const RunOutputs&) = delete;
    /** The final paths of the files committed since this one was made. */
    std::vector<std::string> committed() const;

 private:
    size_t first_ = 0;
};

/** Creates a directory and its parents; an error names the directory. */
void makeDirectories(const std::string& dir);

}  // namespace mrloc::common
