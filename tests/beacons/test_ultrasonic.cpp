// The ultrasonic link model: closed-form levels and trigger delays, the beam's directivity,
// and its INI checks.
#include <gtest/gtest.h>
#include <mrloc/beacons/BeaconRanging.h>
#include <mrloc/beacons/BeaconsMethod.h>
#include <mrloc/common/Error.h>
#include <mrloc/sim/Scenario.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/random/RandomGenerators.h>

#include <cmath>
#include <iostream>

using namespace mrloc;

TEST(UltrasonicLink, LevelFallsWithDistanceAndOffAxisAngleAsModelled) {
    const beacons::UltrasonicLink link{beacons::UltrasonicOptions{}};
    EXPECT_NEAR(link.marginDb(1.0, 0), 23.0, 1e-12);
    EXPECT_NEAR(link.marginDb(2.0, 0), 23.0 - 20 * std::log10(2.0) - 1.3, 1e-12);
    // Half the 50 degree beam off the axis: 6 dB down.
    EXPECT_NEAR(link.marginDb(1.0, 25 * M_PI / 180), 17.0, 1e-12);
}

TEST(UltrasonicLink, TriggerDelayAndDetectionThresholdInClosedForm) {
    const beacons::UltrasonicLink link{beacons::UltrasonicOptions{}};
    // A 450 us burst with a 150 us rise time peaks at 1 - e^-3 of its amplitude.
    EXPECT_NEAR(link.detectionThresholdDb(), -20 * std::log10(1 - std::exp(-3.0)), 1e-12);
    EXPECT_NEAR(link.detectionThresholdDb(), 0.4436, 1e-4);
    EXPECT_FALSE(link.triggerDelay(0.4).has_value());
    // 20 dB above the threshold: the envelope crosses it at 10 % of its amplitude.
    EXPECT_NEAR(*link.triggerDelay(20.0), -150e-6 * std::log(0.9), 1e-15);
    // Calibrated on the axis at 1 m: no bias there, a weaker signal reads long.
    EXPECT_NEAR(*link.rangeBias(link.marginDb(1.0, 0)), 0.0, 1e-12);
    EXPECT_GT(*link.rangeBias(3.0), 0.05);  // 3 dB: 343 m/s * ~220 us later
}

TEST(UltrasonicLink, BeamPointedAtTheReceiverAlwaysBeatsOnePointedAway) {
    const beacons::UltrasonicLink link{beacons::UltrasonicOptions{}};
    mrpt::random::CRandomGenerator rng(5);
    for (int k = 0; k < 2000; ++k) {
        const mrpt::math::TPoint3D beacon(rng.drawUniform(0.0, 6.0), rng.drawUniform(0.0, 6.0),
                                          2.5);
        const mrpt::math::TPoint3D rx(rng.drawUniform(0.0, 6.0), rng.drawUniform(0.0, 6.0),
                                      rng.drawUniform(0.0, 1.0));
        const mrpt::math::TPoint3D elsewhere(rng.drawUniform(0.0, 6.0), rng.drawUniform(0.0, 6.0),
                                             0.0);
        const beacons::PanTiltHead head(beacon);
        const auto at = head.aimAt(rx), away = head.aimAt(elsewhere);
        const double d = std::sqrt((rx - beacon).sqrNorm());
        const double onAxis = head.offAxisAngle(at, rx), offAxis = head.offAxisAngle(away, rx);
        ASSERT_NEAR(onAxis, 0.0, 1e-6);
        const double mAt = link.marginDb(d, onAxis), mAway = link.marginDb(d, offAxis);
        ASSERT_GE(mAt, mAway);
        // Heard at least as often, and never later (a later trigger reads longer).
        const auto bAt = link.rangeBias(mAt), bAway = link.rangeBias(mAway);
        if (bAway) {
            ASSERT_TRUE(bAt);
            ASSERT_LE(*bAt, *bAway + 1e-15);
        }
    }
}

namespace {
struct Loaded {
    sim::ScenarioConfig config;
    beacons::BeaconMap beacons;
    beacons::SensorOptions sensors;
    beacons::UltrasonicOptions ultrasonic;
};

Loaded load(const std::string& ultrasonic) {
    mrpt::config::CConfigFileMemory ini(
        "[scenario]\nrobots = r1\n[world]\nsize = 3 3 2.5\n[robot.r1]\nstart = 1 1 0\n"
        "[beacons]\nbeacon_1 = 0 0 2.5\n[ultrasonic]\n" +
        ultrasonic);
    Loaded l;
    l.config = beacons::loadScenario(ini).config;
    l.sensors.loadFromConfigFile(ini, "sensors");
    l.ultrasonic.loadFromConfigFile(ini, "ultrasonic");
    mrloc::common::IniSection section(ini, "beacons");
    l.beacons = beacons::loadBeaconMap(ini, section);
    return l;
}
}  // namespace

