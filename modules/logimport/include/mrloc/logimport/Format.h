#pragma once
// An import format: its name, what it reads, its options, and the conversion. Formats
// register themselves by name (AllFormats.cpp, one line each), as methods do.
#include <mrloc/logimport/ImportOutput.h>

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace mrloc::logimport {

struct FormatOption {
    std::string key, defaultValue, help;
};

/** A format's options as given (--opt key=value), checked against what it declares. */
class FormatOptions {
 public:
    FormatOptions(const std::string& format, const std::vector<FormatOption>& declared,
                  const std::vector<std::string>& given);
    const std::string& text(const std::string& key) const;
    double number(const std::string& key) const;
    bool flag(const std::string& key) const;
    /** A comma- or space-separated list of numbers. */
    std::vector<double> numbers(const std::string& key) const;
    bool given(const std::string& key) const { return given_.count(key) > 0; }

 private:
    std::string format_;
    std::map<std::string, std::string> values_;
    std::map<std::string, bool> given_;
};

struct ImportRequest {
    std::vector<std::string> inputs;
    FormatOptions options;
};

struct Format {
    std::string name;
    std::string summary;  ///< one line for `mrloc import --help`
    std::string inputs;   ///< what the inputs are: "<input.txt> [<gt.txt>]"
    size_t minInputs = 1, maxInputs = 1;
    std::vector<FormatOption> options;
    std::function<void(const ImportRequest&, ImportOutput&)> convert;
    /** Converted in a child process: for a reader that is not ours (a library not hardened
     *  against hostile files), so that its crash is one line and not mrloc's. */
    bool isolated = false;
};

class FormatRegistry {
 public:
    void add(Format format);
    /** Throws mrloc::Error listing the formats (and the near miss) when `name` is none. */
    const Format& get(const std::string& name) const;
    const std::map<std::string, Format>& all() const { return formats_; }

 private:
    std::map<std::string, Format> formats_;
};

/** `mrloc import --help`: the formats, their inputs and options. */
std::string formatsHelp(const FormatRegistry& registry);
/** `mrloc import <format> --help`: that format's inputs and options. */
std::string formatHelp(const Format& format);

/** The [beacons] keys every beacon INI an import writes carries for a real log (the
 *  odometry's random walk), with comments on the keys a user may want to change and why. */
std::string realLogBeaconKeys();

/** Runs `format` on the inputs into `rawlogPath`, all or nothing. */
ImportSummary runImport(const Format& format, const std::vector<std::string>& inputs,
                        const std::vector<std::string>& options, const std::string& rawlogPath);

// The formats (one file each) and the list of all of them.
void registerLibrsf(FormatRegistry& r);
void registerSonarText(FormatRegistry& r);
void registerMrclam(FormatRegistry& r);
void registerCarmen(FormatRegistry& r);
void registerRosbag(FormatRegistry& r);
void registerAllFormats(FormatRegistry& r);

}  // namespace mrloc::logimport
