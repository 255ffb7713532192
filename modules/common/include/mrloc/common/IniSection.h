#pragma once
// Validated access to one INI section on top of mrpt::config::CConfigFileBase.
//
// MRPT's read_* functions fall back silently (read_int("x") of "abc" is 0). Here every value
// is parsed strictly and range-checked, and finish() rejects keys nobody asked for, so a
// misspelt key stops the run with a message naming file, section and key.
#include <mrpt/config/CConfigFileBase.h>

#include <limits>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace mrloc::common {

/** Name of the file behind a config source ("<memory>" for a CConfigFileMemory). */
std::string configOrigin(const mrpt::config::CConfigFileBase& cfg);

class IniSection {
 public:
    static constexpr double kInf = std::numeric_limits<double>::infinity();

    IniSection(const mrpt::config::CConfigFileBase& cfg, std::string section);

    const std::string& section() const { return section_; }
    /** The whole file (a key that depends on another section's: the run's seed). */
    const mrpt::config::CConfigFileBase& config() const { return cfg_; }
    bool has(const std::string& key) const;

    double real(const std::string& key, double def, double lo = -kInf, double hi = kInf);
    double requireReal(const std::string& key, double lo = -kInf, double hi = kInf);
    long integer(const std::string& key, long def, long lo, long hi);
    bool flag(const std::string& key, bool def);
    std::string text(const std::string& key, const std::string& def);
    std::string requireText(const std::string& key);
    /** One of a fixed set of words. */
    std::string choice(const std::string& key, const std::string& def,
                       const std::vector<std::string>& options);
    /** Whitespace-separated reals; `count` 0 means any number. */
    std::vector<double> reals(const std::string& key, std::vector<double> def, size_t count = 0);
    std::vector<double> requireReals(const std::string& key, size_t count = 0);

    /** This key is accepted by finish(): another reader owns it (a method's key in
     *  [robot.<name>]). */
    void allowKey(const std::string& key);
    /** Keys beginning with this prefix are accepted by finish() (e.g. "beacon_"). */
    void allowPrefix(const std::string& prefix) { prefixes_.push_back(prefix); }
    /** Keys `<prefix><id>` with a non-negative integer id, by id (the prefix is allowed;
     *  a key with the prefix and anything else after it is an error). */
    std::map<int, std::string> numberedKeys(const std::string& prefix);
    /** All keys present in the section, as written. */
    std::vector<std::string> keys() const;
    /** Throws mrloc::Error if the section holds a key that was never read nor allowed. */
    void finish() const;

    [[noreturn]] void fail(const std::string& key, const std::string& problem) const;

 private:
    std::optional<std::string> raw(const std::string& key);
    double parseReal(const std::string& key, const std::string& value) const;

    const mrpt::config::CConfigFileBase& cfg_;
    std::string section_;
    std::string origin_;
    std::set<std::string> used_;  // lower case: MRPT's INI keys are case-insensitive
    std::vector<std::string> prefixes_;
};

}  // namespace mrloc::common
