#include <mrloc/common/KeyTable.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>

#include <cmath>
#include <cstdlib>
#include <regex>

namespace mrloc::common {

std::string keyNumberText(double x) {
    if (!std::isfinite(x)) return mrpt::format("%g", x);
    // 12 digits: an angle read in degrees and kept in radians shows as 30, not 29.999...96
    x = std::strtod(mrpt::format("%.12g", x).c_str(), nullptr);
    // the shortest text that reads back as x, with and without an exponent; the exponent
    // form ("1.7e9", "1e-9") only when it is clearly shorter ("1000" stays as it is)
    std::string exponent, plain;
    for (int p = 1; p <= 17 && exponent.empty(); ++p) {
        const std::string t = mrpt::format("%.*e", p - 1, x);
        if (std::strtod(t.c_str(), nullptr) == x) exponent = t;
    }
    for (int d = 0; d <= 17 && plain.empty(); ++d) {
        const std::string t = mrpt::format("%.*f", d, x);
        if (std::strtod(t.c_str(), nullptr) == x) plain = t;
    }
    // "1.70e+09" -> "1.7e9", "1e-09" -> "1e-9"
    static const std::regex form("^(-?[0-9]+)(\\.[0-9]*[1-9])?0*e([+-])0*([0-9]+)$");
    std::smatch m;
    if (std::regex_match(exponent, m, form))
        exponent = m[1].str() + m[2].str() + "e" + (m[3] == "-" ? "-" : "") + m[4].str();
    if (plain.empty() || exponent.size() + 2 < plain.size()) return exponent;
    return plain;
}

std::string keyValueText(double member, double (*toMember)(double), double (*toIni)(double)) {
    const double ini = toIni ? toIni(member) : member;
    const auto readsBack = [&](const std::string& text) {
        const double x = std::strtod(text.c_str(), nullptr);
        return (toMember ? toMember(x) : x) == member;
    };
    std::string text = keyNumberText(ini);
    for (int digits = 13; digits <= 17 && !readsBack(text) && std::isfinite(ini); ++digits)
        text = mrpt::format("%.*g", digits, ini);
    return text;
}

std::string keyDegreesText(double radians) {
    // 12 digits, not every digit: a pose's angle does not read back bit for bit whatever the
    // text (CPose2D wraps it to (-pi, pi], CPose3D keeps a rotation matrix), and "30" gives
    // the pose "30" gave, where "29.99999999999999" would not
    return keyNumberText(mrpt::RAD2DEG(radians));
}

std::string keyListText(const std::vector<double>& values) {
    std::string out;
    for (const double x : values) out += (out.empty() ? "" : " ") + keyValueText(x);
    return out;
}

std::vector<double> readKeyList(IniSection& s, const std::string& name, std::vector<double> def,
                                const KeyList& list, bool whole, const std::string& unit) {
    const auto v = s.reals(name, std::move(def));
    if (v.size() > list.most) s.fail(name, "at most " + std::to_string(list.most) + " values");
    if (v.size() < list.least)
        s.fail(name, list.least == 1 ? std::string("give at least one value")
                                     : "give at least " + std::to_string(list.least) + " values");
    for (const double x : v)
        if (!(x >= list.lo && x <= list.hi) || (whole && x != std::floor(x)))
            s.fail(name, std::string("each value must be ") + (whole ? "a whole number " : "") +
                             "from " + keyNumberText(list.lo) + " to " + keyNumberText(list.hi) +
                             (unit.empty() ? "" : " " + unit));
    return v;
}

std::string keyRangeText(double lo, double hi, const std::string& loKey, const std::string& hiKey) {
    const bool hasLo = !loKey.empty() || std::isfinite(lo);
    const bool hasHi = !hiKey.empty() || std::isfinite(hi);
    const std::string l = loKey.empty() ? keyNumberText(lo) : "`" + loKey + "`";
    const std::string h = hiKey.empty() ? keyNumberText(hi) : "`" + hiKey + "`";
    if (hasLo && hasHi) return l + " .. " + h;
    if (hasLo) return "at least " + l;
    if (hasHi) return "at most " + h;
    return "";
}

namespace {
/** A table cell: a '|' would end it. */
std::string cell(const std::string& s) {
    std::string out;
    for (const char c : s) out += c == '|' ? std::string("\\|") : std::string(1, c);
    return out;
}
}  // namespace

std::string keysMarkdown(const SectionKeys& keys) {
    std::string out =
        "| key | default | unit | range | meaning |\n| --- | --- | --- | --- | --- |\n";
    for (const auto& k : keys.keys) {
        // a value in backquotes; words in parentheses, or text already quoted, as they are
        const bool word = !k.defaultText.empty() && k.defaultText.front() != '(' &&
                          k.defaultText.find('`') == std::string::npos;
        out += "| `" + cell(k.name) + "` | " +
               (word ? "`" + cell(k.defaultText) + "`" : cell(k.defaultText)) + " | " +
               cell(k.unit) + " | " + cell(k.range) + " | " + cell(k.doc) + " |\n";
    }
    return out;
}

}  // namespace mrloc::common
