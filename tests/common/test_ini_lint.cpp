// The INI line checks: what MRPT's parser would silently change is refused with file and
// line; what MRPT's own INIs hold (continued lines, @define, sections of MRPT's apps) passes.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/IniLint.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "TestPaths.h"

using namespace mrloc;

namespace {

/** The app's rule: lines before any section and lower-case sections are mrloc's. */
bool ours(const std::string& section) {
    return section.empty() || std::islower(static_cast<unsigned char>(section[0]));
}

/** The error lintIni gives, or "" if it accepts the text. */
std::string lint(const std::string& text) {
    try {
        common::lintIni(text, "x.ini", ours);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(IniLint, AcceptsCommentsContinuationsDirectivesAndMrptSections) {
    EXPECT_EQ(lint("# c\n; c\n// c\n\n[scenario]\nname = a  // why\n"
                   "robots = r1 \\\n  r2\n@define X 1\n"
                   "[CMultiObjectiveMotionOptimizerBase]\nvar x : y\nvar x : y\nno equals here\n"),
              "");
}

TEST(IniLint, RefusesWhatMrptWouldSilentlyChange) {
    EXPECT_EQ(lint(std::string("[scenario]\nname = a # x\0y\n", 26)),
              "x.ini:2: a NUL byte (MRPT's parser would silently drop the rest of the file)");
    EXPECT_EQ(lint("[polymap]\nheading 45\n"),
              "x.ini:2: [polymap]: 'heading 45' is not key = value (missing '=')");
    // Keys are case-insensitive in MRPT, and a section may be opened twice.
    EXPECT_EQ(lint("[polymap]\nHeading = 1\n[world]\n[polymap]\nheading = 2\n"),
              "x.ini:5: [polymap] heading: given twice (first at line 2); MRPT would keep the "
              "last silently");
    EXPECT_EQ(lint("[polymap\nx = 1\n"),
              "x.ini:1: '[polymap': a section header without its "
              "closing ']'");
    EXPECT_EQ(lint("[scenario]\nname = q\xe9\n"),
              "x.ini:2: [scenario]: bytes that are not valid UTF-8");
    EXPECT_EQ(lint("[scenario]\n = 3\n"), "x.ini:2: [scenario]: '= 3' has no key before '='");
    // A line continued onto the next is reported at its first line.
    EXPECT_EQ(lint("[a]\nk = 1 \\\n 2\nk = 3\n"),
              "x.ini:4: [a] k: given twice (first at line 2); MRPT would keep the last silently");
}

TEST(IniLint, Utf8Validation) {
    EXPECT_TRUE(common::isUtf8("plain ascii"));
    EXPECT_TRUE(common::isUtf8("\xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80"));  // é € 😀
    EXPECT_FALSE(common::isUtf8("\xe9"));                                   // Latin-1 é
    EXPECT_FALSE(common::isUtf8("\xc0\xaf"));                               // overlong '/'
    EXPECT_FALSE(common::isUtf8("\xed\xa0\x80"));                           // a surrogate
    EXPECT_FALSE(common::isUtf8("\xe2\x82"));                               // cut short
    EXPECT_FALSE(common::isUtf8("\xf4\x90\x80\x80"));                       // past U+10FFFF
}

TEST(IniLint, EveryIniOfMrptAndOfMrlocPasses) {
    // MRPT's example INIs run unchanged: nothing in them trips the checks of our sections.
    size_t n = 0;
    for (const auto& root :
         {std::string("/usr/share/mrpt/config_files"), std::string(MRLOC_SOURCE_DIR) + "/config"}) {
        ASSERT_TRUE(std::filesystem::is_directory(root)) << root;
        for (const auto& e : std::filesystem::recursive_directory_iterator(root)) {
            if (e.path().extension() != ".ini") continue;
            std::ifstream in(e.path(), std::ios::binary);
            std::stringstream text;
            text << in.rdbuf();
            EXPECT_NO_THROW(common::lintIni(text.str(), e.path().string(), ours)) << e.path();
            ++n;
        }
    }
    EXPECT_GT(n, 90u);  // 101 here: 90 of MRPT's, 11 of mrloc's own
}
