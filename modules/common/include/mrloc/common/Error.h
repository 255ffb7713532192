#pragma once
// The one exception type of mrloc: what went wrong and where (file, section, key, line...).
#include <stdexcept>
#include <string>

namespace mrloc {

class Error : public std::runtime_error {
 public:
    explicit Error(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace mrloc
