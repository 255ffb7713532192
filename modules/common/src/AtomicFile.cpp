#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/RunTransaction.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

namespace mrloc::common {

PendingFile::PendingFile(std::string finalPath, const std::string& tempSuffix)
    : final_(std::move(finalPath)), temp_(final_ + tempSuffix) {
    const auto parent = fs::path(final_).parent_path();
    if (!parent.empty()) makeDirectories(parent.string());
    std::error_code ec;
    fs::remove(temp_, ec);  // a link or a stale temporary at the name: never written through
    if (ec) throw Error("cannot write " + final_ + ": cannot clear " + temp_ + ": " + ec.message());
    signalSlot_ = holdTemporaryOnSignal(temp_);
}

PendingFile::~PendingFile() {
    if (!committed_) {
        std::error_code ec;
        fs::remove(temp_, ec);
    }
    releaseTemporaryOnSignal(signalSlot_);
}

void PendingFile::commit() {
    std::error_code ec;
    fs::rename(temp_, final_, ec);
    if (ec) throw Error("cannot rename " + temp_ + " to " + final_ + ": " + ec.message());
    releaseTemporaryOnSignal(signalSlot_);
    signalSlot_ = -1;
    committed_ = true;
}

void writeFileAtomically(const std::string& path, const std::string& content) {
    PendingFile file(path);
    {
        std::ofstream out(file.tempPath(), std::ios::binary);
        if (!out) throw Error("cannot write " + path + ": " + std::strerror(errno));
        out << content;
        out.close();
        if (!out) throw Error("cannot write " + path + " (is the disk full?)");
    }
    file.commit();
}

void makeDirectories(const std::string& dir) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw Error("cannot create directory " + dir + ": " + ec.message());
}

std::string pathInWords(const std::string& path) {
    std::error_code ec;
    if (path.empty() || fs::path(path).is_absolute()) return path;
    const fs::path abs = fs::absolute(path, ec);
    return ec ? path : path + " (" + abs.lexically_normal().string() + ")";
}

std::string pathFromIni(const std::string& iniPath, const std::string& path) {
    std::error_code ec;
    if (path.empty() || !fs::path(path).is_relative() || !fs::is_regular_file(iniPath, ec))
        return path;
    return (fs::path(iniPath).parent_path() / path).lexically_normal().string();
}

void checkReadableFile(const std::string& path, const std::string& what, size_t maxBytes) {
    std::error_code ec;
    const auto st = fs::status(path, ec);
    if (ec || !fs::exists(st)) throw Error(what + " " + pathInWords(path) + ": no such file");
    if (fs::is_directory(st))
        throw Error(what + " " + pathInWords(path) + ": is a folder, not a file");
    if (!fs::is_regular_file(st))
        throw Error(what + " " + path + ": not a regular file (a FIFO or a device?)");
    const auto size = fs::file_size(path, ec);
    if (ec) throw Error(what + " " + path + ": cannot read: " + ec.message());
    if (size > maxBytes)
        throw Error(what + " " + path + ": " + std::to_string(size) + " bytes, more than the " +
                    std::to_string(maxBytes) + " allowed");
}

}  // namespace mrloc::common
