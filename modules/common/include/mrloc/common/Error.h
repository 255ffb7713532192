#pragma once
// The one exception type of mrloc: what went wrong and where (file, section, key, line...).
#include <stdexcept>
#include <string>

namespace mrloc {

class Error : public std::runtime_error {
 public:
    explicit Error(const std::string& what) : std::runtime_error(what) {}
};

/** An exception's text on one line. MRPT's exceptions span many lines (a banner, nested
 *  "Message:" lines, a location and a call stack); of those the innermost message is kept. */
std::string oneLine(const std::string& what);

}  // namespace mrloc
