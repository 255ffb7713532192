// Rawlog I/O in both MRPT formats, bad files, TUM trajectories, metrics.
#include <gtest/gtest.h>
#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/Metrics.h>
#include <mrloc/common/ObservationCheck.h>
#include <mrloc/common/Rawlog.h>
#include <mrloc/common/Trajectory.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/io/CFileOutputStream.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBeaconRanges.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/poses/CPose3DInterpolator.h>
#include <mrpt/serialization/CArchive.h>

#include <filesystem>
#include <fstream>

using namespace mrloc;
using mrpt::obs::CObservationBeaconRanges;
using mrpt::obs::CObservationOdometry;

namespace {

/** A fresh path in the test temp directory (left-overs of earlier runs removed). */
std::string tmp(const std::string& name) {
    const std::string p = testing::TempDir() + "/mrloc_io_" + name;
    std::filesystem::remove(p);
    std::filesystem::remove(p + ".tmp");
    return p;
}

CObservationBeaconRanges::Ptr ranges(double t, float r) {
    auto o = CObservationBeaconRanges::Create();
    o->sensorLabel = "r1.beacons";
    o->timestamp = mrpt::Clock::fromDouble(1000 + t);
    CObservationBeaconRanges::TMeasurement m;
    m.beaconID = 7;
    m.sensedDistance = r;
    o->sensedData.push_back(m);
    return o;
}

}  // namespace

TEST(Rawlog, ObservationsOnlyRoundTrip) {
    const std::string path = tmp("obs.rawlog");
    {
        common::RawlogWriter w(path);
        for (int i = 0; i < 100; ++i) w.write(*ranges(0.1 * i, float(i)));
        EXPECT_FALSE(std::filesystem::exists(path));  // only the temporary name until commit
        w.commit();
    }
    common::RawlogReader r(path);
    int i = 0;
    for (mrpt::obs::CObservation::Ptr obs; r.next(obs); ++i) {
        auto b = std::dynamic_pointer_cast<CObservationBeaconRanges>(obs);
        ASSERT_TRUE(b);
        EXPECT_EQ(b->sensedData.at(0).sensedDistance, float(i));
        EXPECT_EQ(b->sensorLabel, "r1.beacons");
    }
    EXPECT_EQ(i, 100);
    EXPECT_EQ(r.format(), common::RawlogFormat::ObservationsOnly);
}

TEST(Rawlog, UncommittedWriterLeavesNoFile) {
    const std::string path = tmp("aborted.rawlog");
    {
        common::RawlogWriter w(path);
        w.write(*ranges(0, 1));
    }
    EXPECT_FALSE(std::filesystem::exists(path));
    EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
}

TEST(Rawlog, ActionsAndSensoryFramesAreFlattenedWithIntegratedOdometry) {
    const std::string path = tmp("sf.rawlog");
    {
        mrpt::io::CFileGZOutputStream f(path);
        auto a = mrpt::serialization::archiveFrom(f);
        for (int i = 0; i < 5; ++i) {
            mrpt::obs::CActionCollection acts;
            mrpt::obs::CActionRobotMovement2D move;
            move.timestamp = mrpt::Clock::fromDouble(1000 + i);
            mrpt::obs::CActionRobotMovement2D::TMotionModelOptions opts;
            move.computeFromOdometry(mrpt::poses::CPose2D(0.5, 0, M_PI / 2), opts);
            acts.insert(move);
            mrpt::obs::CSensoryFrame sf;
            sf.insert(ranges(i, float(i)));
            a << acts << sf;
        }
    }
    common::RawlogReader r(path);
    std::vector<mrpt::poses::CPose2D> odo;
    int nRanges = 0;
    for (mrpt::obs::CObservation::Ptr obs; r.next(obs);) {
        if (auto o = std::dynamic_pointer_cast<CObservationOdometry>(obs)) {
            EXPECT_EQ(o->sensorLabel, common::kActionOdometryLabel);
            odo.push_back(o->odometry);
        } else if (std::dynamic_pointer_cast<CObservationBeaconRanges>(obs)) {
            ++nRanges;
        }
    }
    EXPECT_EQ(r.format(), common::RawlogFormat::ActionsSensoryFrames);
    EXPECT_EQ(nRanges, 5);
    ASSERT_EQ(odo.size(), 5u);
    // Four increments of (0.5 forward, +90 deg) close a square: back at the origin.
    EXPECT_NEAR(odo[3].x(), 0.0, 1e-9);
    EXPECT_NEAR(odo[3].y(), 0.0, 1e-9);
    EXPECT_NEAR(odo[1].x(), 0.5, 1e-9);
    EXPECT_NEAR(odo[1].y(), 0.5, 1e-9);
}

