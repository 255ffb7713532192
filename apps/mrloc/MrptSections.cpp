#include "MrptSections.h"

#include <mrloc/common/MrptKeys.h>
#include <mrloc/common/Names.h>

#include <map>
#include <regex>

namespace mrloc::app {

const std::vector<MrptKey>& mrptKeysRead() {
    static const std::vector<MrptKey> table = [] {
        std::vector<MrptKey> keys;
        for (const auto& k : common::mrpt_ini::kAll) keys.push_back({k.section, k.name, k.readBy});
        return keys;
    }();
    return table;
}

std::vector<std::string> mrptKeyWarnings(const mrpt::config::CConfigFileBase& ini,
                                         const std::string& iniPath) {
    std::map<std::string, std::vector<std::string>> read;  // section -> keys mrloc reads
    for (const auto& k : mrptKeysRead()) read[k.section].push_back(k.key);
    std::vector<std::string> warnings;
    for (const auto& [section, keys] : read) {
        if (!ini.sectionExists(section)) continue;
        std::vector<std::string> present;
        ini.getAllKeys(section, present);
        for (const auto& key : present) {
            // a numbered family's key is the pattern with NNN for its three digits
            const std::string asPattern = std::regex_replace(key, std::regex("[0-9]{3}"), "NNN");
            bool known = false;
            for (const auto& k : keys)
                known = known || k == key || (k.find("NNN") != std::string::npos && k == asPattern);
            if (known) continue;
            if (const auto near = common::nearMiss(asPattern, keys))
                warnings.push_back(
                    iniPath + ": [" + section + "] " + common::printable(key) +
                    ": not a key mrloc reads, so its default is used (did you mean " + *near +
                    "? mrloc keys mrpt lists what mrloc reads here)");
        }
    }
    return warnings;
}

std::string mrptKeysText() {
    std::string out =
        "Keys mrloc reads from MRPT's sections (the rest of those sections belong to MRPT's\n"
        "apps, pf-localization and ro-localization, and mrloc leaves them to them; a key within\n"
        "an edit or two of one below is a warning with \"did you mean\"):\n";
    std::string section;
    for (const auto& k : mrptKeysRead()) {
        if (k.section != section) out += "[" + (section = k.section) + "]\n";
        out += "  " + k.key + std::string(k.key.size() < 18 ? 18 - k.key.size() : 1, ' ') +
               k.readBy + "\n";
    }
    return out;
}

}  // namespace mrloc::app
