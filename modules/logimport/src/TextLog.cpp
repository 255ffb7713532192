#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/Names.h>
#include <mrloc/logimport/TextLog.h>

#include <charconv>
#include <cmath>
#include <type_traits>

namespace mrloc::logimport {

TextLog::TextLog(const std::string& path, const std::string& what, char commentPrefix)
    : path_(path), comment_(commentPrefix) {
    common::checkReadableFile(path, what, kMaxFileBytes);
    in_.open(path, std::ios::binary);
    if (!in_) throw Error(common::pathInWords(path) + ": cannot open the " + what);
}

std::string TextLog::where() const { return path_ + ":" + std::to_string(lineNo_); }

void TextLog::fail(const std::string& message) const { throw Error(where() + ": " + message); }

bool TextLog::next() {
    for (;;) {
        line_.clear();
        fields_.clear();
        // read by hand so that a line longer than the bound is refused before it is held whole
        char c;
        bool any = false;
        while (in_.get(c)) {
            any = true;
            if (c == '\n') break;
            if (line_.size() >= kMaxLineBytes)
                throw Error(path_ + ":" + std::to_string(lineNo_ + 1) + ": a line longer than " +
                            std::to_string(kMaxLineBytes) + " bytes");
            line_.push_back(c);
        }
        if (!any) return false;
        ++lineNo_;
        if (!line_.empty() && line_.back() == '\r') line_.pop_back();  // files written on Windows
        for (const char ch : line_)
            if (ch == '\0' || (static_cast<unsigned char>(ch) < 32 && ch != '\t'))
                fail("a control character (not a text file?)");
        size_t i = 0;
        while (i < line_.size()) {
            while (i < line_.size() && (line_[i] == ' ' || line_[i] == '\t')) ++i;
            const size_t start = i;
            while (i < line_.size() && line_[i] != ' ' && line_[i] != '\t') ++i;
            if (i > start) {
                if (fields_.size() == kMaxFields)
                    fail("more than " + std::to_string(kMaxFields) + " fields");
                fields_.emplace_back(line_.data() + start, i - start);
            }
        }
        if (fields_.empty() || fields_[0][0] == comment_) continue;
        return true;
    }
}

std::string_view TextLog::field(size_t i) const {
    if (i >= fields_.size())
        fail("field " + std::to_string(i + 1) + " is missing (the line is cut short?)");
    return fields_[i];
}

template <typename T>
std::optional<T> parseNumber(std::string_view text) {
    T v{};
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (text.empty() || ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
    if constexpr (std::is_floating_point_v<T>)
        if (!std::isfinite(v)) return std::nullopt;
    return v;
}
template std::optional<double> parseNumber<double>(std::string_view);
template std::optional<long> parseNumber<long>(std::string_view);

double TextLog::number(size_t i, const char* name) const {
    const std::string_view f = field(i);
    if (const auto v = parseNumber<double>(f)) return *v;
    double any = 0;  // a number that is not finite, or not a number: say which
    const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), any);
    if (ec == std::errc() && end == f.data() + f.size())
        fail(std::string(name) + " (field " + std::to_string(i + 1) + ") is not finite");
    fail(std::string(name) + " (field " + std::to_string(i + 1) + ") is '" +
         common::printable(std::string(f.substr(0, 40))) + "', not a number");
}

long TextLog::integer(size_t i, const char* name, long lo, long hi) const {
    const std::string_view f = field(i);
    const auto v = parseNumber<long>(f);
    if (!v)
        fail(std::string(name) + " (field " + std::to_string(i + 1) + ") is '" +
             common::printable(std::string(f.substr(0, 40))) + "', not an integer");
    if (*v < lo || *v > hi)
        fail(std::string(name) + " (field " + std::to_string(i + 1) + ") is " + std::to_string(*v) +
             ", outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return *v;
}

void TextLog::expectAtLeast(size_t n, const char* layout) const {
    if (fields_.size() < n)
        fail(std::to_string(fields_.size()) + " fields where " + std::to_string(n) +
             " are needed (" + layout + "): the line is cut short?");
}

void TextLog::expectExactly(size_t n, const char* layout) const {
    if (fields_.size() != n)
        fail(std::to_string(fields_.size()) + " fields where " + std::to_string(n) +
             " are expected (" + layout + ")");
}

void TimeOrder::check(const TextLog& log, const std::string& stream, double t) {
    for (auto& [name, last] : last_)
        if (name == stream) {
            if (t < last)
                log.fail("time goes back, from " + std::to_string(last) + " to " +
                         std::to_string(t) + " s (" + stream + ")");
            last = t;
            return;
        }
    last_.emplace_back(stream, t);
}

}  // namespace mrloc::logimport
