// The seed-and-grow search's image lookup (modules/omnivision/src/LayoutGrowth.h, private):
// the nearest unlabelled image within a tolerance, across the seam at +-180 degrees.
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