TEST(UltrasonicOptions, ZeroBeamAngleIsAnErrorNamingTheKey) {
    EXPECT_NO_THROW(load("beam_angle = 40\n"));
    const std::pair<const char*, const char*> cases[] = {
        {"beam_angle = 0\n", "[ultrasonic] beam_angle"},
        {"beam_angle = -5\n", "[ultrasonic] beam_angle"},
        {"rise_time = 0\n", "[ultrasonic] rise_time"},
        {"pan_min = 90\npan_max = 10\n", "[ultrasonic] pan_"},
        {"beam_agnle = 40\n", "[ultrasonic] beam_agnle: unknown key"}};
    for (const auto& [bad, where] : cases) {
        try {
            load(bad);
            ADD_FAILURE() << "accepted " << bad;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(where), std::string::npos) << e.what();
        }
    }
}

TEST(BeaconRanging, HeadsSlewBeforeTheFirstShotAndShotsFollowTheInterval) {
    const auto cfg = load("slew_rate = 90\n");  // deg/s
    const sim::World world(cfg.config.world);
    beacons::BeaconRanging ranging(world, cfg.beacons, cfg.sensors, cfg.ultrasonic);
    beacons::RangingEpoch e;
    e.robot = "r1";
    e.section = "s";
    e.beacons = {1};
    e.shotInterval = 0.02;
    e.aimPoints = {{2.5, 0, 0}};  // tilt atan2(2.5, 2.5) = 45 degrees from straight down
    const double free = ranging.begin(1.0, e);
    EXPECT_NEAR(free, 1.0 + 0.5 + 0.02, 1e-12);  // 45 degrees at 90 deg/s, then one shot
    EXPECT_NEAR(ranging.angles(1).tilt, M_PI / 4, 1e-12);
    mrpt::random::CRandomGenerator rng(1);
    beacons::ShotLog log;
    const auto at = [](double) { return mrpt::math::TPoint3D(2.5, 0, 0); };
    EXPECT_FALSE(ranging.fireDue(1.49, at, {0, 0, 0}, rng, log));
    EXPECT_TRUE(log.empty());
    const auto obs = ranging.fireDue(1.5, at, {0, 0, 0}, rng, log);
    ASSERT_TRUE(obs);
    ASSERT_EQ(log.size(), 1u);
    EXPECT_NEAR(log[0].start, 1.5, 1e-12);
    EXPECT_NEAR(log[0].offAxis, 0.0, 1e-9);
    EXPECT_FALSE(ranging.inEpoch());
}

TEST(UltrasonicLink, ExpectedRangeBiasIsTheMeanOverTheFading) {
    // Without fading it is rangeBias at the mean level; with it, the mean over N(0, 1.5 dB)
    // levels of the shots that are heard, against a Monte Carlo of 200,000 shots at 1-6 m,
    // on the axis and 20 deg off it (at 6 m, 20 deg, a third of the shots are not heard).
    // Measured: at most 0.36 mm apart (6 m, 20 deg), the Monte Carlo's own error about
    // 0.1 mm there; the bound is 0.5 mm. A 5-point Gauss-Hermite rule was 23 mm off near the
    // detection threshold, where the bias is steep.
    beacons::UltrasonicOptions still;
    still.fadingSigmaDb = 0;
    const beacons::UltrasonicLink noFading{still};
    EXPECT_NEAR(noFading.expectedRangeBias(3.0, 0.1),
                *noFading.rangeBias(noFading.marginDb(3.0, 0.1)), 1e-12);
    EXPECT_NEAR(noFading.expectedRangeBias(1.0, 0), 0.0, 1e-12);  // the calibration point
    const beacons::UltrasonicLink link{beacons::UltrasonicOptions{}};
    mrpt::random::CRandomGenerator rng(11);
    for (const double d : {1.0, 2.0, 4.0, 6.0})
        for (const double offAxis : {0.0, 20 * M_PI / 180}) {
            double sum = 0;
            int heard = 0;
            for (int k = 0; k < 200000; ++k)
                if (const auto b =
                        link.rangeBias(link.marginDb(d, offAxis) + rng.drawGaussian1D(0, 1.5))) {
                    sum += *b;
                    ++heard;
                }
            ASSERT_GT(heard, 0);
            std::cout << d << " m, " << offAxis << " rad: quadrature "
                      << link.expectedRangeBias(d, offAxis) << ", Monte Carlo " << sum / heard
                      << " m\n";
            EXPECT_NEAR(link.expectedRangeBias(d, offAxis), sum / heard, 5e-4)
                << d << " m, " << offAxis << " rad";
        }
    // it grows with distance: 4 m reads about 3 cm long on the axis
    EXPECT_GT(link.expectedRangeBias(4.0, 0), 0.02);
    EXPECT_GT(link.expectedRangeBias(4.0, 0), link.expectedRangeBias(2.0, 0));
}
