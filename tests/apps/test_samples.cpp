// rawlogs/: one small sample per method with its ground truth (rawlogs/README.md). Each is what
// the simulator makes today from its INI (byte for byte, truth included), each localizes with
// that INI to its headline, and MRPT's own rawlog-edit reads each as mrloc info does.
#include <gtest/gtest.h>
#include <mrloc/common/Metrics.h>

#include <nlohmann/json.hpp>
#include <regex>

#include "MrlocCli.h"
#include "TestPaths.h"

namespace fs = std::filesystem;
using namespace mrloc;
using namespace mrloc::testing_cli;

namespace {

struct Sample {
    std::string ini;                  // config/<ini>.ini, the sample rawlogs/<ini>.rawlog
    std::vector<std::string> robots;  // each with rawlogs/<ini>.<robot>.gt.txt
};

const std::vector<Sample> kSamples{{"quickstart", {"r1"}},
                                   {"polymap_steps148", {"r1"}},
                                   {"omnivision_5robots", {"A", "B", "C", "D", "E"}},
                                   {"formation_pixel", {"dr", "f1", "f2", "f3", "f4"}},
                                   {"framesync_corridor", {"real", "virtual"}}};

std::string sample(const std::string& file) {
    return std::string(MRLOC_SOURCE_DIR) + "/rawlogs/" + file;
}

}  // namespace

TEST(Samples, EachIsWhatTheSimulatorMakesTodayTruthIncluded) {
    for (const auto& s : kSamples) {
        SCOPED_TRACE(s.ini);
        const std::string out = tmp("sample_" + s.ini);
        const auto r = mrlocCmd("simulate " + config(s.ini) + " -q --out " + out);
        ASSERT_EQ(r.code, 0) << r.output;
        const std::string rawlog = s.ini + ".rawlog";
        EXPECT_EQ(slurp(out + "/" + rawlog), slurp(sample(rawlog)));
        for (const auto& robot : s.robots) {
            const std::string gt = s.ini + "." + robot + ".gt.txt";
            ASSERT_TRUE(fs::exists(sample(gt))) << gt;
            EXPECT_EQ(slurp(out + "/" + gt), slurp(sample(gt))) << gt;
        }
    }
}

TEST(Samples, EachLocalizesWithItsIniToItsHeadline) {
    for (const auto& s : kSamples) {
        SCOPED_TRACE(s.ini);
        const std::string out = tmp("sample_loc_" + s.ini);
        const auto r = mrlocCmd("localize " + config(s.ini) + " " + sample(s.ini + ".rawlog") +
                                " -q --out " + out);
        ASSERT_EQ(r.code, 0) << r.output;
        const auto m = common::readJsonFile(out + "/metrics.json");
        EXPECT_GT(m["use"]["used"].get<size_t>(), 0u);
        EXPECT_TRUE(m["headline"]["reached"].get<bool>()) << m["headline"].dump();
        EXPECT_TRUE(m["ground_truth"].get<bool>()) << "the truth beside the sample was not read";
    }
}

TEST(Samples, MrptsRawlogEditReadsEachAsMrlocInfoDoes) {
    if (!fs::exists("/usr/bin/rawlog-edit"))
        GTEST_SKIP() << "MRPT's rawlog-edit (Debian mrpt-apps) is not installed";
    for (const auto& s : kSamples) {
        SCOPED_TRACE(s.ini);
        const std::string rawlog = sample(s.ini + ".rawlog");
        FILE* p = popen(("/usr/bin/rawlog-edit --info -i " + rawlog + " 2>&1").c_str(), "r");
        ASSERT_NE(p, nullptr);
        std::string text;
        char buf[4096];
        while (size_t n = fread(buf, 1, sizeof buf, p)) text.append(buf, n);
        ASSERT_EQ(pclose(p), 0) << text;
        std::smatch objects;
        ASSERT_TRUE(
            std::regex_search(text, objects, std::regex("Overall number of objects *: *([0-9]+)")))
            << text;
        const auto info = mrlocCmd("info --json " + rawlog);
        ASSERT_EQ(info.code, 0) << info.output;
        const auto j = nlohmann::json::parse(info.output);
        EXPECT_EQ(std::stoul(objects[1]), j["entries"].get<size_t>()) << info.output;
        EXPECT_NE(text.find("Observations format               : Yes"), std::string::npos) << text;
    }
}
