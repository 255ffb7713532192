#pragma once
// Outputs are written to "<name>.tmp" and renamed when complete, so that an error or a crash
// never leaves a half-written file under the final name. Inside a run folder the whole step
// is a transaction besides (RunTransaction.h).
#include <string>

namespace mrloc::common {

/** Writes `content` to `path` atomically (temporary name, then rename); every write is
 *  checked, and an error (a full disk) names the file. */
void writeFileAtomically(const std::string& path, const std::string& content);

/** Holds a temporary path; commit() renames it to the final path, otherwise the destructor
 *  removes it. Whatever was at the temporary name (a symbolic link, say) is removed first,
 *  so nothing is ever written through a link; the rename replaces a link at the final name
 *  rather than following it. */
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
    /** The temporary's slot in the SIGINT / SIGTERM clean-up (holdTemporaryOnSignal): an
     *  interrupted command leaves no "<name>.tmp" behind. */
    int signalSlot_ = -1;
};

/** Creates a directory and its parents; an error names the directory. */
void makeDirectories(const std::string& dir);

/** A path as an error shows it: a relative one with the absolute path it resolved to,
 *  "maps/x.poly (/home/u/maps/x.poly)", so that a file looked for in the wrong folder says
 *  which folder; an absolute one as it is. */
std::string pathInWords(const std::string& path);

/** A path named in an INI: a relative one is taken from the INI's folder (so that the INI
 *  works from any folder, as MRPT's apps read theirs), when `iniPath` is a file. */
std::string pathFromIni(const std::string& iniPath, const std::string& path);

/** Throws mrloc::Error naming `what` unless `path` is a regular file (not a folder, FIFO or
 *  device) of at most `maxBytes` bytes: checked before a user's file is read. */
void checkReadableFile(const std::string& path, const std::string& what, size_t maxBytes);

}  // namespace mrloc::common
