// The files between the omnivision localizer and its report section round-trip.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/omnivision/OmniFiles.h>

#include <cmath>
#include <filesystem>
#include <fstream>

using namespace mrloc;

TEST(OmniFiles, LayoutAndAccuracyFilesRoundTrip) {
    const std::string dir = testing::TempDir() + "/omni_files";
    std::filesystem::create_directories(dir);
    const double nan = std::nan("");
    omnivision::LayoutFile l;
    l.time = 1700000012.5;
    l.a = "A", l.b = "B";
    l.points = {{"A", 0, 0, 0, 0, 1e-8, 0, 1e-8, 0, 0},
                {"C", 1.0 / 3, 2.0 / 3, 0.34, 0.66, 2e-5, -1e-6, 3e-5, 0.335, 0.667},
                {"E", nan, nan, nan, nan, nan, nan, nan, 4, 5}};
    l.write(dir);
    const auto r = omnivision::LayoutFile::read(dir);
    EXPECT_EQ(r.time, l.time);
    EXPECT_EQ(r.a, "A");
    EXPECT_EQ(r.b, "B");
    ASSERT_EQ(r.points.size(), 3u);
    EXPECT_EQ(r.points[1].robot, "C");
    EXPECT_NEAR(r.points[1].paperX, 1.0 / 3, 1e-10);
    EXPECT_NEAR(r.points[1].cxy, -1e-6, 1e-16);
    EXPECT_TRUE(std::isnan(r.points[2].refinedX));
    EXPECT_EQ(r.points[2].trueY, 5);

    omnivision::AccuracyFile a;
    a.distanceName = "odometer";
    a.points = {{"angle", 0.05, 0.02, 0.017, 0.0085, 100, 0},
                {"distance", 0.1, 0.05, 0.059, 0.027, 100, 3}};
    a.write(dir);
    const auto b = omnivision::AccuracyFile::read(dir);
    EXPECT_EQ(b.distanceName, "odometer");
    ASSERT_EQ(b.points.size(), 2u);
    EXPECT_EQ(b.points[1].axis, "distance");
    EXPECT_NEAR(b.points[1].refined, 0.027, 1e-12);
    EXPECT_EQ(b.points[1].failures, 3);

    std::ofstream(omnivision::AccuracyFile::path(dir)) << "speed 1 2 3 4 5 6\n";
    EXPECT_THROW(omnivision::AccuracyFile::read(dir), Error);
}
