// Validated INI access: every kind of INI error names file, section and key.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/IniSection.h>
#include <mrpt/config/CConfigFileMemory.h>

using namespace mrloc;
using common::IniSection;

namespace {

// Runs `read` on section [s] of `text` and returns the error message ("" if none).
template <class F>
std::string errorOf(const std::string& text, F read) {
    mrpt::config::CConfigFileMemory ini(text);
    IniSection s(ini, "s");
    try {
        read(s);
        s.finish();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(IniSection, ReadsValuesAndDefaults) {
    mrpt::config::CConfigFileMemory ini(
        "[s]\nx = 2.5 // metres\nn = 7\nb = true\nw = a b\nv = 1 2 3\n");
    IniSection s(ini, "s");
    EXPECT_DOUBLE_EQ(s.real("x", 0), 2.5);
    EXPECT_DOUBLE_EQ(s.real("missing", 4.0), 4.0);
    EXPECT_EQ(s.integer("n", 0, 0, 10), 7);
    EXPECT_TRUE(s.flag("b", false));
    EXPECT_EQ(s.text("w", ""), "a b");
    EXPECT_EQ(s.reals("v", {}, 3), (std::vector<double>{1, 2, 3}));
    EXPECT_NO_THROW(s.finish());
}

TEST(IniSection, UnknownKeyIsAnError) {
    const auto e =
        errorOf("[s]\nrange_sigam = 1\n", [](IniSection& s) { s.real("range_sigma", 0); });
    EXPECT_NE(e.find("<memory>: [s] range_sigam: unknown key"), std::string::npos) << e;
}

TEST(IniSection, MissingRequiredKeyIsAnError) {
    const auto e = errorOf("[s]\n", [](IniSection& s) { s.requireReal("start"); });
    EXPECT_NE(e.find("[s] start: required key is missing"), std::string::npos) << e;
}

TEST(IniSection, WrongTypeIsAnError) {
    EXPECT_NE(errorOf("[s]\nx = abc\n", [](IniSection& s) { s.real("x", 0); })
                  .find("[s] x: expected a number, got 'abc'"),
              std::string::npos);
    EXPECT_NE(errorOf("[s]\nx = 1.5\n", [](IniSection& s) { s.integer("x", 0, 0, 9); })
                  .find("expected an integer"),
              std::string::npos);
    EXPECT_NE(errorOf("[s]\nx = maybe\n", [](IniSection& s) { s.flag("x", 0); })
                  .find("expected true or false"),
              std::string::npos);
    EXPECT_NE(errorOf("[s]\nx = nan\n", [](IniSection& s) { s.real("x", 0); }).find("finite"),
              std::string::npos);
    EXPECT_NE(errorOf("[s]\nx = 1 2\n", [](IniSection& s) { s.reals("x", {}, 3); })
                  .find("expected 3 numbers, got 2"),
              std::string::npos);
    EXPECT_NE(errorOf("[s]\nx = fast\n",
                      [](IniSection& s) {
                          s.choice("x", "a", {"a", "b"});
                      })
                  .find("'fast' is not one of: a, b"),
              std::string::npos);
}

TEST(IniSection, OutOfRangeIsAnError) {
    const auto e = errorOf("[s]\np = 1.5\n", [](IniSection& s) { s.real("p", 0.5, 0, 1); });
    EXPECT_NE(e.find("[s] p: value 1.5 is out of range [0, 1]"), std::string::npos) << e;
    EXPECT_NE(errorOf("[s]\nn = -2\n", [](IniSection& s) { s.integer("n", 0, 0, 9); })
                  .find("out of range"),
              std::string::npos);
}
