#include <mrloc/common/Error.h>
#include <mrloc/common/IniSection.h>
#include <mrloc/common/Names.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/system/string_utils.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace mrloc::common {


std::map<int, std::string> IniSection::numberedKeys(const std::string& prefix) {
    allowPrefix(prefix);
    std::map<int, std::string> out;
    for (const auto& key : keys()) {
        if (mrpt::system::lowerCase(key).rfind(prefix, 0) != 0) continue;
        const std::string idText = key.substr(prefix.size());
        char* end = nullptr;
        const long id = std::strtol(idText.c_str(), &end, 10);
        if (idText.empty() || *end != '\0' || id < 0 || id > (1L << 30))
            fail(key, "expected " + prefix + "<id> with a non-negative integer id");
        out[int(id)] = key;
    }
    return out;
}

void IniSection::allowKey(const std::string& key) { used_.insert(mrpt::system::lowerCase(key)); }

std::string configOrigin(const mrpt::config::CConfigFileBase& cfg) {
    if (auto* f = dynamic_cast<const mrpt::config::CConfigFile*>(&cfg))
        return f->getAssociatedFile();
    return "<memory>";
}

IniSection::IniSection(const mrpt::config::CConfigFileBase& cfg, std::string section)
    : cfg_(cfg), section_(std::move(section)), origin_(configOrigin(cfg)) {}

void IniSection::fail(const std::string& key, const std::string& problem) const {
    throw Error(origin_ + ": [" + section_ + "] " + key + ": " + problem);
}

bool IniSection::has(const std::string& key) const { return cfg_.keyExists(section_, key); }

std::optional<std::string> IniSection::raw(const std::string& key) {
    used_.insert(mrpt::system::lowerCase(key));
    if (!has(key)) return std::nullopt;
    // Inline comments after the value are MRPT convention ("x = 1 // metres").
    std::string v = cfg_.read_string(section_, key, "", false);
    for (const char* marker : {"//", "#"}) {
        if (auto p = v.find(marker); p != std::string::npos) v.erase(p);
    }
    return mrpt::system::trim(v);
}

double IniSection::parseReal(const std::string& key, const std::string& value) const {
    const char* begin = value.c_str();
    char* end = nullptr;
    const double x = std::strtod(begin, &end);
    if (value.empty() || end == begin || *end != '\0')
        fail(key, "expected a number, got '" + value + "'");
    if (!std::isfinite(x)) fail(key, "expected a finite number, got '" + value + "'");
    return x;
}

static std::string rangeText(double lo, double hi) {
    std::ostringstream s;
    s << "[" << lo << ", " << hi << "]";
    return s.str();
}

double IniSection::real(const std::string& key, double def, double lo, double hi) {
    const auto v = raw(key);
    if (!v) return def;
    const double x = parseReal(key, *v);
    if (x < lo || x > hi) fail(key, "value " + *v + " is out of range " + rangeText(lo, hi));
    return x;
}

double IniSection::requireReal(const std::string& key, double lo, double hi) {
    if (!has(key)) fail(key, "required key is missing");
    return real(key, 0.0, lo, hi);
}

long IniSection::integer(const std::string& key, long def, long lo, long hi) {
    const auto v = raw(key);
    if (!v) return def;
    char* end = nullptr;
    const long x = std::strtol(v->c_str(), &end, 10);
    if (v->empty() || *end != '\0') fail(key, "expected an integer, got '" + *v + "'");
    if (x < lo || x > hi)
        fail(key, "value " + *v + " is out of range " + rangeText(double(lo), double(hi)));
    return x;
}

bool IniSection::flag(const std::string& key, bool def) {
    const auto v = raw(key);
    if (!v) return def;
    const std::string s = mrpt::system::lowerCase(*v);
    if (s == "true" || s == "1" || s == "yes" || s == "on") return true;
    if (s == "false" || s == "0" || s == "no" || s == "off") return false;
    fail(key, "expected true or false, got '" + *v + "'");
}

std::string IniSection::text(const std::string& key, const std::string& def) {
    const auto v = raw(key);
    return v ? *v : def;
}

std::string IniSection::requireText(const std::string& key) {
    const auto v = raw(key);
    if (!v || v->empty()) fail(key, "required key is missing");
    return *v;
}

std::string IniSection::choice(const std::string& key, const std::string& def,
                               const std::vector<std::string>& options) {
    const std::string v = text(key, def);
    if (std::find(options.begin(), options.end(), v) != options.end()) return v;
    std::string list;
    for (const auto& o : options) list += (list.empty() ? "" : ", ") + o;
    fail(key, "'" + v + "' is not one of: " + list);
}

std::vector<double> IniSection::reals(const std::string& key, std::vector<double> def,
                                      size_t count) {
    const auto v = raw(key);
    if (!v) return def;
    std::vector<double> out;
    std::istringstream in(*v);
    for (std::string tok; in >> tok;) out.push_back(parseReal(key, tok));
    if (count != 0 && out.size() != count)
        fail(key, "expected " + std::to_string(count) + " numbers, got " +
                      std::to_string(out.size()) + " ('" + *v + "')");
    return out;
}

std::vector<double> IniSection::requireReals(const std::string& key, size_t count) {
    if (!has(key)) fail(key, "required key is missing");
    return reals(key, {}, count);
}

std::vector<std::string> IniSection::keys() const {
    std::vector<std::string> keys;
    cfg_.getAllKeys(section_, keys);
    return keys;
}

void IniSection::finish() const {
    for (const auto& key : keys()) {
        const std::string k = mrpt::system::lowerCase(key);
        if (used_.count(k)) continue;
        const bool allowed = std::any_of(prefixes_.begin(), prefixes_.end(), [&](const auto& p) {
            return k.rfind(mrpt::system::lowerCase(p), 0) == 0;
        });
        if (!allowed) {
            // every key the section's reader asked for, present or not
            const auto near = nearMiss(k, std::vector<std::string>(used_.begin(), used_.end()));
            fail(key, near ? "unknown key (did you mean '" + *near + "'? see doc/ini.md)"
                           : "unknown key (misspelt? see doc/ini.md for the keys of this section)");
        }
    }
}

}  // namespace mrloc::common
