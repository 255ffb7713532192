// Ground truth in MRPT's dataset formats: index-stamped "i x y phi" and per-step
// "x y z yaw pitch roll" robot paths, timed by the log's odometry steps, with a frame offset.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/GroundTruthFile.h>

#include <cmath>
#include <fstream>

using namespace mrloc;
using common::GroundTruthSource;

namespace {
std::vector<double> steps(size_t n) {
    std::vector<double> t;
    for (size_t i = 0; i < n; ++i) t.push_back(1000 + 0.5 * double(i));
    return t;
}
}  // namespace

TEST(GroundTruthFile, MrptsIndexedPathsTakeTheirStepsTimesAndTheOffset) {
    GroundTruthSource s;
    s.path = "/usr/share/mrpt/datasets/uwb_ro-localization_demo_GT.txt";
    s.format = "index_x_y_phi";
    s.offset = mrpt::poses::CPose3D(2, 4, 0, 0, 0, 0);
    const auto gt = common::loadGroundTruth(s, steps(342));
    ASSERT_EQ(gt.size(), 342u);  // rows 0 .. 341
    // row 1: "1 0.002535 -0.007280 0.001317", at step 1's time, moved by (2, 4)
    EXPECT_DOUBLE_EQ(gt[1].t, 1000.5);
    EXPECT_NEAR(gt[1].pose.x(), 2.002535, 1e-9);
    EXPECT_NEAR(gt[1].pose.y(), 3.992720, 1e-9);
    EXPECT_NEAR(gt[1].pose.yaw(), 0.001317, 1e-9);
    // fewer steps in the log: the rows past them are left out
    EXPECT_EQ(common::loadGroundTruth(s, steps(100)).size(), 100u);
}

TEST(GroundTruthFile, MrptsRobotPathsOneRowPerStep) {
    GroundTruthSource s;
    s.path = "/usr/share/mrpt/datasets/kf-slam_6D_demo_ground_truth_robot_path.txt";
    s.format = "x_y_z_yaw_pitch_roll";
    std::ifstream in(s.path);
    size_t rows = 0;
    std::string first;
    for (std::string l; std::getline(in, l);)
        if (!l.empty() && l[0] != '%') {
            if (!rows) first = l;
            ++rows;
        }
    const auto gt = common::loadGroundTruth(s, steps(rows));
    ASSERT_EQ(gt.size(), rows);
    std::istringstream f(first);
    double x, y, z, yaw, pitch, roll;
    f >> x >> y >> z >> yaw >> pitch >> roll;
    EXPECT_DOUBLE_EQ(gt[0].pose.x(), x);
    EXPECT_DOUBLE_EQ(gt[0].pose.z(), z);
    EXPECT_NEAR(gt[0].pose.yaw(), yaw, 1e-12);
    EXPECT_NEAR(gt[0].pose.pitch(), pitch, 1e-12);
    EXPECT_NEAR(gt[0].pose.roll(), roll, 1e-12);
}

TEST(GroundTruthFile, AMalformedRowIsNamedByFileAndLine) {
    const std::string path = testing::TempDir() + "/gt_bad.txt";
    std::ofstream(path) << "% header\n0 0 0 0\n1 0.1 zero 0\n";
    GroundTruthSource s;
    s.path = path;
    s.format = "index_x_y_phi";
    try {
        common::loadGroundTruth(s, steps(5));
        FAIL() << "accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("gt_bad.txt:3: 'zero' is not a number"),
                  std::string::npos)
            << e.what();
    }
    std::ofstream(path) << "0 0 0\n";
    EXPECT_THROW(common::loadGroundTruth(s, steps(5)), Error);  // 3 numbers for 4
}

