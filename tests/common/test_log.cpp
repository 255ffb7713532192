// The log the app passes down (common/Log.h, issue 52): a run's warnings and its progress go
// to the Log it is given, and nothing below the app writes to stderr itself.
#include <gtest/gtest.h>
#include <mrloc/common/LocalizationRun.h>
#include <mrloc/common/Log.h>
#include <mrloc/common/Progress.h>
#include <mrloc/common/Rawlog.h>
#include <mrpt/obs/CObservationOdometry.h>

#include <chrono>
#include <thread>
#include <vector>

using namespace mrloc;

namespace {

/** Keeps what it is told. */
class KeptLog final : public common::Log {
 public:
    mutable std::vector<std::string> warnings, shown;
    void warning(const std::string& line) const override { warnings.push_back(line); }
    bool showsProgress() const override { return true; }
    bool redraws() const override { return true; }  // a terminal: drawn at once
    void progress(const std::string& text) const override { shown.push_back(text); }
    void clearProgress() const override {}
};

/** Odometry in, odometry out: every observation used. */
class EchoLocalizer final : public common::Localizer {
 public:
    void configure(const mrpt::config::CConfigFileBase&) override {}
    void saveConfig(mrpt::config::CConfigFileBase&) const override {}
    void process(const mrpt::obs::CObservation::Ptr& obs) override {
        if (const auto o = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(obs))
            track_["r1"].push_back(
                {mrpt::Clock::toDouble(o->timestamp), mrpt::poses::CPose3D(o->odometry)});
    }
    common::Trajectories estimates() const override { return track_; }
    common::ObservationUse observationUse() const override {
        const size_t n = track_.count("r1") ? track_.at("r1").size() : 0;
        return {"odometry (CObservationOdometry)", n, n, {}};
    }

 private:
    common::Trajectories track_;
};

}  // namespace

TEST(Log, ARunsWarningsGoToTheLogItIsGivenNotToStderr) {
    const std::string dir = testing::TempDir() + "/log_run";
    const std::string rawlog = testing::TempDir() + "/log_run.rawlog";
    {
        common::RawlogWriter w(rawlog);
        for (int i = 0; i < 10; ++i) {
            mrpt::obs::CObservationOdometry o;
            o.sensorLabel = "r1.odometry";
            o.timestamp = mrpt::Clock::fromDouble(1000.0 + 0.1 * i);
            o.odometry = mrpt::poses::CPose2D(0.1 * i, 0, 0);
            w.write(o);
            if (i == 4) w.write(o);  // an exact copy: left out, with a warning
        }
        w.commit();
    }
    KeptLog log;
    common::LocalizationRunOptions o{"echo", rawlog, dir, &log};
    EchoLocalizer localizer;
    testing::internal::CaptureStderr();
    common::runLocalization(localizer, o);
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
    ASSERT_EQ(log.warnings.size(), 1u);
    EXPECT_EQ(log.warnings[0], "rawlog " + rawlog +
                                   ": 1 'r1.odometry' observation(s) were exact copies of the one "
                                   "before (same time stamp): left out");

    // the silent log, the default, says nothing anywhere
    common::LocalizationRunOptions silent{"echo", rawlog, dir + "2"};
    EchoLocalizer again;
    testing::internal::CaptureStderr();
    common::runLocalization(again, silent);
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}

TEST(Log, ProgressIsToldToTheLogOnceWorkTakesASecond) {
    KeptLog log;
    {
        common::Progress p("counting", 3, log);
        p.update(1);  // under a second: nothing
        EXPECT_TRUE(log.shown.empty());
        std::this_thread::sleep_for(std::chrono::milliseconds(1100));
        p.update(2);
    }
    ASSERT_EQ(log.shown.size(), 1u);
    EXPECT_NE(log.shown[0].find("] counting: "), std::string::npos) << log.shown[0];
    EXPECT_NE(log.shown[0].find("(2 of 3)"), std::string::npos) << log.shown[0];
    common::Progress quiet("counting", 3, common::silentLog());
    quiet.update(1);  // nothing to see, and nothing to crash
}
