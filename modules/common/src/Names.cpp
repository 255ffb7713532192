#include <mrloc/common/Error.h>
#include <mrloc/common/Names.h>

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

}  // namespace mrloc::common