TEST(Covariances, TextFormatRoundTripsExactlyWithUnknownTerms) {
    const std::string path = testing::TempDir() + "/covariance.r.txt";
    common::CovarianceTrack track(2);
    track[0].t = 1700000000.123456789;
    track[0].cov.setZero();
    track[0].cov(0, 0) = 1e-4, track[0].cov(1, 1) = 2e-4, track[0].cov(2, 2) = 3e-3;
    track[0].cov(0, 1) = track[0].cov(1, 0) = -5e-5;
    track[1].t = 1700000001;
    track[1].cov.fill(NAN);
    track[1].cov(0, 0) = 0.25;
    common::saveCovariances(path, track);
    const auto back = common::loadCovariances(path);
    ASSERT_EQ(back.size(), 2u);
    EXPECT_EQ(back[0].t, track[0].t);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) EXPECT_EQ(back[0].cov(i, j), track[0].cov(i, j)) << i << j;
    EXPECT_EQ(back[1].cov(0, 0), 0.25);
    EXPECT_TRUE(std::isnan(back[1].cov(2, 2)));
    EXPECT_TRUE(std::isnan(back[1].cov(1, 0)));  // symmetric: the lower half from the upper
    std::ofstream(path) << "1 2 3\n";
    EXPECT_THROW(common::loadCovariances(path), Error);  // 3 fields for 7, named
}

// issue 51, item 7: a truth (or estimate) of 1e19 m was an "RMSE" of 3.8e17 m, exit 0; every
// trajectory is bounded where it enters (common::checkTrajectoryPose), in each format
TEST(GroundTruthFile, ValuesBeyondTheBoundsAreRefusedAtTheirLine) {
    const std::string dir = testing::TempDir();
    const auto errorOf = [](const GroundTruthSource& s, size_t n) {
        try {
            common::loadGroundTruth(s, steps(n));
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    GroundTruthSource tum;
    tum.path = dir + "/gt_far.txt";
    tum.format = "tum";
    std::ofstream(tum.path) << "1000 0 0 0 0 0 0 1\n1000.5 1e19 0 0 0 0 0 1\n";
    EXPECT_EQ(errorOf(tum, 2), "trajectory " + tum.path +
                                   ":2: position (1e+19, 0, 0) m is not within 1,000 km of the "
                                   "origin");
    std::ofstream(tum.path) << "1000 999999 -999999 0 0 0 0 1\n";  // just inside: read
    EXPECT_EQ(errorOf(tum, 1), "");
    std::ofstream(tum.path) << "1e12 0 0 0 0 0 0 1\n";
    EXPECT_EQ(errorOf(tum, 1), "trajectory " + tum.path + ":1: time 1e+12 s is not within +/-1e11 s");
    GroundTruthSource indexed;
    indexed.path = dir + "/gt_far_indexed.txt";
    indexed.format = "index_x_y_phi";
    std::ofstream(indexed.path) << "0 0 0 0\n1 0 -2e6 0\n";
    EXPECT_EQ(errorOf(indexed, 2), indexed.path +
                                       ":2: position (0, -2e+06, 0) m is not within 1,000 km of "
                                       "the origin");
}

// found by fuzz_json_readers: a TUM quaternion off unit norm reached MRPT's CQuaternion, which
// threw "quaternion is not normalized" past mrloc's errors; it is normalized first, whatever
// its scale, and a zero one is refused at its line
TEST(GroundTruthFile, TumQuaternionsOfAnyScaleAreNormalized) {
    GroundTruthSource tum;
    tum.path = testing::TempDir() + "/gt_quaternions.txt";
    tum.format = "tum";
    std::ofstream(tum.path) << "1000 0 0 0 0 0 1e300 1e300\n1000.5 0 0 0 0 0 3e-5 3e-5\n"
                               "1001 0 0 0 0 0 0.5 0\n";
    const auto gt = common::loadGroundTruth(tum, steps(3));
    ASSERT_EQ(gt.size(), 3u);
    EXPECT_NEAR(gt[0].pose.yaw(), M_PI / 2, 1e-12);
    EXPECT_NEAR(gt[1].pose.yaw(), M_PI / 2, 1e-12);
    EXPECT_NEAR(std::abs(gt[2].pose.yaw()), M_PI, 1e-12);
    std::ofstream(tum.path) << "1000 0 0 0 0 0 0 1e-7\n";
    try {
        common::loadGroundTruth(tum, steps(1));
        ADD_FAILURE() << "a zero quaternion was read";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), "trajectory " + tum.path + ":1: zero quaternion");
    }
}
