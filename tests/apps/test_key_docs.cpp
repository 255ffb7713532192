// doc/ini.md's key tables are the code's: generated from each section's common::KeyTable by
// `mrloc keys --update doc/ini.md`, and this test fails when someone edits one side only.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>

#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "AllMethods.h"
#include "KeysDoc.h"
#include "TestPaths.h"

namespace {

std::string docText(const std::string& name) {
    std::ifstream in(std::string(MRLOC_SOURCE_DIR) + "/doc/" + name);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

std::string iniDoc() { return docText("ini.md"); }

/** Every number a text holds ("at most 1e7 voxels", "16 to 100000", "1 .. 1e5"). */
std::set<double> numbersIn(const std::string& text) {
    static const std::regex number(R"((^|[^0-9A-Za-z_.])([0-9]+(\.[0-9]+)?(e[0-9]+)?))");
    std::set<double> out;
    for (std::sregex_iterator it(text.begin(), text.end(), number), end; it != end; ++it)
        out.insert(std::stod((*it)[2].str()));
    return out;
}

mrloc::method::Registry allMethods() {
    mrloc::method::Registry registry;
    mrloc::app::registerAllMethods(registry);
    return registry;
}

}  // namespace

TEST(KeyDocs, DocIniMdShowsEveryKeyTableAsTheCodeDeclaresIt) {
    const auto registry = allMethods();
    const std::string doc = iniDoc();
    ASSERT_FALSE(doc.empty());
    const std::string generated = mrloc::app::updateKeyDoc(registry, doc);
    EXPECT_TRUE(generated == doc)
        << "doc/ini.md's key tables differ from the code's: run `build/apps/mrloc/mrloc keys "
           "--update doc/ini.md` (or `cmake --build build --target ini-doc`) and review the diff";
    // every table is there: the sections that moved to a key table, the framework's first
    for (const char* section : {"report", "polymap", "omnivision", "formation", "framesync"})
        EXPECT_NE(doc.find("<!-- keys [" + std::string(section) + "]"), std::string::npos)
            << section;
}

TEST(KeyDocs, AKeyTheCodeDeclaresIsInTheDocWithItsDefaultUnitAndRange) {
    const std::string doc = iniDoc();
    // a few rows as the code declares them: a bound from another key, an angle in degrees,
    // a sub-seed, a word list
    EXPECT_NE(doc.find("| `pair_gap` | `1` | m | `erp_baseline` .. 100 |"), std::string::npos);
    EXPECT_NE(doc.find("| `cone_margin` | `5` | deg | 0 .. 90 |"), std::string::npos);
    EXPECT_NE(doc.find("| `swarm_seed` | (drawn from the run's seed) |"), std::string::npos);
    EXPECT_NE(doc.find("| `camera` | `render` |  | render, bearings |"), std::string::npos);
}

TEST(KeyDocs, AMarkerForASectionWithoutATableOrATableWithoutAMarkerIsNamed) {
    const auto registry = allMethods();
    const std::string doc = iniDoc();
    try {
        mrloc::app::updateKeyDoc(registry, doc + "\n<!-- keys [nosuch] x -->\n<!-- end keys -->\n");
        FAIL() << "an unknown section was accepted";
    } catch (const mrloc::Error& e) {
        EXPECT_STREQ(e.what(), "the doc shows keys of [nosuch], which has no key table");
    }
    try {
        mrloc::app::updateKeyDoc(registry, "# no tables\n");
        FAIL() << "a doc without the tables was accepted";
    } catch (const mrloc::Error& e) {
        EXPECT_NE(std::string(e.what()).find("has no '<!-- keys ["), std::string::npos) << e.what();
    }
    EXPECT_THROW(mrloc::app::updateKeyDoc(registry, "<!-- keys [report] no end\n"), mrloc::Error);
}

// doc/errors.md's table of upper bounds says why each is there; its numbers must be the key
// tables' (a bound changed in the code and not in the doc fails here).
TEST(KeyDocs, EveryBoundErrorsMdGivesIsTheKeyTablesRange) {
    const auto tables = mrloc::app::allKeyTables(allMethods());
    const std::string doc = docText("errors.md");
    const size_t from = doc.find("### Upper bounds on sizes and counts");
    ASSERT_NE(from, std::string::npos);
    std::istringstream rows(doc.substr(from, doc.find("\n## ", from) - from));
    // a row naming keys: | `[section] key`, `key` | bound | why |
    static const std::regex keyRow(
        R"(^\| `\[([a-z_.<>]+)\] ([a-z_<>]+)`((, `[a-z_<>]+`)*) \| ([^|]*) \|)");
    static const std::regex moreKeys("`([a-z_<>]+)`");
    size_t checked = 0;
    for (std::string row; std::getline(rows, row);) {
        std::smatch m;
        if (!std::regex_search(row, m, keyRow)) continue;
        const std::string section = m[1];
        std::vector<std::string> keys{m[2]};
        const std::string rest = m[3];
        for (std::sregex_iterator it(rest.begin(), rest.end(), moreKeys), end; it != end; ++it)
            keys.push_back((*it)[1]);
        std::set<double> declared;
        for (const auto& t : tables)
            if (t.section == section)
                for (const auto& k : t.keys)
                    for (const auto& key : keys)
                        if (k.name == key) {
                            const auto n = numbersIn(k.range);
                            declared.insert(n.begin(), n.end());
                        }
        ASSERT_FALSE(declared.empty()) << "errors.md names [" << section << "] " << keys[0]
                                       << ", which no key table declares with a range";
        for (const double bound : numbersIn(m[5].str()))
            EXPECT_TRUE(declared.count(bound))
                << "errors.md gives " << bound << " for [" << section << "] " << keys[0]
                << "; its key table's range is " << ::testing::PrintToString(declared);
        ++checked;
    }
    EXPECT_GE(checked, 15u);  // the rows above: a regex that matched none would pass
}
