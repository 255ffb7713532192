#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

namespace mrloc::common {

PendingFile::PendingFile(std::string finalPath, const std::string& tempSuffix)
    : final_(std::move(finalPath)), temp_(final_ + tempSuffix) {
    const auto parent = fs::path(final_).parent_path();
    if (!parent.empty()) makeDirectories(parent.string());
}

PendingFile::~PendingFile() {
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
