// Report pictures: the off-screen top view puts things where they are; plots and HTML exist.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/Evaluation.h>
#include <mrloc/report/EvaluationPlots.h>
#include <mrloc/report/PictureLayout.h>
#include <mrloc/report/Plots.h>
#include <mrloc/report/TopView.h>
#include <mrpt/img/CImage.h>
#include <mrpt/opengl/COpenGLScene.h>
#include <mrpt/opengl/CSetOfLines.h>

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
    // The room 4 x 4 m with its 6 % and 0.3 m margins: 4.54 m over the 400 px drawing, framed
    // by axes (tick labels 1 character, "y (m)" 5: 16 + 9 x 5 = 61 px left, 26 top, 46 below),
    // the legend's panel right of it (14 px apart; its longest entry, "r odometry alone", 16
    // characters: 60 + 9 x 16 = 204 px).
    const auto layout = report::readLayout(png);
    ASSERT_TRUE(layout);
    EXPECT_EQ(layout->data.x0, 61);
    EXPECT_EQ(layout->data.y0, 26);
    EXPECT_EQ(layout->data.width(), 400);
    EXPECT_EQ(layout->data.height(), 400);
    ASSERT_EQ(img.getWidth(), 61u + 400 + 14 + 204);
    ASSERT_EQ(img.getHeight(), 26u + 400 + 46);
    EXPECT_EQ(layout->width, int(img.getWidth()));
    ASSERT_TRUE(layout->legend);
    EXPECT_FALSE(layout->legend->overlaps(layout->data));
    EXPECT_EQ(layout->legend->x0, 61 + 400 + 14);
    ASSERT_EQ(layout->labels.size(), 1u);
    EXPECT_TRUE(layout->labels[0].inside(layout->data));
    ASSERT_TRUE(layout->inkShare);
    EXPECT_GT(*layout->inkShare, 0.7);  // the room's walls span the drawing (measured 0.78)
    const double pxPerM = 400 / (1.06 * 4 + 0.3);
    const auto px = [&](double x) { return int(61 + 200 + (x - 2.0) * pxPerM); };
    const auto py = [&](double y) { return int(26 + 200 - (y - 2.0) * pxPerM); };
    // The robot's colour (the palette's first, blue): blue well above red, green between.
    const auto blue = [&](int x, int y, int rLo, int rHi) {
        int n = 0;
        for (int v = y - 6; v <= y + 6; ++v)
            for (int u = x - 6; u <= x + 6; ++u) {
                const uint8_t* p = img(u, v);
                n += p[0] > p[2] + 40 && p[1] > p[2] + 20 && p[2] >= rLo && p[2] <= rHi;
            }
        return n;
    };
    EXPECT_GT(blue(px(1.5), py(1.1), 0, 60), 3);     // the estimate, full colour
    EXPECT_EQ(blue(px(1.5), py(1.1), 120, 255), 0);  // not pale
    EXPECT_GT(blue(px(3.1), py(2.0), 140, 200), 3);  // the truth, pale
    EXPECT_EQ(blue(px(3.1), py(2.0), 0, 60), 0);
    EXPECT_EQ(blue(px(1.5), py(3.0), 0, 255), 0);  // no path elsewhere
    // the truth a wide band (10 px), the estimate a thin line (2 px): across each, pixels of
    // its colour in one column
    const auto across = [&](int x, int y, int rLo, int rHi) {
        int n = 0;
        for (int v = y - 12; v <= y + 12; ++v) {
            const uint8_t* p = img(x, v);
            n += p[0] > p[2] + 40 && p[1] > p[2] + 20 && p[2] >= rLo && p[2] <= rHi;
        }
        return n;
    };
    EXPECT_LE(across(px(1.5), py(1.1), 0, 60), 3);
    int bandWidth = 0;  // the truth runs up x = 3.1: count along a row
    for (int u = px(3.1) - 12; u <= px(3.1) + 12; ++u) {
        const uint8_t* p = img(u, py(2.0));
        bandWidth += p[0] > p[2] + 40 && p[2] >= 140 && p[2] <= 200;
    }
    EXPECT_GE(bandWidth, 8);
    // odometry alone dashed: along y = 2.6 (its fullest row) the robot's colour and gaps
    // alternate (7 px drawn, 5 not, the line's caps narrowing the gaps: about 80 % drawn)
    int drawn = 0, columns = px(3.3) - px(0.7) + 1;
    for (int v = py(2.6) - 2; v <= py(2.6) + 2; ++v) {
        int inRow = 0;
        for (int u = px(0.7); u <= px(3.3); ++u) {
            const uint8_t* p = img(u, v);
            inRow += p[0] > p[2] + 40 && p[1] > p[2] + 20 && p[2] <= 60;
        }
        drawn = std::max(drawn, inRow);
    }
    EXPECT_GT(drawn, columns / 3);
    EXPECT_LT(drawn, columns * 9 / 10);
    EXPECT_GT(countColoured(img, px(0.5), py(3.5), {230, 159, 0}), 3);  // the landmark
    // the start: a black ring where the truth begins, (3.1, 0.5)
    const int ring = int(std::lround((0.015 * 4 + 0.03) * pxPerM * 0.85));
    EXPECT_GT(countColoured(img, px(3.1) + ring, py(0.5), {0, 0, 0}), 3);
    // the landmark's name on white, centred above it
    EXPECT_GT(countColoured(img, px(0.5), py(3.5) - 33, {255, 255, 255}), 20);
    // the axes: a tick label "0" under x = 0 and beside y = 0, dark on white
    EXPECT_GT(countColoured(img, px(0.0), 26 + 400 + 15, {30, 30, 30}), 3);
    // The legend in its panel, clear of the drawing: walls first, the landmarks' dot second.
    EXPECT_GT(countColoured(img, 61 + 400 + 14 + 27, 26 + 20 + 8, {230, 159, 0}), 3);
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