TEST(Rawlog, MissingEmptyTruncatedAndWrongClassAreClearErrors) {
    EXPECT_THROW(common::RawlogReader(tmp("nope.rawlog")), Error);
    const std::string empty = tmp("empty.rawlog");
    { std::ofstream touch(empty); }
    try {
        common::RawlogReader r(empty);
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("the file is empty"), std::string::npos) << e.what();
    }

    // Truncate a rawlog in the middle of its last object: a .gz one (the stream's end is
    // missing) and a plain one (MRPT's reader hits the end inside the entry).
    auto truncated = [&](bool gz) -> std::string {
        const std::string full = tmp(gz ? "full.rawlog" : "plain.rawlog");
        if (gz) {
            common::RawlogWriter w(full, /*compressionLevel=*/0);
            for (int i = 0; i < 20; ++i) w.write(*ranges(i, 1));
            w.commit();
        } else {
            mrpt::io::CFileOutputStream f(full);
            auto a = mrpt::serialization::archiveFrom(f);
            for (int i = 0; i < 20; ++i) a << *ranges(i, 1);
        }
        std::string bytes;
        {
            std::ifstream in(full, std::ios::binary);
            bytes.assign(std::istreambuf_iterator<char>(in), {});
        }
        const std::string cut = tmp(gz ? "cut.rawlog" : "cut_plain.rawlog");
        {
            std::ofstream out(cut, std::ios::binary);
            out.write(bytes.data(), std::streamsize(bytes.size() - 40));
        }
        try {
            common::RawlogReader r(cut);
        } catch (const Error& e) {
            return e.what();
        }
        return "a truncated rawlog opened as complete";
    };
    const std::string gzCut = truncated(true);
    EXPECT_NE(gzCut.find("mrloc_io_cut.rawlog: the gzip stream stops at byte"), std::string::npos)
        << gzCut;
    EXPECT_NE(gzCut.find("truncated"), std::string::npos) << gzCut;
    const std::string plainCut = truncated(false);
    EXPECT_NE(plainCut.find("mrloc_io_cut_plain.rawlog: cannot read entry 20 (truncated"),
              std::string::npos)
        << plainCut;

    // A serialized object that is no observation: a pose interpolator.
    const std::string wrong = tmp("wrong.rawlog");
    {
        mrpt::io::CFileGZOutputStream f(wrong);
        auto a = mrpt::serialization::archiveFrom(f);
        a << mrpt::poses::CPose3DInterpolator();
    }
    try {
        common::RawlogReader r(wrong);
        mrpt::obs::CObservation::Ptr obs;
        r.next(obs);
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("CPose3DInterpolator"), std::string::npos) << e.what();
    }

    // Not a rawlog at all.
    const std::string text = tmp("text.rawlog");
    { std::ofstream(text) << "hello, this is not a rawlog\n"; }
    EXPECT_THROW(
        {
            common::RawlogReader r(text);
            mrpt::obs::CObservation::Ptr obs;
            r.next(obs);
        },
        Error);
}

// A pose known at one instant carried on by odometry (omnivision's layout, polymap's start):
// odometry driving along its x at 1 m/s, read every second; the pose at t0 = 1.5 s faces +y,
// so each later reading moves it along +y by what the odometry moved since 1.5 s.
TEST(Trajectory, APoseIsCarriedOnByTheOdometrysMotionSinceItsTime) {
    common::Trajectory odometry;
    for (int k = 0; k <= 3; ++k)
        odometry.push_back({double(k), mrpt::poses::CPose3D(k, 0, 0, 0, 0, 0)});
    const mrpt::poses::CPose3D pose(10, 5, 0, M_PI / 2, 0, 0);
    const auto carried = common::carriedByOdometry(pose, 1.5, odometry);
    ASSERT_EQ(carried.size(), 3u);  // the pose, then the readings at 2 and 3 s
    EXPECT_EQ(carried[0].t, 1.5);
    EXPECT_EQ(carried[1].t, 2.0);
    EXPECT_EQ(carried[2].t, 3.0);
    for (const auto& [i, y] : std::vector<std::pair<size_t, double>>{{0, 5}, {1, 5.5}, {2, 6.5}}) {
        EXPECT_NEAR(carried[i].pose.x(), 10, 1e-12) << i;
        EXPECT_NEAR(carried[i].pose.y(), y, 1e-12) << i;
        EXPECT_NEAR(carried[i].pose.yaw(), M_PI / 2, 1e-12) << i;
    }
    // odometry that does not reach t0, or none: the pose alone
    EXPECT_EQ(common::carriedByOdometry(pose, 3.5, odometry).size(), 1u);
    EXPECT_EQ(common::carriedByOdometry(pose, 1.5, {}).size(), 1u);
}

