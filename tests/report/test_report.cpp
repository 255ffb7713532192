// Report pictures: the off-screen top view puts things where they are; plots and HTML exist.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/Evaluation.h>
#include <mrloc/report/EvaluationPlots.h>
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
    for (int i = 0; i < 5; ++i) e["r" + std::to_string(i)].push_back({0.1 * i, 0.01 * i});
    const std::string dir = testing::TempDir();
    report::plotErrorPerRobot(e, dir + "/mrloc_err.png");
    mrpt::img::CImage img;
    ASSERT_TRUE(img.loadFromFile(dir + "/mrloc_err.png"));
    EXPECT_EQ(img.getWidth(), 900u);
    EXPECT_THROW(report::plotErrorPerRobot({}, dir + "/mrloc_none.png"), Error);
    EXPECT_FALSE(std::filesystem::exists(dir + "/mrloc_none.png"));
    EXPECT_THROW(report::plotTruthTimelineCdf({}, dir + "/mrloc_none.png"), Error);
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
        report::EvaluatedTrack track;  // a robot's name is every truth-timeline title
        track.name = name;
        track.truth = {{0.0, mrpt::poses::CPose3D()},
                       {1.0, mrpt::poses::CPose3D(1, 0, 0, 0, 0, 0)}};
        track.estimate = common::evaluate(track.truth, track.truth);
        report::plotTruthTimelineError({track}, png);
        report::plotPoseOverTime(track, png + ".pose.png");
        report::plotErrorTopView(track, png + ".top.png");
        report::plotErrorPerRobot(errors, png + ".robots.png");
        report::runGnuplot("m = 'touch " + marker + "'\nset title " + report::gnuplotString(name) +
                               "\nplot x title " + report::gnuplotString(name) + "\n",
                           png + ".title.png");
        for (const char* suffix : {"", ".pose.png", ".top.png", ".robots.png", ".title.png"})
            EXPECT_TRUE(report::isCompletePng(png + suffix)) << name << suffix;
        EXPECT_FALSE(fs::exists(marker)) << "ran: " << name;
    }
    // gnuplot's own check: a raw string would have run the command (the test can fail)
    report::runGnuplot("system('touch " + marker + "')\nplot x\n", dir + "/raw.png");
    EXPECT_TRUE(fs::exists(marker));
}

namespace {

/** Pixels of exactly this colour in the whole picture. */
size_t countExactly(const mrpt::img::CImage& img, uint8_t r, uint8_t g, uint8_t b) {
    size_t n = 0;
    for (int y = 0; y < int(img.getHeight()); ++y)
        for (int x = 0; x < int(img.getWidth()); ++x) {
            const uint8_t* p = img(x, y);  // BGR
            n += p[2] == r && p[1] == g && p[0] == b;
        }
    return n;
}

common::Trajectory straightDrive(double t1, double dt) {
    common::Trajectory out;
    for (int k = 0; k * dt <= t1 + 1e-9; ++k)
        out.push_back({k * dt, mrpt::poses::CPose3D(k * dt, 0, 0, 0, 0, 0)});
    return out;
}

}  // namespace

// The shaded stretches are where the truth has no estimate: a 2 s gap of a 10 s drive shades
// about a fifth of the plot's width; the same drive without the gap shades nothing but the
// legend's swatch.
TEST(EvaluationPlots, TheUncoveredStretchIsShadedAndOnlyIt) {
    const auto truth = straightDrive(10, 0.1);
    common::Trajectory gapped, whole;
    for (const auto& p : truth) {
        auto q = p;
        q.pose.x_incr(0.05 + 0.01 * std::sin(p.t));
        whole.push_back(q);
        if (p.t < 4 - 1e-9 || p.t > 6 + 1e-9) gapped.push_back(q);
    }
    const std::string dir = testing::TempDir();
    report::EvaluatedTrack t;
    t.name = "r1";
    t.truth = truth;
    t.estimate = common::evaluate(gapped, truth);
    ASSERT_EQ(t.estimate.coverage.uncovered.size(), 1u);
    report::plotTruthTimelineError({t}, dir + "/mrloc_eval_gap.png");
    t.estimate = common::evaluate(whole, truth);
    report::plotTruthTimelineError({t}, dir + "/mrloc_eval_whole.png");
    mrpt::img::CImage gap, full;
    ASSERT_TRUE(gap.loadFromFile(dir + "/mrloc_eval_gap.png"));
    ASSERT_TRUE(full.loadFromFile(dir + "/mrloc_eval_whole.png"));
    // #c8c8c8 at 0.6 opacity over white: 222, 222, 222
    const size_t shadedGap = countExactly(gap, 222, 222, 222);
    const size_t shadedWhole = countExactly(full, 222, 222, 222);
    EXPECT_LT(shadedWhole, 50u);  // measured 7: antialiased edges that happen to match
    // a 1000 x 500 picture, about 300 px of plot height: a fifth of ~700 px wide is ~140 px
    EXPECT_GT(shadedGap, 100u * 250u) << shadedGap;
    EXPECT_LT(shadedGap, 200u * 450u) << shadedGap;
    // the other pictures draw from the same evaluation
    report::plotPoseOverTime(t, dir + "/mrloc_eval_pose.png");
    report::plotErrorTopView(t, dir + "/mrloc_eval_top.png");
    report::plotTruthTimelineCdf({t}, dir + "/mrloc_eval_cdf.png");
    for (const char* f : {"mrloc_eval_pose.png", "mrloc_eval_top.png", "mrloc_eval_cdf.png"})
        EXPECT_TRUE(report::isCompletePng(dir + "/" + f)) << f;
}

TEST(EvaluationPlots, TheTwoSigmaEllipseOfACovarianceHasItsAxesAndAngle) {
    mrpt::math::CMatrixDouble33 c;
    c.setZero();
    c(0, 0) = 4, c(1, 1) = 1;  // sigma 2 m along x, 1 m along y: full axes 8 m and 4 m
    auto e = report::twoSigmaEllipse(c);
    ASSERT_TRUE(e);
    EXPECT_NEAR(e->major, 8, 1e-12);
    EXPECT_NEAR(e->minor, 4, 1e-12);
    EXPECT_NEAR(std::fmod(e->angleDeg + 360, 180), 0, 1e-9);
    // the same turned by 30 degrees: R diag(4, 1) R^T
    const double a = M_PI / 6, ca = std::cos(a), sa = std::sin(a);
    c(0, 0) = 4 * ca * ca + sa * sa;
    c(1, 1) = 4 * sa * sa + ca * ca;
    c(0, 1) = c(1, 0) = 3 * ca * sa;
    e = report::twoSigmaEllipse(c);
    ASSERT_TRUE(e);
    EXPECT_NEAR(e->major, 8, 1e-9);
    EXPECT_NEAR(e->minor, 4, 1e-9);
    EXPECT_NEAR(std::fmod(e->angleDeg + 360, 180), 30, 1e-9);
    c(0, 0) = NAN;  // a method that does not estimate a term writes nan
    EXPECT_FALSE(report::twoSigmaEllipse(c));
}
