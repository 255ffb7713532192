#include <mrloc/common/Error.h>

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
            if (line.rfind("Message:", 0) == 0) inner = line.substr(8);
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
    const auto b = message.find_first_not_of(' ');
    const auto e = message.find_last_not_of(' ');
    return b == std::string::npos ? std::string() : message.substr(b, e - b + 1);
}

}  // namespace mrloc
