#include <mrloc/common/Error.h>
#include <mrloc/common/Names.h>

#include <algorithm>
#include <cctype>

#include <cstdio>

namespace mrloc::common {

namespace {

bool nameCharacter(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '-';
}

}  // namespace

std::string printable(const std::string& s) {
    std::string out;
    for (const char c : s) {
        const auto u = static_cast<unsigned char>(c);
        if (u >= 0x20 && u < 0x7f) {
            out += c;
        } else {
            char hex[8];
            std::snprintf(hex, sizeof hex, "\\x%02x", u);
            out += hex;
        }
    }
    return out;
}

bool isRobotName(const std::string& name) {
    if (name.empty() || name.size() > kMaxNameLength || name.front() == '-') return false;
    for (const char c : name)
        if (!nameCharacter(c)) return false;
    return true;
}

void checkRobotName(const std::string& name, const std::string& where) {
    if (!isRobotName(name))
        throw Error(where + ": robot name '" + printable(name) +
                    "' is not a name (1 to 64 of A-Z a-z 0-9 _ -, not starting with '-')");
}

void checkName(const std::string& name, const std::string& where) {
    bool ok = !name.empty() && name.size() <= kMaxNameLength && nameCharacter(name.front()) &&
              name.front() != '-';
    for (const char c : name) ok = ok && (nameCharacter(c) || c == '.');
    if (!ok)
        throw Error(where + ": '" + printable(name) +
                    "' is not a name (1 to 64 of A-Z a-z 0-9 _ - ., starting with a letter, a "
                    "digit or '_')");
}

SensorLabel parseSensorLabel(const std::string& label) {
    const auto dot = label.find('.');
    if (dot == std::string::npos) return {"robot", label};
    return {label.substr(0, dot), label.substr(dot + 1)};
}

void checkSensorLabel(const std::string& label, const std::string& where) {
    for (const char c : label)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
            throw Error(where + ": sensor label '" + printable(label) +
                        "' holds a control character");
    if (label.size() > 4 * kMaxNameLength)
        throw Error(where + ": sensor label of " + std::to_string(label.size()) +
                    " bytes, more than the " + std::to_string(4 * kMaxNameLength) + " allowed");
    if (label.find('.') == std::string::npos) return;
    const auto robot = parseSensorLabel(label).robot;
    if (!isRobotName(robot))
        throw Error(where + ": sensor label '" + printable(label) + "': its robot part '" +
                    printable(robot) +
                    "' is not a robot name (1 to 64 of A-Z a-z 0-9 _ -, not starting with '-')");
}

size_t editDistance(const std::string& a, const std::string& b) {
    const auto lower = [](char c) { return char(std::tolower(static_cast<unsigned char>(c))); };
    std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
    for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
    for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
    for (size_t i = 1; i <= a.size(); ++i)
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t cost = lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1;
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
            if (i > 1 && j > 1 && lower(a[i - 1]) == lower(b[j - 2]) &&
                lower(a[i - 2]) == lower(b[j - 1]))
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
        }
    return d[a.size()][b.size()];
}

std::optional<std::string> nearMiss(const std::string& word,
                                    const std::vector<std::string>& candidates) {
    if (word.size() > 256) return std::nullopt;  // a stranger's long word: no quadratic table
    std::optional<std::string> best;
    size_t bestDistance = SIZE_MAX;
    for (const auto& c : candidates) {
        const size_t allowed = c.size() >= 6 ? 2 : 1;
        const size_t d = editDistance(word, c);
        if (d <= allowed && d < bestDistance) best = c, bestDistance = d;
    }
    return best;
}

}  // namespace mrloc::common
