// Report pictures: the off-screen top view puts things where they are; plots and HTML exist.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/report/Plots.h>
#include <mrloc/report/TopView.h>
#include <mrpt/img/CImage.h>

#include <filesystem>

using namespace mrloc;

namespace {

/** Counts pixels within a small window whose colour is dominated by one channel. */
int countColoured(const mrpt::img::CImage& img, int cx, int cy, int channel) {
    int n = 0;
    for (int y = cy - 6; y <= cy + 6; ++y)
        for (int x = cx - 6; x <= cx + 6; ++x) {
            const uint8_t* p = img(x, y);  // BGR order in CImage
            const int b = p[0], g = p[1], r = p[2];
            const int c[3] = {r, g, b};
            int others = 0;
            for (int k = 0; k < 3; ++k)
                if (k != channel) others = std::max(others, c[k]);
            if (c[channel] > others + 20) ++n;
        }
    return n;
}

}  // namespace

TEST(TopView, DrawsPathsAndBeaconsWhereTheyAre) {
    report::TopViewContent c;
    sim::WorldOptions w;
    w.sizeX = 4, w.sizeY = 4, w.height = 2.5;
    c.world = w;
    c.beacons = {{1, {0.5, 3.5, 2.5}}};
    // A horizontal estimated path along y = 1 and a vertical true path along x = 3.
    for (int i = 0; i <= 10; ++i) {
        c.estimates["r"].push_back(
            {double(i), mrpt::poses::CPose3D(0.5 + 0.3 * i, 1.0, 0, 0, 0, 0)});
        c.groundTruth["r"].push_back(
            {double(i), mrpt::poses::CPose3D(3.0, 0.5 + 0.3 * i, 0, 0, 0, 0)});
    }
    const std::string png = testing::TempDir() + "/mrloc_topview.png";
    report::renderTopView(c, png, 400, 400);
    mrpt::img::CImage img;
    ASSERT_TRUE(img.loadFromFile(png));
    ASSERT_EQ(img.getWidth(), 400u);
    // The view is centred on the room; the scale follows from the fitted zoom:
    // 400 px span 2.2 * 4 + 0.2 = 9 m / 2 = 4.5 m, so 1 m = 88.9 px, image y grows downwards.
    const auto px = [](double x) { return int(200 + (x - 2.0) * 400 / 4.5); };
    const auto py = [](double y) { return int(200 - (y - 2.0) * 400 / 4.5); };
    EXPECT_GT(countColoured(img, px(1.5), py(1.0), 0), 3);  // red estimate
    EXPECT_GT(countColoured(img, px(3.0), py(2.0), 1), 3);  // green ground truth
    EXPECT_GT(countColoured(img, px(0.5), py(3.5), 2), 3);  // blue beacon
    EXPECT_EQ(countColoured(img, px(1.5), py(3.0), 0), 0);  // nothing red elsewhere
}

TEST(Plots, GnuplotWritesPngs) {
    report::RobotErrors e;
    for (int i = 0; i < 50; ++i) e["r1"].push_back({0.1 * i, 0.01 * (i % 7)});
    const std::string dir = testing::TempDir();
    report::plotErrorOverTime(e, dir + "/mrloc_err.png");
    report::plotErrorCdf(e, dir + "/mrloc_cdf.png");
    mrpt::img::CImage img;
    ASSERT_TRUE(img.loadFromFile(dir + "/mrloc_err.png"));
    EXPECT_EQ(img.getWidth(), 900u);
    ASSERT_TRUE(img.loadFromFile(dir + "/mrloc_cdf.png"));
    EXPECT_THROW(report::plotErrorCdf({}, dir + "/mrloc_none.png"), Error);
    EXPECT_FALSE(std::filesystem::exists(dir + "/mrloc_none.png"));
}
