// The wall detector (seed 004 sec. 4.1): walls from a sonar passing a flat wall, none from
// a pillar (the line fit's tests), and what a redefinition does to its ERPs. The sonar is
// the simulator's, in an OctoMap world.
#include <gtest/gtest.h>
#include <mrloc/framesync/Sonar.h>
#include <mrloc/framesync/WallDetector.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/math/wrap2pi.h>

#include <cmath>

using namespace mrloc;
using namespace mrloc::framesync;

namespace {

sim::WorldOptions room(double x, double y) {
    sim::WorldOptions w;
    w.sizeX = x, w.sizeY = y, w.height = 1;
    w.resolution = 0.05;
    return w;
}

struct Pass {
    std::vector<Wall> walls;
    WallDetectorCounts counts;
};

/** A left-looking sonar (the rig's defaults) on a robot driving east along y from x0 to x1,
 *  a reading every 3 cm (0.3 m/s at 10 Hz). */
Pass drive(const sim::World& world, double y, double x0, double x1, double sigma,
           WallDetectorOptions options = {}) {
    SonarRigOptions rig;
    rig.sigma = sigma;
    rig.mounts = {{"left", mrpt::poses::CPose3D(0, 0, 0.3, M_PI / 2, 0, 0)}};
    options.halfAperture = rig.aperture / 2;
    const FloorSlice slice(world, 0.3);
    mrpt::random::CRandomGenerator rng(7);
    WallDetector detector(options);
    Pass out;
    for (double x = x0; x <= x1; x += 0.03) {
        const mrpt::poses::CPose2D robot(x, y, 0);
        const auto obs = readSonars({&slice}, robot, rig, rng);
        SonarReading r;
        r.sensor = robot + mrpt::poses::CPose2D(0, 0, M_PI / 2);
        r.range = obs->sensedData[0].sensedDistance;
        r.echo = r.range > 0;
        if (auto w = detector.add(r)) out.walls.push_back(*w);
    }
    if (auto w = detector.flush()) out.walls.push_back(*w);
    out.counts = detector.counts();
    return out;
}

}  // namespace

TEST(WallDetector, ASonarPassingAFlatWallFindsItsLineAndNormal) {
    // the wall y = 3 (the room's), the robot 1.2 m from it, 1 cm range noise
    const sim::World world(room(8, 3));
    const auto pass = drive(world, 1.8, 1, 6, 0.01);
    // 5 m of wall in groups of 1 m. Measured: 6 walls.
    ASSERT_GE(pass.walls.size(), 5u);
    for (const auto& w : pass.walls) {
        // Measured: normals within 0.42 deg, ends within 11 mm of the wall; the tolerances
        // are about twice that. (With only the second ERP of each pair, every normal leaned
        // the same way by 0.7 deg: the noise on r2 - r1 tilts a one-sided fit.)
        EXPECT_NEAR(mrpt::math::wrapToPi(w.normal - M_PI / 2), 0, mrpt::DEG2RAD(0.8));
        EXPECT_NEAR(w.a.y, 3, 0.02);
        EXPECT_NEAR(w.b.y, 3, 0.02);
        EXPECT_GT(w.length(), 0.5);
        EXPECT_LT(w.residual, 0.04);
    }
    // unbiased: the normals' mean error is well under their spread
    double mean = 0;
    for (const auto& w : pass.walls) mean += mrpt::math::wrapToPi(w.normal - M_PI / 2);
    EXPECT_LT(std::abs(mean / double(pass.walls.size())), mrpt::DEG2RAD(0.25));
}

TEST(WallDetector, StandingOrCrawlingKeepsABoundedHistory) {
    // seed 004 pairs each echo with the newest one a baseline back; a robot standing still
    // never has one, and the detector kept every echo and searched them all for each new one
    // (10,000 s of log: over 300 s). Now a standing robot keeps one reading (the one the
    // search would pick) and a crawl at most kMaxHistory.
    WallDetector detector{WallDetectorOptions{}};
    SonarReading r;
    r.sensor = mrpt::poses::CPose2D(1, 1, M_PI / 2);
    r.range = 1.2, r.echo = true;
    for (int i = 0; i < 20000; ++i) detector.add(r);
    EXPECT_EQ(detector.historySize(), 1u);
    for (int i = 0; i < 20000; ++i) {  // 0.1 mm per echo (1 mm/s at 10 Hz): 2 m in all
        r.sensor = mrpt::poses::CPose2D(1 + 1e-4 * i, 1, M_PI / 2);
        detector.add(r);
        ASSERT_LE(detector.historySize(), WallDetector::kMaxHistory);
    }
    EXPECT_EQ(detector.historySize(), WallDetector::kMaxHistory);
    EXPECT_EQ(detector.counts().readings, 40000u);
    // the documented price: 1000 echoes span 0.1 m, under the 0.4 m baseline, so a crawl
    // this slow pairs nothing (standing, the one reading kept pairs nothing either)
    EXPECT_EQ(detector.counts().erps, 0u);
}

