// A key table: each key declared once gives loading with bounds, effective.ini and the docs.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/KeyTable.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <cmath>

using namespace mrloc;

namespace {

enum class Shape { Round, Square };

struct Toy {
    double length = 2.5;             // m
    double angle = 30 * M_PI / 180;  // rad; deg in the INI
    double reach = 4;                // m, at least `length`
    size_t count = 7;
    bool on = true;
    Shape shape = Shape::Round;
    std::string note;
    common::SubSeed seed;

    static const common::KeyTable<Toy>& keys() {
        static const auto table =
            common::KeyTable<Toy>("toy")
                .real("length", MRLOC_KEY_FIELD(length), {0.1, 10}, "m", "how long")
                .degrees("angle", MRLOC_KEY_FIELD(angle), {0, 90}, "how steep")
                .real("reach", MRLOC_KEY_FIELD(reach), {"length", 100}, "m", "how far")
                .integer("count", MRLOC_KEY_FIELD(count), 1, 100, "", "how many")
                .flag("on", MRLOC_KEY_FIELD(on), "whether")
                .choice("shape", MRLOC_KEY_FIELD(shape),
                        std::vector<std::pair<std::string, Shape>>{{"round", Shape::Round},
                                                                   {"square", Shape::Square}},
                        "which")
                .text("note", MRLOC_KEY_FIELD(note), "free text")
                .savedOnlyIf([](const Toy& t) { return !t.note.empty(); })
                .subSeed("seed", MRLOC_KEY_FIELD(seed), "toy draws", "the toy's seed");
        return table;
    }
};

/** Loads [toy] of `text`; the error message, or "" and `out` set. */
std::string load(const std::string& text, Toy& out) {
    mrpt::config::CConfigFileMemory ini(text);
    common::IniSection s(ini, "toy");
    try {
        Toy::keys().load(s, out);
        s.finish();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

std::string saved(const Toy& t) {
    mrpt::config::CConfigFileMemory out;
    Toy::keys().save(t, out, "toy");
    return out.getContent();
}

}  // namespace

TEST(KeyTable, AbsentKeysKeepTheStructsDefaultsAndGivenOnesAreConverted) {
    Toy t;
    ASSERT_EQ(load("[toy]\nangle = 45\ncount = 3\nshape = square\n", t), "");
    EXPECT_EQ(t.length, 2.5);               // the member initializer, untouched
    EXPECT_EQ(t.angle, 45 * (M_PI / 180));  // as mrpt::DEG2RAD computes it
    EXPECT_EQ(t.count, 3u);
    EXPECT_EQ(t.shape, Shape::Square);
    EXPECT_TRUE(t.on);
    // the seed absent: drawn from the run's seed ([scenario] seed absent: 1), not given
    EXPECT_FALSE(t.seed.given);
    EXPECT_EQ(t.seed.value, common::drawSeed(1, "toy draws"));
}

TEST(KeyTable, BoundsTypesAndUnknownKeysAreOneLineNamingTheKey) {
    Toy t;
    EXPECT_EQ(load("[toy]\nlength = 11\n", t),
              "<memory>: [toy] length: value 11 is out of range [0.1, 10]");
    EXPECT_EQ(load("[toy]\nangle = 91\n", t),
              "<memory>: [toy] angle: value 91 is out of range [0, 90]");
    EXPECT_EQ(load("[toy]\ncount = 2.5\n", t),
              "<memory>: [toy] count: expected an integer, got '2.5'");
    EXPECT_EQ(load("[toy]\nshape = oval\n", t),
              "<memory>: [toy] shape: 'oval' is not one of: round, square");
    EXPECT_EQ(load("[toy]\nlenght = 1\n", t),
              "<memory>: [toy] lenght: unknown key (did you mean 'length'? see doc/ini.md)");
    // a bound that is another key: reach at least length, the value read
    Toy u;
    EXPECT_EQ(load("[toy]\nlength = 5\nreach = 4\n", u),
              "<memory>: [toy] reach: value 4 is out of range [5, 100]");
    Toy w;
    EXPECT_EQ(load("[toy]\nlength = 3\nreach = 4\n", w), "");
}

// MRPT's write of a double keeps 6 decimals (1e-7 became "0.000000"): effective.ini must give
// back the very value the member held, in the INI's shortest words where they do.
TEST(KeyTable, EffectiveIniGivesBackEveryDigit) {
    for (const char* given :
         {"0.2000000000001", "1.23456789", "2.5000000001", "9.87654321098765"}) {
        Toy t;
        ASSERT_EQ(load(std::string("[toy]\nlength = 0.2\nreach = ") + given + "\n", t), "");
        Toy back;
        ASSERT_EQ(load(saved(t), back), "") << saved(t);
        EXPECT_EQ(back.reach, t.reach) << given << " -> " << saved(t);
    }
    // an angle read in degrees comes back to the radian it was, and reads as typed
    for (const char* given : {"0.1", "33.3", "89.99999999999", "1e-5"}) {
        Toy t;
        ASSERT_EQ(load(std::string("[toy]\nangle = ") + given + "\n", t), "");
        Toy back;
        ASSERT_EQ(load(saved(t), back), "") << saved(t);
        EXPECT_EQ(back.angle, t.angle) << given << " -> " << saved(t);
    }
    Toy t;
    ASSERT_EQ(load("[toy]\nlength = 0.2\nangle = 33.3\nreach = 1.23456789\n", t), "");
    EXPECT_NE(saved(t).find("angle = 33.3\n"), std::string::npos) << saved(t);
    EXPECT_NE(saved(t).find("reach = 1.23456789\n"), std::string::npos) << saved(t);
}

TEST(KeyTable, SavesInDeclaredOrderAndLoadsBackTheSame) {
    Toy t;
    ASSERT_EQ(load("[toy]\nangle = 45\nnote = hi\nseed = 9\n", t), "");
    const std::string text = saved(t);
    EXPECT_EQ(text,
              "[toy]\nlength = 2.5\nangle = 45\nreach = 4\ncount = 7\n"
              "on = true\nshape = round\nnote = hi\nseed = 9\n");
    Toy back;
    ASSERT_EQ(load(text, back), "");
    EXPECT_EQ(saved(back), text);
    // a note left empty and a seed not given are left out of effective.ini
    EXPECT_EQ(saved(Toy{}).find("note"), std::string::npos);
    EXPECT_EQ(saved(Toy{}).find("seed"), std::string::npos);
}

TEST(KeyTable, TheDocsShowDefaultsUnitsAndRangesFromTheDeclaration) {
    const auto docs = Toy::keys().docs();
    ASSERT_EQ(docs.section, "toy");
    ASSERT_EQ(docs.keys.size(), 8u);
    EXPECT_EQ(docs.keys[0].defaultText, "2.5");
    EXPECT_EQ(docs.keys[0].range, "0.1 .. 10");
    EXPECT_EQ(docs.keys[1].defaultText, "30");
    EXPECT_EQ(docs.keys[1].unit, "deg");
    EXPECT_EQ(docs.keys[2].range, "`length` .. 100");
    EXPECT_EQ(docs.keys[5].range, "round, square");
    EXPECT_EQ(docs.keys[6].defaultText, "(none)");
    EXPECT_EQ(docs.keys[7].defaultText, "(drawn from the run's seed)");
    const std::string md = common::keysMarkdown(docs);
    EXPECT_NE(md.find("| `length` | `2.5` | m | 0.1 .. 10 | how long |"), std::string::npos) << md;
    EXPECT_NE(md.find("| `note` | (none) |  |  | free text |"), std::string::npos) << md;
}

TEST(KeyTable, NumbersAndRangesReadAsOneWouldTypeThem) {
    EXPECT_EQ(common::keyNumberText(1.7e9), "1.7e9");
    EXPECT_EQ(common::keyNumberText(1e-4), "0.0001");
    EXPECT_EQ(common::keyNumberText(1e-9), "1e-9");
    EXPECT_EQ(common::keyNumberText(0.05), "0.05");
    EXPECT_EQ(common::keyNumberText(100000), "1e5");
    EXPECT_EQ(common::keyNumberText(1000), "1000");
    EXPECT_EQ(common::keyNumberText(242.5), "242.5");
    EXPECT_EQ(common::keyNumberText(-0.5), "-0.5");
    EXPECT_EQ(common::keyNumberText(4294967295.0), "4294967295");
    EXPECT_EQ(common::keyRangeText(0, common::IniSection::kInf), "at least 0");
    EXPECT_EQ(common::keyRangeText(-common::IniSection::kInf, 5), "at most 5");
    EXPECT_EQ(common::keyRangeText(-common::IniSection::kInf, common::IniSection::kInf), "");
}
