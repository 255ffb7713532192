// Pieces of the seed-and-grow search (modules/omnivision/src/LayoutGrowth.h, private): the
// image lookup (the nearest unlabelled image within a tolerance, across the seam at +-180
// degrees) and the final matching of images near the lines to several robots.
#include <gtest/gtest.h>
#include <mrloc/omnivision/Snapshot.h>

#include "../../modules/omnivision/src/LayoutGrowth.h"

using namespace mrloc::omnivision;

namespace {

constexpr double kOneDegree = M_PI / 180;

Snapshot oneView(std::vector<double> degrees) {
    for (double& d : degrees) d *= kOneDegree;
    Snapshot s;
    s.views.push_back(makeView(degrees, "test"));
    return s;
}

}  // namespace

TEST(ImageTable, FindsTheNearestImageAcrossTheSeam) {
    // sorted: -179.9 (0), -90 (1), 10 (2), 179.8 (3)
    const Snapshot s = oneView({10, 179.8, -179.9, -90});
    const seedgrow::ImageTable table(s);
    const double tol = 0.5 * kOneDegree;
    EXPECT_EQ(table.findImage({}, 0, 179.98 * kOneDegree, tol),
              0);  // 0.12 across the seam, 0.18 to 3
    EXPECT_EQ(table.findImage({}, 0, 179.7 * kOneDegree, tol), 3);   // 0.1 deg to image 3
    EXPECT_EQ(table.findImage({}, 0, -179.6 * kOneDegree, tol), 0);  // 0.3 to 0, 0.6 to 3
    EXPECT_EQ(table.findImage({}, 0, -179.8 * kOneDegree, 0.1 * kOneDegree + 1e-9), 0);
    EXPECT_EQ(table.findImage({}, 0, 180.3 * kOneDegree, tol), 0);  // a query a turn away
    EXPECT_EQ(table.findImage({}, 0, -539.7 * kOneDegree, tol), 0);
    EXPECT_EQ(table.findImage({}, 0, 9.4 * kOneDegree, tol), -1);  // 0.6 deg off: none
    EXPECT_EQ(table.findImage({}, 0, -91 * kOneDegree, 2 * kOneDegree), 1);
    // labelled images are passed over for the next nearest in the window
    Labels labels{{7, -1, -1, -1}};
    EXPECT_EQ(table.findImage(labels, 0, 179.95 * kOneDegree, tol), 3);
    labels[0][3] = 8;
    EXPECT_EQ(table.findImage(labels, 0, 179.95 * kOneDegree, tol), -1);
    // a window wider than the circle still finds the nearest (79.8 deg away, across 180)
    EXPECT_EQ(table.findImage({}, 0, 100 * kOneDegree, 4.0), 3);
    EXPECT_EQ(table.findImage({}, 0, 100 * kOneDegree, 4.0 * 100), 3);
}

TEST(ImageTable, AnEmptyViewAndANonFiniteBearingFindNothing) {
    Snapshot s = oneView({0, 90});
    s.views.push_back(makeView({}, "empty"));
    const seedgrow::ImageTable table(s);
    EXPECT_EQ(table.findImage({}, 1, 0, 1), -1);
    EXPECT_EQ(table.findImage({}, 0, INFINITY, 1), -1);
    EXPECT_EQ(table.findImage({}, 0, NAN, 1), -1);
    EXPECT_EQ(table.findImage({}, 0, 89.9 * kOneDegree, 0.2 * kOneDegree), 1);
}

namespace {

/** Robot 0 at the origin, heading 0, with images at `images` (deg); robots 1 and 2 ten
 *  metres away at bearings `robots` (deg), each seeing robot 0 (labelled). */
struct NearLine {
    Snapshot s;
    seedgrow::Layout layout;
    NearLine(std::vector<double> images, std::array<double, 2> robots) {
        s = oneView(std::move(images));
        for (const double b : robots) s.views.push_back(makeView({b * kOneDegree + M_PI}, "w"));
        layout.placed.assign(3, 1);
        layout.order = {0, 1, 2};
        layout.heading.assign(3, 0);
        layout.p = {seedgrow::Vec2::Zero(), 10 * seedgrow::unit(robots[0] * kOneDegree),
                    10 * seedgrow::unit(robots[1] * kOneDegree)};
        layout.labels = {std::vector<int>(s.views[0].size(), -1), {0}, {0}};
        layout.scale = 1;
    }
};

SearchOptions sigma005() {  // the tolerances for a 0.05 deg bearing sigma
    SearchOptions o;
    o.sumTolerance = 6 * 0.05 * kOneDegree;
    o.bearingTolerance = 4 * 0.05 * kOneDegree;
    return o;
}

}  // namespace

TEST(NearLines, ImagesOfRobotsNearlyInLineAreMatchedWhenTheMatchIsBeyondDoubt) {
    const auto o = sigma005();  // each prediction's tolerance: 0.21 deg at 10 m
    {
        // 0.15 deg apart, each image 0.01 deg from its robot: the other way round costs
        // 14 squared sigmas more
        NearLine n({10.01, 10.14, 100}, {10.0, 10.15});
        const seedgrow::ImageTable table(n.s);
        seedgrow::LayoutGrower(table, o).assignNearLines(n.layout);
        EXPECT_EQ(n.layout.labels[0], (std::vector<int>{1, 2, -1}));
    }
    {
        // 0.08 deg apart, the images 0.03 deg in from each: 1.2 squared sigmas between the
        // two matchings, under the 9 required: left unlabelled
        NearLine n({10.03, 10.05}, {10.0, 10.08});
        const seedgrow::ImageTable table(n.s);
        seedgrow::LayoutGrower(table, o).assignNearLines(n.layout);
        EXPECT_EQ(n.layout.labels[0], (std::vector<int>{-1, -1}));
    }
    {
        // one image for the two robots (one hides the other): not matched here
        NearLine n({10.07}, {10.0, 10.15});
        const seedgrow::ImageTable table(n.s);
        seedgrow::LayoutGrower(table, o).assignNearLines(n.layout);
        EXPECT_EQ(n.layout.labels[0], (std::vector<int>{-1}));
    }
    {
        // an image already labelled stays, and its robot is not matched again
        NearLine n({10.01, 10.14}, {10.0, 10.15});
        n.layout.labels[0][1] = 1;
        const seedgrow::ImageTable table(n.s);
        seedgrow::LayoutGrower(table, o).assignNearLines(n.layout);
        EXPECT_EQ(n.layout.labels[0], (std::vector<int>{-1, 1}));
    }
}