TEST(WallDetector, APillarIsNotAWall) {
    // a pillar of radius 0.2 m, 0.8 m from the path; the room's walls beyond the 4 m range
    auto o = room(10, 12);
    o.pillars.push_back({"p", 5, 6.8, 0.2, 1});
    const sim::World world(o);
    const auto pass = drive(world, 6, 2, 8, 0.0);
    EXPECT_TRUE(pass.walls.empty()) << pass.walls.size() << " walls";
    // it did give echoes and ERPs: they were turned down as a wall
    EXPECT_GT(pass.counts.erps, 5u);
    EXPECT_GT(pass.counts.tooShort + pass.counts.offLine + pass.counts.notPerpendicular, 0u);
}

TEST(WallDetector, ThePerpendicularTestTurnsDownACurvedGroupTheResidualLets) {
    // A column of radius 0.5 m seen from 0.5 m while the sonar circles it, always aimed at
    // its centre, over +-0.3 rad: the ERPs lie on an arc of 0.3 m whose sagitta (2.2 cm) the
    // residual bound (4 cm) lets through, but the rays fan out by +-17 deg. Seed 004: the
    // ray and the line "will not meet at right angles".
    WallDetectorOptions o;
    o.minLength = 0.2;
    o.baseline = 0.02;
    o.groupAngle = M_PI;  // keep the arc in one group: this is about the fit's tests
    WallDetector d(o);
    std::optional<Wall> wall;
    for (double a = -0.3; a <= 0.3 + 1e-9; a += 0.005) {
        SonarReading r;
        const double out = -M_PI / 2 + a;  // from the centre to the sensor
        r.sensor = mrpt::poses::CPose2D(std::cos(out), std::sin(out), out + M_PI);
        r.range = 0.5;
        r.echo = true;
        if (auto w = d.add(r)) wall = w;
    }
    if (auto w = d.flush()) wall = w;
    EXPECT_FALSE(wall.has_value());
    EXPECT_EQ(d.counts().notPerpendicular, 1u);
    EXPECT_EQ(d.counts().offLine, 0u);
    // the same arc with a looser right-angle bound (20 deg) passes: the test is what
    // turned it down
    o.maxRayAngle = mrpt::DEG2RAD(20.0);
    WallDetector loose(o);
    size_t walls = 0;
    for (double a = -0.3; a <= 0.3 + 1e-9; a += 0.005) {
        SonarReading r;
        const double out = -M_PI / 2 + a;
        r.sensor = mrpt::poses::CPose2D(std::cos(out), std::sin(out), out + M_PI);
        r.range = 0.5;
        r.echo = true;
        walls += loose.add(r).has_value();
    }
    walls += loose.flush().has_value();
    EXPECT_EQ(walls, 1u);
}

TEST(WallDetector, DropForgetsTheOldFrameAndTransformCarriesItOver) {
    const sim::World world(room(8, 3));
    SonarRigOptions rig;
    rig.sigma = 0;
    rig.mounts = {{"left", mrpt::poses::CPose3D(0, 0, 0.3, M_PI / 2, 0, 0)}};
    const FloorSlice slice(world, 0.3);
    mrpt::random::CRandomGenerator rng(1);
    WallDetectorOptions o;
    o.halfAperture = rig.aperture / 2;
    // feed 0.8 m of the wall, redefine the frame, feed 0.5 m more: with drop, the group
    // restarts (0.5 m < wall_length: no wall yet); with transform, the 1 m group completes
    // and its wall is where the new frame puts it
    const mrpt::poses::CPose2D f(0.1, -0.2, 0.05);  // new = f (+) old
    for (const bool drop : {true, false}) {
        WallDetector d(o);
        std::vector<Wall> walls;
        for (double x = 1; x <= 2.8; x += 0.03) {
            const mrpt::poses::CPose2D truth(x, 1.8, 0);
            const bool after = x > 1.8;
            if (after && x - 0.03 <= 1.8) drop ? d.drop() : d.transform(f);
            const auto obs = readSonars({&slice}, truth, rig, rng);
            SonarReading r;
            r.sensor = (after ? f + truth : truth) + mrpt::poses::CPose2D(0, 0, M_PI / 2);
            r.range = obs->sensedData[0].sensedDistance;
            r.echo = true;
            if (auto w = d.add(r)) walls.push_back(*w);
        }
        if (drop) {
            EXPECT_TRUE(walls.empty());
        } else {
            ASSERT_FALSE(walls.empty());
            // the wall y = 3 in the new frame: normal turned by 0.05 rad, the line through
            // f (+) (x, 3)
            for (const auto& w : walls) {
                EXPECT_NEAR(w.normal, M_PI / 2 + 0.05, 1e-3);
                EXPECT_NEAR(w.distanceFrom(composePoint(f, {2, 1.8})), 1.2, 2e-3);
            }
        }
    }
}