TEST(Trajectory, TumRoundTripInterpolationAndBadLines) {
    common::Trajectory t = {{10.0, mrpt::poses::CPose3D(0, 0, 0, 0, 0, 0)},
                            {11.0, mrpt::poses::CPose3D(1, 2, 0, M_PI / 2, 0, 0)}};
    const std::string p = tmp("traj.txt");
    common::saveTum(p, t);
    const auto back = common::loadTum(p);
    ASSERT_EQ(back.size(), 2u);
    EXPECT_NEAR(back[1].pose.yaw(), M_PI / 2, 1e-9);
    EXPECT_NEAR(back[1].pose.y(), 2.0, 1e-9);
    const auto mid = common::interpolate(back, 10.5);
    ASSERT_TRUE(mid);
    EXPECT_NEAR(mid->x(), 0.5, 1e-9);
    EXPECT_NEAR(mid->yaw(), M_PI / 4, 1e-9);
    EXPECT_FALSE(common::interpolate(back, 12.0));

    const std::string bad = tmp("bad.txt");
    { std::ofstream(bad) << "# header\n1 2 3\n"; }
    try {
        common::loadTum(bad);
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("bad.txt:2"), std::string::npos) << e.what();
    }
    EXPECT_EQ(common::groundTruthPath("a/run.rawlog", "r1"), "a/run.r1.gt.txt");
}

TEST(Metrics, StatsOfKnownValues) {
    const auto s = common::computeStats({3, 4, 0, 5, 1, 2});
    EXPECT_EQ(s.n, 6u);
    EXPECT_DOUBLE_EQ(s.mean, 2.5);
    EXPECT_DOUBLE_EQ(s.max, 5);
    EXPECT_DOUBLE_EQ(s.median, 2.5);
    EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(55.0 / 6.0));
    EXPECT_DOUBLE_EQ(common::percentile({0, 10}, 95), 9.5);
}

TEST(Rawlog, AnObservationMrptRefusesToWriteIsRefusedForItsCauseNotTheDisk) {
    // a landmark twice in one CObservationBearingRange: MRPT's writer throws "Duplicate
    // landmark ID", which mrloc once reported as "(is the disk full?)"; ObservationCheck
    // refuses it first, naming the landmark
    auto o = mrpt::obs::CObservationBearingRange::Create();
    o->sensorLabel = "r1.camera";
    o->sensedData.push_back({3.0f, 0.1f, 0.0f, 14, {}});
    o->sensedData.push_back({3.1f, 0.2f, 0.0f, 14, {}});
    const std::string path = tmp("duplicate_landmark.rawlog");
    {
        common::RawlogWriter w(path);
        try {
            w.write(*o);
            ADD_FAILURE() << "MRPT wrote a landmark twice";
        } catch (const Error& e) {
            const std::string what = e.what();
            EXPECT_EQ(what.find("disk"), std::string::npos) << what;
            EXPECT_NE(what.find("Duplicate landmark ID=14"), std::string::npos) << what;
        }
    }
    EXPECT_FALSE(std::filesystem::exists(path));
    common::ObservationCheck check;
    try {
        check.check(*o);
        ADD_FAILURE() << "a landmark twice passed the check";
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "landmark 14 is seen twice in one observation");
    }
    o->sensedData[1].landmarkID = mrpt::obs::INVALID_LANDMARK_ID;  // without IDs: any number of them
    o->sensedData[0].landmarkID = mrpt::obs::INVALID_LANDMARK_ID;
    EXPECT_NO_THROW(check.check(*o));
}
