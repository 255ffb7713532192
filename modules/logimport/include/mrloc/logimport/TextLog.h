#pragma once
// A text log read line by line, as every text format's importer reads its files: sizes bounded,
// numbers parsed strictly (a NaN, an infinity or trailing junk is refused), and every error one
// line naming the file and line.
#include <fstream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace mrloc::logimport {

/** The whole of `text` as a number of type T (double or long): nothing if it is not one, has
 *  trailing characters, or (a double) is not finite. The one number parser of the importers. */
template <typename T>
std::optional<T> parseNumber(std::string_view text);

class TextLog {
 public:
    static constexpr size_t kMaxFileBytes = size_t(4) << 30;  ///< 4 GiB: any dataset's file
    static constexpr size_t kMaxLineBytes = size_t(1) << 20;  ///< 1 MiB: a CARMEN scan is ~10 kB
    static constexpr size_t kMaxFields = 100000;

    /** Opens `path` (a regular file of at most kMaxFileBytes; `what` names it in errors:
     *  "librsf input"). `commentPrefix` lines are skipped ('#' for most datasets). */
    TextLog(const std::string& path, const std::string& what, char commentPrefix = '#');

    /** Advances to the next line that is neither blank nor a comment; false at the end. */
    bool next();
    const std::string& path() const { return path_; }
    size_t lineNumber() const { return lineNo_; }
    /** "file:line", as errors name a place. */
    std::string where() const;
    [[noreturn]] void fail(const std::string& message) const;

    size_t size() const { return fields_.size(); }
    std::string_view field(size_t i) const;
    /** Field i as a finite number; `name` says what it is ("range") in the error. */
    double number(size_t i, const char* name) const;
    /** Field i as an integer in [lo, hi]. */
    long integer(size_t i, const char* name, long lo, long hi) const;
    /** Refuses the line unless it has at least `n` fields; `layout` is what a line holds. */
    void expectAtLeast(size_t n, const char* layout) const;
    void expectExactly(size_t n, const char* layout) const;

 private:
    std::string path_;
    std::ifstream in_;
    std::string line_;
    std::vector<std::string_view> fields_;
    size_t lineNo_ = 0;
    char comment_;
};

/** Times that must not go back, per stream (a file's record type): the check every format
 *  runs on what it reads. */
class TimeOrder {
 public:
    /** Throws through log.fail when t is before the stream's last time. */
    void check(const TextLog& log, const std::string& stream, double t);

 private:
    std::vector<std::pair<std::string, double>> last_;
};

}  // namespace mrloc::logimport
