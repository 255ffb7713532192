#include "KeysDoc.h"

#include <mrloc/common/Error.h>

#include <algorithm>
#include <set>

namespace mrloc::app {

std::vector<common::SectionKeys> allKeyTables(const method::Registry& registry) {
    auto tables = method::frameworkKeys();
    for (const auto& name : registry.names())
        for (const auto& t : registry.get(name).keys) {
            // a method's keys of a framework section ([robot.<name>]) join its table
            const auto same = std::find_if(tables.begin(), tables.end(),
                                           [&](const auto& u) { return u.section == t.section; });
            if (same == tables.end())
                tables.push_back(t);
            else
                same->keys.insert(same->keys.end(), t.keys.begin(), t.keys.end());
        }
    return tables;
}

std::string keysText(const method::Registry& registry, const std::string& section) {
    std::string out, names;
    for (const auto& t : allKeyTables(registry)) {
        names += (names.empty() ? "" : ", ") + t.section;
        if (!section.empty() && t.section != section) continue;
        out += (out.empty() ? "" : "\n") + std::string("## [") + t.section + "]\n\n" +
               common::keysMarkdown(t);
    }
    if (out.empty())
        throw Error("no key table for section [" + section + "] (the sections with one: " + names +
                    ")");
    return out;
}

namespace {
constexpr const char* kBegin = "<!-- keys [";
constexpr const char* kEnd = "<!-- end keys -->";
}  // namespace

std::string updateKeyDoc(const method::Registry& registry, const std::string& doc) {
    const auto tables = allKeyTables(registry);
    std::set<std::string> shown;
    std::string out;
    size_t at = 0;
    for (size_t begin; (begin = doc.find(kBegin, at)) != std::string::npos;) {
        const size_t nameEnd = doc.find(']', begin);
        const size_t lineEnd = doc.find('\n', begin);
        const size_t end = doc.find(kEnd, begin);
        if (nameEnd == std::string::npos || lineEnd == std::string::npos || nameEnd > lineEnd ||
            end == std::string::npos)
            throw Error("a '" + std::string(kBegin) + "...' marker without its section or its '" +
                        kEnd + "'");
        const std::string section = doc.substr(begin + std::string(kBegin).size(),
                                               nameEnd - begin - std::string(kBegin).size());
        const common::SectionKeys* table = nullptr;
        for (const auto& t : tables)
            if (t.section == section) table = &t;
        if (!table) throw Error("the doc shows keys of [" + section + "], which has no key table");
        shown.insert(section);
        out += doc.substr(at, lineEnd + 1 - at) + common::keysMarkdown(*table) + kEnd;
        at = end + std::string(kEnd).size();
    }
    out += doc.substr(at);
    for (const auto& t : tables)
        if (!shown.count(t.section))
            throw Error("the key table of [" + t.section + "] has no '" + kBegin + t.section +
                        "] ...' marker in the doc");
    return out;
}

}  // namespace mrloc::app
