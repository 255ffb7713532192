// The file between the polymap localizer and its report section round-trips.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/polymap/PolymapFiles.h>

#include <filesystem>
#include <fstream>

using namespace mrloc;

TEST(PolymapFiles, HypothesesFileRoundTripsAndNamesABadLine) {
    const std::string dir = testing::TempDir() + "/polymap_files";
    std::filesystem::create_directories(dir);
    polymap::HypothesesFile f;
    f.time = 1700000000.25;
    f.sensed = {{1.5, -2.25}, {0.1, 1e-7}, {-3, 4}};
    for (int i = 0; i < 3; ++i) {
        polymap::Hypothesis h;
        h.point = {1.0 / 3 + i, 2.0 / 7 - i};
        h.translation = {0.5 * i, -0.25 * i};
        h.mismatch = 1e-3 * i;
        f.hypotheses.push_back(h);
    }
    f.write(dir, "r1");
    const auto g = polymap::HypothesesFile::read(dir, "r1");
    EXPECT_EQ(g.time, f.time);  // 17 digits: the same double
    ASSERT_EQ(g.sensed.size(), 3u);
    ASSERT_EQ(g.hypotheses.size(), 3u);
    for (size_t i = 0; i < 3; ++i) {
        EXPECT_NEAR(g.sensed[i].x, f.sensed[i].x, 1e-9);
        EXPECT_NEAR(g.sensed[i].y, f.sensed[i].y, 1e-9);
        EXPECT_NEAR(g.hypotheses[i].point.x, f.hypotheses[i].point.x, 1e-9);
        EXPECT_NEAR(g.hypotheses[i].point.y, f.hypotheses[i].point.y, 1e-9);
        EXPECT_NEAR(g.hypotheses[i].translation.y, f.hypotheses[i].translation.y, 1e-9);
        EXPECT_NEAR(g.hypotheses[i].mismatch, f.hypotheses[i].mismatch, 1e-12);
    }
    std::ofstream(polymap::HypothesesFile::path(dir, "r2")) << "t 1\nH 1 2 3\n";
    try {
        polymap::HypothesesFile::read(dir, "r2");
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("hypotheses.r2.txt:2: expected 6 fields"),
                  std::string::npos)
            << e.what();
    }
}
