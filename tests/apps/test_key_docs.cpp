// doc/ini.md's key tables are the code's: generated from each section's common::KeyTable by
// `mrloc keys --update doc/ini.md`, and this test fails when someone edits one side only.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>

#include <fstream>
#include <sstream>

#include "AllMethods.h"
#include "KeysDoc.h"
#include "TestPaths.h"

namespace {

std::string iniDoc() {
    std::ifstream in(std::string(MRLOC_SOURCE_DIR) + "/doc/ini.md");
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
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
