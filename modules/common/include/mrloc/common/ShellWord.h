#pragma once
// Where mrloc writes shell for a user to run or copy (a Slurm script, a command list, the
// command line in an imported beacon map's comment), every user string goes through this.
#include <cctype>
#include <cstring>
#include <string>

namespace mrloc::common {

/** `text` as one word of a POSIX shell: single-quoted, a quote as '\''; a control character
 *  (a newline would end a comment line) as its printable escape. */
inline std::string shellWord(const std::string& text) {
    std::string out = "'";
    for (const char c : text) {
        if (c == '\'')
            out += "'\\''";
        else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
            out += "'$'\\x" + std::string(1, "0123456789abcdef"[(c >> 4) & 15]) +
                   "0123456789abcdef"[c & 15] + "''";
        else
            out += c;
    }
    return out + "'";
}

/** `text` as a shell word for a line a user reads and may copy ("next: mrloc report out/x"):
 *  as it is when a shell would take it whole, else shellWord's quoting. */
inline std::string shellArgument(const std::string& text) {
    if (text.empty()) return "''";
    for (const char c : text)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || std::strchr("_-./+:=,@%", c)))
            return shellWord(text);
    return text;
}

}  // namespace mrloc::common
