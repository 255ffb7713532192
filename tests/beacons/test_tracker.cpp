// The tracking filter: one bad range, a sudden range bias, a kidnapped robot.
#include <gtest/gtest.h>
#include <mrloc/beacons/BeaconTracker.h>
#include <mrpt/random/RandomGenerators.h>

#include <cmath>

using namespace mrloc;
using mrpt::poses::CPose2D;

namespace {

const beacons::BeaconMap kMap = {
    {1, {0, 0, 2.5}}, {2, {3, 0, 2.5}}, {3, {3, 3, 2.5}}, {4, {0, 3, 2.5}}};

struct Drive {
    beacons::BeaconTracker tracker{kMap, beacons::TrackerOptions{}};
    mrpt::random::CRandomGenerator rng{42};
    CPose2D truth{0.5, 0.5, 0.3};
    double t = 0;

    Drive() {
        beacons::TrackerOptions o;
        o.rangeSigma = 0.01;
        o.fix.knownHeight = 0.0;
        tracker = beacons::BeaconTracker(kMap, o);
    }

    /** One 0.2 s epoch at 0.25 m/s along a gentle curve; `bias` is added to beacon `biased`. */
    std::optional<CPose2D> epoch(double bias = 0, int biased = -1) {
        const CPose2D delta(0.05, 0, 0.02);
        truth = truth + delta;
        odometry = odometry + delta;  // perfect odometry: errors come from the ranges alone
        tracker.onOdometry(odometry);
        t += 0.2;
        mrpt::obs::CObservationBeaconRanges obs;
        for (const auto& [id, b] : kMap) {
            mrpt::obs::CObservationBeaconRanges::TMeasurement m;
            m.beaconID = id;
            m.sensorLocationOnRobot = mrpt::poses::CPoint3D(0, 0, 0.5);
            const double d =
                std::sqrt(std::pow(b.x - truth.x(), 2) + std::pow(b.y - truth.y(), 2) + 4.0);
            m.sensedDistance = float(d + rng.drawGaussian1D(0, 0.01) + (id == biased ? bias : 0));
            obs.sensedData.push_back(m);
        }
        return tracker.onRanges(t, obs);
    }
    double error(const CPose2D& p) const {
        return std::hypot(p.x() - truth.x(), p.y() - truth.y());
    }
    CPose2D odometry{5, -2, 1.0};  // an odometry frame unrelated to the world frame
};

}  // namespace

TEST(BeaconTracker, BootstrapsHeadingFromTwoFixesAndConverges) {
    Drive d;
    std::optional<CPose2D> p;
    for (int k = 0; k < 30; ++k) p = d.epoch();
    ASSERT_TRUE(d.tracker.initialized());
    ASSERT_TRUE(p);
    EXPECT_LT(d.error(*p), 0.02);
    EXPECT_NEAR(std::remainder(p->phi() - d.truth.phi(), 2 * M_PI), 0.0, 0.05);
}

TEST(BeaconTracker, OneBadRangeDoesNotDragTheEstimate) {
    Drive d;
    for (int k = 0; k < 30; ++k) d.epoch();
    const auto before = d.tracker.stats().rangesGated;
    const auto p = d.epoch(/*bias=*/3.0, /*biased=*/2);  // a 3 m late echo
    ASSERT_TRUE(p);
    EXPECT_LT(d.error(*p), 0.03);
    EXPECT_EQ(d.tracker.stats().rangesGated, before + 1);
}

TEST(BeaconTracker, SuddenRangeBiasOnOneBeaconIsRejectedWhileItLasts) {
    Drive d;
    for (int k = 0; k < 30; ++k) d.epoch();
    double worst = 0;
    for (int k = 0; k < 25; ++k) {  // 5 s of +0.5 m on beacon 3
        const auto p = d.epoch(0.5, 3);
        ASSERT_TRUE(p) << "epoch " << k;
        worst = std::max(worst, d.error(*p));
    }
    EXPECT_LT(worst, 0.05);
    for (int k = 0; k < 10; ++k) {
        const auto p = d.epoch();
        ASSERT_TRUE(p) << "epoch " << k;
        worst = std::max(worst, d.error(*p));
    }
    EXPECT_LT(worst, 0.05);
}

TEST(BeaconTracker, KidnappedRobotIsRecoveredByAReset) {
    Drive d;
    for (int k = 0; k < 30; ++k) d.epoch();
    d.truth = CPose2D(d.truth.x() + 1.0, d.truth.y() - 0.6, d.truth.phi());  // carried away
    std::optional<CPose2D> p;
    for (int k = 0; k < 20; ++k) p = d.epoch();
    EXPECT_GE(d.tracker.stats().resets, 1u);
    ASSERT_TRUE(p);
    EXPECT_LT(d.error(*p), 0.05);
}

TEST(BeaconTracker, ChiSquareGateQuantiles) {
    EXPECT_NEAR(beacons::chi2Quantile1(0.95), 3.841459, 1e-5);
    EXPECT_NEAR(beacons::chi2Quantile1(0.999), 10.827566, 1e-5);
}
