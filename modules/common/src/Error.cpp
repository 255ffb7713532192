#include <mrloc/common/Error.h>
#include <mrloc/common/IniLint.h>

#include <sstream>

namespace mrloc {

std::string oneLine(const std::string& what) {
    std::string message;
    if (what.find("==== MRPT exception ====") != std::string::npos) {
        // Keep the innermost "Message:" line; without one, the lines before the location
        // and the call stack.
        std::istringstream in(what);
        std::string inner, plain;
        for (std::string line; std::getline(in, line);) {
            if (line.rfind("Message:", 0) == 0)
                inner = line.substr(8);
            else if (line.rfind("Location:", 0) == 0 || line.rfind("Call stack", 0) == 0 ||
                     line.rfind("[", 0) == 0 || line.rfind("====", 0) == 0 ||
                     line.rfind("Original exception", 0) == 0)
                continue;
            else if (inner.empty())
                plain += (plain.empty() ? "" : " ") + line;
        }
        message = inner.empty() ? plain : inner;
    }
    if (message.empty()) message = what;
    for (char& c : message)
        if (c == '\n' || c == '\r' || c == '\t') c = ' ';
    // a corrupt file's bytes quoted by MRPT (a class name read from noise) stay readable:
    // control bytes and bytes that are not UTF-8 become '?' (a path in UTF-8 is kept), and a
    // long message is cut short
    std::string clean;
    for (size_t i = 0; i < message.size();) {
        const auto c = static_cast<unsigned char>(message[i]);
        const size_t n = common::utf8Length(message, i);
        if (n > 1 || (n == 1 && c >= 0x20 && c != 0x7f))
            clean.append(message, i, n), i += n;
        else
            clean += '?', ++i;
    }
    message = clean.size() > 600 ? clean.substr(0, 600) + "..." : clean;
    const auto b = message.find_first_not_of(' ');
    const auto e = message.find_last_not_of(' ');
    return b == std::string::npos ? std::string() : message.substr(b, e - b + 1);
}

}  // namespace mrloc