// What OpenGL draws (walls, beacons, the polygon maps) and what is drawn in pixels over it
// (paths, bands) land on the same pixels for the same place, in a wide, a tall and a square
// extent: a square outline drawn both ways, red through OpenGL, blue as a path, has its
// left and right sides in the same columns of the row through its middle.
TEST(TopView, OpenGlAndPixelPathsAgreeInEveryShape) {
    for (const auto& [x1, y1] : std::vector<std::pair<double, double>>{{8, 4}, {4, 8}, {5, 5}}) {
        mrpt::opengl::COpenGLScene scene;
        scene.getViewport()->setCustomBackgroundColor({1, 1, 1});
        auto lines = mrpt::opengl::CSetOfLines::Create();
        lines->setColor_u8(mrpt::img::TColor(255, 0, 0));
        const double s0 = 1, s1 = 3;  // the square's sides
        lines->appendLine(s0, s0, 0.03, s1, s0, 0.03);
        lines->appendLine(s1, s0, 0.03, s1, s1, 0.03);
        lines->appendLine(s1, s1, 0.03, s0, s1, 0.03);
        lines->appendLine(s0, s1, 0.03, s0, s0, 0.03);
        scene.insert(lines);
        // the blue path a little inside the red square, so that neither hides the other
        const double in = 0.1;
        const report::PicturePath path{{{s0 + in, s0 + in},
                                        {s1 - in, s0 + in},
                                        {s1 - in, s1 - in},
                                        {s0 + in, s1 - in},
                                        {s0 + in, s0 + in}},
                                       mrpt::img::TColor(0, 0, 255),
                                       1,
                                       false};
        const std::string png = testing::TempDir() + "/mrloc_agree.png";
        report::saveTopDown(scene, 0, 0, x1, y1, png, 600, 600, {}, {}, {path});
        mrpt::img::CImage img;
        ASSERT_TRUE(img.loadFromFile(png));
        const auto layout = report::readLayout(png);
        ASSERT_TRUE(layout);
        // the square's middle row, from the blue path's extent
        int by0 = -1, by1 = -1;
        for (int v = layout->data.y0; v < layout->data.y1; ++v)
            for (int u = layout->data.x0; u < layout->data.x1; ++u) {
                const uint8_t* p = img(u, v);
                if (p[0] > 200 && p[2] < 80 && p[1] < 80) {
                    if (by0 < 0) by0 = v;
                    by1 = v;
                }
            }
        ASSERT_GE(by0, 0);
        const int mid = (by0 + by1) / 2;
        std::vector<int> red, blue;
        for (int u = layout->data.x0; u < layout->data.x1; ++u) {
            const uint8_t* p = img(u, mid);
            if (p[2] > 150 && p[2] > p[1] + 60 && p[2] > p[0] + 60) red.push_back(u);
            if (p[0] > 200 && p[2] < 80 && p[1] < 80) blue.push_back(u);
        }
        ASSERT_GE(red.size(), 2u) << x1 << " x " << y1;
        ASSERT_GE(blue.size(), 2u) << x1 << " x " << y1;
        const double m = double(by1 - by0) / (s1 - s0 - 2 * in);  // pixels per metre, from blue
        // the red sides 0.1 m outside the blue ones, to a pixel
        EXPECT_NEAR(blue.front() - red.front(), in * m, 1.5) << x1 << " x " << y1;
        EXPECT_NEAR(red.back() - blue.back(), in * m, 1.5) << x1 << " x " << y1;
    }
}
