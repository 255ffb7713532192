// The one JSON reader (issue 51, item 2): every file mrloc reads is bounded in size and
// nesting, read through no link, and its keys' types are checked, each refusal one line
// naming the file.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/JsonFile.h>
#include <mrloc/common/Metrics.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;
using namespace mrloc;
using common::JsonType;

namespace {

std::string tempFile(const std::string& name, const std::string& text) {
    const std::string path = testing::TempDir() + "/json_" + name;
    fs::remove(path);
    std::ofstream(path) << text;
    return path;
}

/** The message of the mrloc::Error `f` throws, or "" when it throws none. */
template <class F>
std::string errorOf(F f) {
    try {
        f();
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
        return e.what();
    }
    return "";
}

std::string nested(size_t depth) { return std::string(depth, '[') + std::string(depth, ']'); }

}  // namespace

TEST(JsonFile, NestingBoundedBeforeTheTreeIsBuilt) {
    // 32 levels pass (mrloc's own files nest 6), 33 are refused; 300,000 (the crash of
    // `mrloc report`: SIGSEGV in the recursive dump) are refused as fast
    EXPECT_EQ(common::parseJson(nested(32), "a").dump().size(), 64u);
    EXPECT_EQ(errorOf([] { common::parseJson(nested(33), "x.json"); }),
              "x.json: JSON nested more than 32 levels deep");
    const std::string deep = tempFile("deep", "{\"warnings\": " + nested(300000) + "}");
    EXPECT_EQ(errorOf([&] { common::readJsonFile(deep); }),
              deep + ": JSON nested more than 32 levels deep");
    EXPECT_EQ(errorOf([] { common::parseJson(nested(4), "y", {1000, 3}); }),
              "y: JSON nested more than 3 levels deep");
}

TEST(JsonFile, SizeLinksAndSpecialFilesRefusedNamingTheFile) {
    const std::string ok = tempFile("ok", R"({"a": [1, 2], "b": "x"})");
    EXPECT_EQ(common::readJsonFile(ok)["a"][1], 2);
    EXPECT_EQ(errorOf([&] { common::readJsonFile(ok, {10, 32}); }),
              ok + ": 23 bytes, more than the 10 a JSON file may hold here");
    const std::string link = testing::TempDir() + "/json_link";
    fs::remove(link);
    fs::create_symlink(ok, link);
    EXPECT_EQ(errorOf([&] { common::readJsonFile(link); }),
              link + ": a symbolic link (mrloc reads no JSON file through a link)");
    const std::string fifo = testing::TempDir() + "/json_fifo";
    fs::remove(fifo);
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    EXPECT_EQ(errorOf([&] { common::readJsonFile(fifo); }),
              fifo + ": not a regular file (a FIFO or a device?)");
    EXPECT_EQ(errorOf([&] { common::readJsonFile(testing::TempDir()); }),
              testing::TempDir() + ": a folder, not a JSON file");
    const std::string bad = tempFile("bad", "{\"a\": ");
    EXPECT_EQ(errorOf([&] { common::readJsonFile(bad); }).rfind(bad + ": not valid JSON: ", 0), 0u);
}

TEST(JsonFile, TypesOfTheKeysReadersUseAreChecked) {
    const auto j = nlohmann::json::parse(R"({"method": "beacons", "robots": {"r": {}},
        "headline": {"reached": true, "figures": []}})");
    EXPECT_EQ(errorOf([&] {
                  common::checkJsonShape(j, {{"/method", JsonType::String}, {"/missing", JsonType::Array},
                                     {"/headline/reached", JsonType::Boolean}},
                                 "m.json");
              }),
              "");
    EXPECT_EQ(errorOf([&] { common::checkJsonShape(j, {{"/method", JsonType::Number}}, "m.json"); }),
              "m.json: /method is a string, expected a number");
    EXPECT_EQ(errorOf([&] {
                  common::checkJsonShape(j, {{"/headline/figures", JsonType::Object}}, "m.json");
              }),
              "m.json: /headline/figures is an array, expected an object");
    EXPECT_EQ(errorOf([&] { common::checkJsonShape(j, {{"/method/x", JsonType::Number}}, "m.json"); }),
              "m.json: /method is a string, expected an object");
    EXPECT_EQ(errorOf([] { common::checkJsonShape(nlohmann::json::array(), {}, "m.json"); }),
              "m.json: an array, expected a JSON object");

    // metrics.json as report and index read it
    const std::string metrics =
        tempFile("metrics", R"({"method": "beacons", "robots": {"r1": 5}})");
    EXPECT_EQ(errorOf([&] { common::readMetricsFile(metrics); }),
              metrics + ": /robots/r1 is not an object (a robot's errors)");
    const std::string warnings = tempFile("warnings", R"({"warnings": {"a": 1}})");
    EXPECT_EQ(errorOf([&] { common::readMetricsFile(warnings); }),
              warnings + ": /warnings is an object, expected an array");
    const std::string provenance = tempFile("provenance", R"({"simulated": "yes"})");
    EXPECT_EQ(errorOf([&] { common::readProvenanceFile(provenance); }),
              provenance + ": /simulated is a string, expected true or false");
}
