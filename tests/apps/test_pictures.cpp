// Every picture of the tour's runs (one shipped INI per method: config/tour.txt) reads at a
// glance. Checked from the layout each renderer wrote into its PNG (gnuplot's plot area and
// key placement, the top views' drawing, legend panel and labels: PictureLayout.h), not from
// what the pixels look like: the picture's size; the data area a real share of it (no
// picture half legend); the legend beside the data, never over them; labels inside the data
// and clear of the legend; and a top view's content spanning most of its drawing (no empty
// half; gnuplot's plots are fitted to their data by its autoscale).
#include <gtest/gtest.h>
#include <mrloc/report/PictureLayout.h>
#include <mrpt/img/CImage.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "MrlocCli.h"

using namespace mrloc;
using namespace mrloc::testing_cli;

TEST(Pictures, EveryPictureOfTheTourReadsAtAGlance) {
    namespace fs = std::filesystem;
    std::ifstream list(std::string(MRLOC_SOURCE_DIR) + "/config/tour.txt");
    std::map<std::string, int> picturesPerRun;
    double leastShare = 1, leastData = 1;
    std::string leastShareOf, leastDataOf;
    for (std::string line; std::getline(list, line);) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream words(line);
        std::string name, ini;
        words >> name >> ini;
        const std::string out = tmp("pictures_" + name);
        const auto run =
            mrlocCmd("run " + std::string(MRLOC_SOURCE_DIR) + "/" + ini + " --out " + out + " -q");
        ASSERT_EQ(run.code, 0) << ini << ": " << run.output;
        for (const auto& e : fs::directory_iterator(out)) {
            if (e.path().extension() != ".png") continue;
            const std::string what = name + "/" + e.path().filename().string();
            ++picturesPerRun[name];
            mrpt::img::CImage img;
            ASSERT_TRUE(img.loadFromFile(e.path().string())) << what;
            const auto l = report::readLayout(e.path().string());
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
            // the data (every panel of a multiplot) at least 30 % of the picture: no picture
            // half legend (measured before this test: formation.run.png's plot 26 %)
            const double dataShare =
                double(l->data.width()) * l->data.height() * l->panels / (double(W) * H);
            if (dataShare < leastData) leastData = dataShare, leastDataOf = what;
            EXPECT_GE(dataShare, 0.3) << what;
            // whatever is beside or below the data (legend, key, colour box) no larger than
            // the data: a legend does not take half the picture
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
                if (*l->inkShare < leastShare) leastShare = *l->inkShare, leastShareOf = what;
                EXPECT_GT(*l->inkShare, 0.5) << what << ": its drawing is mostly empty";
            }
        }
    }
    // every method's run drew pictures: the truth timeline's four at least
    EXPECT_EQ(picturesPerRun.size(), 5u);
    for (const auto& [name, n] : picturesPerRun) EXPECT_GE(n, 4) << name;
    std::cout << "least content share: " << leastShare << " (" << leastShareOf
              << "), least data share: " << leastData << " (" << leastDataOf << ")\n";
}
