#include <mrloc/common/Error.h>
#include <mrloc/common/IniLint.h>

#include <algorithm>
#include <cctype>
#include <map>
#include <sstream>

namespace mrloc::common {

size_t utf8Length(const std::string& s, size_t i) {
    const auto c = static_cast<unsigned char>(s[i]);
    // Continuation bytes that follow the lead byte c (4: not a lead byte).
    const size_t n = c < 0x80           ? 0
                     : (c >> 5) == 0x6  ? 1
                     : (c >> 4) == 0xE  ? 2
                     : (c >> 3) == 0x1E ? 3
                                        : 4;
    if (n == 4 || (n == 1 && c < 0xC2) || i + n >= s.size()) return 0;
    unsigned cp = n == 0 ? c : n == 1 ? (c & 0x1F) : n == 2 ? (c & 0x0F) : (c & 0x07);
    for (size_t k = 1; k <= n; ++k) {
        const auto d = static_cast<unsigned char>(s[i + k]);
        if ((d >> 6) != 0x2) return 0;
        cp = (cp << 6) | (d & 0x3F);
    }
    // No overlong forms, no surrogates, nothing past U+10FFFF.
    if ((n == 2 && cp < 0x800) || (n == 3 && (cp < 0x10000 || cp > 0x10FFFF)) ||
        (cp >= 0xD800 && cp <= 0xDFFF))
        return 0;
    return n + 1;
}

bool isUtf8(const std::string& s) {
    for (size_t i = 0; i < s.size();) {
        const size_t n = utf8Length(s, i);
        if (n == 0) return false;
        i += n;
    }
    return true;
}

namespace {

std::string trim(const std::string& s) {
    const auto b = s.find_first_not_of(" \t\r");
    if (b == std::string::npos) return "";
    return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

bool isComment(const std::string& t) { return t[0] == '#' || t[0] == ';' || t.rfind("//", 0) == 0; }

}  // namespace

void lintIni(const std::string& text, const std::string& origin,
             const std::function<bool(const std::string&)>& checked) {
    auto fail = [&](size_t line, const std::string& problem) {
        throw Error(origin + ":" + std::to_string(line) + ": " + problem);
    };
    if (const auto nul = text.find('\0'); nul != std::string::npos)
        fail(size_t(std::count(text.begin(), text.begin() + long(nul), '\n')) + 1,
             "a NUL byte (MRPT's parser would silently drop the rest of the file)");

    std::string section;                      // current section, as written
    bool checking = checked("");              // lines before the first section
    std::map<std::string, size_t> firstLine;  // "section\nkey" (lower case) -> line
    std::istringstream in(text);
    std::string raw;
    size_t lineNo = 0;
    while (std::getline(in, raw)) {
        const size_t start = ++lineNo;
        // MRPT joins a line ending in '\' with the next one.
        std::string t = trim(raw);
        for (std::string next; !t.empty() && t.back() == '\\' && std::getline(in, next);) {
            ++lineNo;
            t.pop_back();
            t = trim(t + next);
        }
        if (t.empty()) continue;
        if (t[0] == '[') {
            const auto close = t.find(']');
            if (close == std::string::npos)
                fail(start, "'" + t + "': a section header without its closing ']'");
            section = trim(t.substr(1, close - 1));
            checking = checked(section);
            if (checking && !isUtf8(section)) fail(start, "the section name is not valid UTF-8");
            continue;
        }
        if (!checking || isComment(t) || t[0] == '@') continue;
        if (!isUtf8(t)) fail(start, "[" + section + "]: bytes that are not valid UTF-8");
        const auto eq = t.find('=');
        if (eq == std::string::npos)
            fail(start, "[" + section + "]: '" + t + "' is not key = value (missing '=')");
        const std::string key = trim(t.substr(0, eq));
        if (key.empty()) fail(start, "[" + section + "]: '" + t + "' has no key before '='");
        const auto [it, fresh] = firstLine.emplace(lower(section) + "\n" + lower(key), start);
        if (!fresh)
            fail(start, "[" + section + "] " + key + ": given twice (first at line " +
                            std::to_string(it->second) + "); MRPT would keep the last silently");
    }
}

}  // namespace mrloc::common
