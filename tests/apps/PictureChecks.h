#pragma once
// Pictures a reader understands at a glance, checked from the layout each renderer writes into
// its PNG (gnuplot's plot area and key placement, the top views' drawing, legend panel and
// labels: report/PictureLayout.h), not from what the pixels look like: the picture's size; the
// data area a real share of it (no picture half legend); the legend beside the data, never
// over them; labels inside the data and clear of the legend; and a top view's content
// spanning most of its drawing (no empty half; gnuplot's plots are fitted to their data by
// its autoscale). Every shipped INI's pictures go through it once: where a test runs a
// shipped INI whole, it checks them there (tests/apps/test_pictures.cpp lists which).
#include <gtest/gtest.h>
#include <mrloc/report/PictureLayout.h>
#include <mrpt/img/CImage.h>

#include <filesystem>
#include <iostream>
#include <string>

namespace mrloc::testing_cli {

/** Checks one picture from its layout (see the file's comment). */
inline void expectPictureReadsAtAGlance(const std::filesystem::path& png, const std::string& what) {
    mrpt::img::CImage img;
    ASSERT_TRUE(img.loadFromFile(png.string())) << what;
    const auto l = report::readLayout(png.string());
    ASSERT_TRUE(l) << what << " carries no layout";
    const int W = int(img.getWidth()), H = int(img.getHeight());
    EXPECT_EQ(l->width, W) << what;
    EXPECT_EQ(l->height, H) << what;
    EXPECT_GE(W, 400) << what;
    EXPECT_LE(W, 2000) << what;
    EXPECT_GE(H, 300) << what;
    EXPECT_LE(H, 1400) << what;
    const report::PixelBox picture{0, 0, W, H};
    EXPECT_TRUE(l->data.inside(picture)) << what;
    // the data (every panel of a multiplot) at least 30 % of the picture: no picture half
    // legend (measured before the layout fixes: formation.run.png's plot 26 %)
    const double dataShare =
        double(l->data.width()) * l->data.height() * l->panels / (double(W) * H);
    EXPECT_GE(dataShare, 0.3) << what;
    // whatever is beside or below the data (legend, key, colour box) no larger than the
    // data: a legend does not take half the picture
    EXPECT_LE(W - l->data.x1, l->data.width()) << what << ": more legend than data";
    EXPECT_LE(H - l->data.y1, l->data.height()) << what << ": more legend than data";
    EXPECT_NE(l->key, "inside") << what << ": its key is over the data";
    if (l->legend) {
        EXPECT_FALSE(l->legend->overlaps(l->data)) << what;
        EXPECT_TRUE(l->legend->inside(picture)) << what << ": its legend is cut";
    }
    for (const auto& label : l->labels) {
        EXPECT_TRUE(label.inside(l->data)) << what;
        EXPECT_FALSE(l->legend && label.overlaps(*l->legend)) << what;
    }
    // a top view's content spans most of its drawing (gnuplot's plots: its autoscale)
    if (l->inkShare) {
        EXPECT_GT(*l->inkShare, 0.5) << what << ": its drawing is mostly empty";
    }
    std::cout << what << ": " << W << " x " << H << ", data " << int(100 * dataShare) << " %"
              << (l->inkShare ? ", content " + std::to_string(int(100 * *l->inkShare)) + " %"
                              : std::string())
              << "\n";
}

/** Every picture of the run folder `dir` (of the shipped INI `ini`) checked; at least one. */
inline void expectPicturesReadAtAGlance(const std::string& dir, const std::string& ini) {
    int pictures = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir)) {
        if (e.path().extension() != ".png") continue;
        ++pictures;
        expectPictureReadsAtAGlance(e.path(), ini + "/" + e.path().filename().string());
    }
    EXPECT_GE(pictures, 1) << ini << ": no picture in " << dir;
}

}  // namespace mrloc::testing_cli
