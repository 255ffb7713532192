// Report pictures: the off-screen top view puts things where they are; plots and HTML exist.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/report/Plots.h>
#include <mrloc/report/TopView.h>
#include <mrpt/img/CImage.h>

#include <cstdlib>
#include <filesystem>

using namespace mrloc;

namespace {

/** Counts pixels within a small window whose colour is within 40 of `c` in each channel. */
int countColoured(const mrpt::img::CImage& img, int cx, int cy, mrpt::img::TColor c) {
    int n = 0;
    for (int y = cy - 6; y <= cy + 6; ++y)
        for (int x = cx - 6; x <= cx + 6; ++x) {
            const uint8_t* p = img(x, y);  // BGR order in CImage
            if (std::abs(p[2] - c.R) < 40 && std::abs(p[1] - c.G) < 40 && std::abs(p[0] - c.B) < 40)
                ++n;
        }
    return n;
}

}  // namespace

TEST(TopView, DrawsPathsAndBeaconsWhereTheyAre) {
    report::TopViewContent c;
    sim::WorldOptions w;
    w.sizeX = 4, w.sizeY = 4, w.height = 2.5;
    c.world = w;
    c.landmarks = {{0.5, 3.5, 2.5}};
    // A horizontal estimated path along y = 1.1 and a vertical true path along x = 3.1 (off
    // the 0.5 m grid lines, which a 1-pixel path would share pixels with).
    for (int i = 0; i <= 10; ++i) {
        c.estimates["r"].push_back(
            {double(i), mrpt::poses::CPose3D(0.5 + 0.3 * i, 1.1, 0, 0, 0, 0)});
        c.groundTruth["r"].push_back(
            {double(i), mrpt::poses::CPose3D(3.1, 0.5 + 0.3 * i, 0, 0, 0, 0)});
    }
    c.landmarkLabels = {"7"};
    // odometry alone along y = 2.6, in the robot's dark shade
    for (int i = 0; i <= 10; ++i)
        c.odometry["r"].push_back(
            {double(i), mrpt::poses::CPose3D(0.5 + 0.3 * i, 2.6, 0, 0, 0, 0)});
    const std::string png = testing::TempDir() + "/mrloc_topview.png";
    report::renderTopView(c, png, 400, 400);
    mrpt::img::CImage img;
    ASSERT_TRUE(img.loadFromFile(png));
    // the drawing 400 x 400, the legend in a panel right of it (its longest entry, "r odometry
    // alone", 16 characters: 48 + 9 x 16 = 192 px)
    ASSERT_EQ(img.getHeight(), 400u);
    ASSERT_EQ(img.getWidth(), 592u);
    // The view is centred on the room; the scale follows from the fitted zoom with its margin:
    // 400 px span (1.12 * 4 + 0.3) * 1.1 = 5.258 m, so 1 m = 76.1 px, image y grows downwards.
    const double pxPerM = 400 / ((1.12 * 4 + 0.3) * 1.1);
    const auto px = [&](double x) { return int(200 + (x - 2.0) * pxPerM); };
    const auto py = [&](double y) { return int(200 - (y - 2.0) * pxPerM); };
    // The estimate in the robot's colour (violet: blue and red well above green), the truth
    // in its pale version (green channel raised towards white), nothing violet elsewhere.
    const auto violet = [&](int x, int y, int gLo, int gHi) {
        int n = 0;
        for (int v = y - 6; v <= y + 6; ++v)
            for (int u = x - 6; u <= x + 6; ++u) {
                const uint8_t* p = img(u, v);
                n += p[0] > p[1] + 30 && p[2] > p[1] + 15 && p[1] >= gLo && p[1] <= gHi;
            }
        return n;
    };
    EXPECT_GT(violet(px(1.5), py(1.1), 0, 150), 3);    // the estimate, full colour
    EXPECT_EQ(violet(px(1.5), py(1.1), 160, 255), 0);  // not pale
    EXPECT_GT(violet(px(3.1), py(2.0), 150, 200), 3);  // the truth, pale
    EXPECT_EQ(violet(px(3.1), py(2.0), 0, 140), 0);
    EXPECT_GT(countColoured(img, px(1.5), py(2.6), {74, 0, 105}), 3);   // odometry, dark
    EXPECT_GT(countColoured(img, px(0.5), py(3.5), {30, 90, 220}), 3);  // the landmark
    EXPECT_EQ(violet(px(1.5), py(3.0), 0, 255), 0);                     // no path elsewhere
    // the start: a black ring where the truth begins, (3.1, 0.5)
    EXPECT_GT(countColoured(img, px(3.1) + 9, py(0.5), {0, 0, 0}), 3);
    // the landmark's name on white, centred above it
    EXPECT_GT(countColoured(img, px(0.5), py(3.5) - 33, {255, 255, 255}), 20);
    // The legend is in the panel, clear of the drawing: the landmarks' swatch at its first
    // row; the scale bar (bottom left) is black on white.
    EXPECT_GT(countColoured(img, 400 + 18, 14 + 7, {30, 90, 220}), 3);
    EXPECT_GT(countColoured(img, 30, 400 - 16, {0, 0, 0}), 3);
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

// Every way a string once ran code in gnuplot: a quote ending the string, a newline ending the
// command, a backtick or system() substitution, a macro, a pipe in `set output`. Each, as a
// curve's title, a plot title and a data word, draws its picture and runs nothing.
TEST(Plots, GnuplotStringsRunNothing) {
    namespace fs = std::filesystem;
    const std::string dir = testing::TempDir() + "/gnuplot_strings";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const std::string marker = dir + "/X";
    EXPECT_EQ(report::gnuplotString("a'b"), "'a''b'");
    EXPECT_EQ(report::gnuplotString("a\nb\r\x7f"),
              "'a?b?"
              "?'");
    EXPECT_EQ(report::gnuplotDataWord("a b\"c'#d\\e$f`g"), "a_b_c__d_e_f_g");
    EXPECT_EQ(report::gnuplotDataWord(""), "_");
    const std::vector<std::string> hostile{"x'; system(\"touch " + marker + "\"); '",
                                           "x\nsystem(\"touch " + marker + "\")\n",
                                           "`touch " + marker + "`",
                                           "@m x' . system('touch " + marker + "') . '",
                                           "$(touch " + marker + ")",
                                           "x\\",
                                           "|touch " + marker,
                                           "x\"; system(\"touch " + marker + "\"); \""};
    int i = 0;
    for (const auto& name : hostile) {
        const std::string png = dir + "/p" + std::to_string(i++) + ".png";
        report::RobotErrors errors{{name, {{0.0, 0.1}, {1.0, 0.2}}}};
        report::plotErrorOverTime(errors, png);
        report::plotErrorPerRobot(errors, png + ".robots.png");
        report::runGnuplot("m = 'touch " + marker + "'\nset title " + report::gnuplotString(name) +
                               "\nplot x title " + report::gnuplotString(name) + "\n",
                           png + ".title.png");
        EXPECT_TRUE(report::isCompletePng(png)) << name;
        EXPECT_TRUE(report::isCompletePng(png + ".title.png")) << name;
        EXPECT_FALSE(fs::exists(marker)) << "ran: " << name;
    }
    // gnuplot's own check: a raw string would have run the command (the test can fail)
    report::runGnuplot("system('touch " + marker + "')\nplot x\n", dir + "/raw.png");
    EXPECT_TRUE(fs::exists(marker));
}
