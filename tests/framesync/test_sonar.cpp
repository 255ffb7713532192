// The simulated sonar in the world's OctoMap: specular echoes give the perpendicular
// distance only while the wall's normal is inside the cone, a pillar echoes diffusely,
// nothing comes back beyond the maximum range, and the noise has the INI's spread.
#include <gtest/gtest.h>
#include <mrloc/framesync/FramesyncPayload.h>
#include <mrloc/framesync/Sonar.h>
#include <mrpt/core/bits_math.h>

#include <cmath>

using namespace mrloc;
using namespace mrloc::framesync;
using mrpt::DEG2RAD;
using mrpt::poses::CPose2D;

namespace {

sim::World world(double x, double y, std::vector<sim::Pillar> pillars = {}) {
    sim::WorldOptions w;
    w.sizeX = x, w.sizeY = y, w.height = 1;
    w.resolution = 0.05;
    w.pillars = std::move(pillars);
    return sim::World(w);
}

SonarRigOptions rig(double maxRange = 4) {
    SonarRigOptions r;
    r.maxRange = maxRange;
    return r;
}

}  // namespace

TEST(Sonar, AWallInTheConeGivesThePerpendicularDistance) {
    // the room 6 x 3: the wall y = 3, 2 m above the sensor at (2, 1)
    const auto w = world(6, 3);
    const FloorSlice slice(w, 0.3);
    for (const double tilt : {0.0, 5.0, -10.0, 12.0}) {  // inside the 25-degree cone
        const auto echo = nearestEcho(slice, CPose2D(2, 1, DEG2RAD(90 + tilt)), rig());
        ASSERT_TRUE(echo.has_value()) << tilt;
        EXPECT_NEAR(*echo, 2.0, 1e-3) << tilt;  // not 2 / cos(tilt)
    }
}

TEST(Sonar, AWallSeenObliquelyGivesNoEcho) {
    // tilted 20 deg (the cone reaches 12.5): the wall reflects the sound away. A 3 m wide
    // sensor path far from corners; the other walls beyond the range of 2.5 m.
    const auto w = world(8, 3);
    const FloorSlice slice(w, 0.3);
    EXPECT_FALSE(nearestEcho(slice, CPose2D(4, 1, DEG2RAD(110)), rig(2.5)).has_value());
    EXPECT_FALSE(nearestEcho(slice, CPose2D(4, 1, DEG2RAD(70)), rig(2.5)).has_value());
    EXPECT_TRUE(nearestEcho(slice, CPose2D(4, 1, DEG2RAD(100)), rig(2.5)).has_value());
}

TEST(Sonar, APillarEchoesFromAnyDirection) {
    // a pillar of radius 0.2 m at (4, 2.5): from (4, 1) its near side is 1.3 m away, and
    // still echoes with the sensor turned 10 deg off it (no face need be square to the ray)
    const auto w = world(8, 6, {{"p", 4, 2.5, 0.2, 1}});
    const FloorSlice slice(w, 0.3);
    for (const double off : {0.0, 10.0, -10.0}) {
        const auto echo = nearestEcho(slice, CPose2D(4, 1, DEG2RAD(90 + off)), rig(3));
        ASSERT_TRUE(echo.has_value()) << off;
        EXPECT_NEAR(*echo, 1.3, 0.06) << off;  // one voxel
    }
}

TEST(Sonar, NothingBeyondTheMaximumRangeAndTheReadingSaysNoEcho) {
    const auto w = world(6, 10);
    const FloorSlice slice(w, 0.3);
    EXPECT_FALSE(nearestEcho(slice, CPose2D(2, 1, DEG2RAD(90)), rig(4)).has_value());
    EXPECT_TRUE(nearestEcho(slice, CPose2D(2, 6.5, DEG2RAD(90)), rig(4)).has_value());
    SonarRigOptions r = rig(4);
    r.mounts = {{"left", mrpt::poses::CPose3D(0, 0.15, 0.3, M_PI / 2, 0, 0)}};
    mrpt::random::CRandomGenerator rng(3);
    const auto obs = readSonars({&slice}, CPose2D(2, 1, 0), r, rng);
    ASSERT_EQ(obs->sensedData.size(), 1u);
    EXPECT_EQ(obs->sensedData[0].sensedDistance, 0.0f);  // MRPT: 0 means no echo
    EXPECT_NEAR(obs->sensedData[0].sensorPose.y, 0.15, 1e-12);
    EXPECT_NEAR(obs->sensorConeApperture, DEG2RAD(25.0), 1e-6);
    EXPECT_NEAR(obs->maxSensorDistance, 4, 1e-6);
}

TEST(Sonar, RangeNoiseHasTheGivenSpread) {
    const auto w = world(6, 3);
    const FloorSlice slice(w, 0.3);
    SonarRigOptions r = rig();
    r.sigma = 0.01;
    r.mounts = {{"up", mrpt::poses::CPose3D(0, 0, 0.3, M_PI / 2, 0, 0)}};
    mrpt::random::CRandomGenerator rng(5);
    double sum = 0, sq = 0;
    const int n = 4000;
    for (int i = 0; i < n; ++i) {
        const double d =
            readSonars({&slice}, CPose2D(2, 1, 0), r, rng)->sensedData[0].sensedDistance;
        sum += d, sq += d * d;
    }
    const double mean = sum / n, sd = std::sqrt(sq / n - mean * mean);
    EXPECT_NEAR(mean, 2.0, 0.001);  // 3 standard errors of the mean: 0.0005
    EXPECT_NEAR(sd, 0.01, 0.0006);  // 5 % (the sd's standard error: 1.1 %)
}

// The floor slices a batch job's trials share (issue 56): one set per world and set of mount
// heights, computed anew when either changes; each slice the one sliceWorld computes.
TEST(Sonar, SharedSlicesAreComputedOncePerWorldAndMountHeights) {
    const auto w = std::make_shared<const sim::World>(world(6, 3));
    auto r = rig();
    r.mounts = {{"front", mrpt::poses::CPose3D(0.2, 0, 0.3, 0, 0, 0)},
                {"left", mrpt::poses::CPose3D(0, 0.2, 0.3, M_PI / 2, 0, 0)}};
    const auto a = sharedSlices(w, r);
    ASSERT_EQ(a->size(), 1u);  // one height
    EXPECT_EQ(sharedSlices(w, r), a);
    r.mounts[1].pose.z(0.5);
    const auto b = sharedSlices(w, r);
    EXPECT_NE(b, a);
    EXPECT_EQ(b->size(), 2u);
    const auto other = std::make_shared<const sim::World>(world(6, 3));
    EXPECT_NE(sharedSlices(other, r), b);  // another world, even an equal one
    const auto fresh = sliceWorld(*w, r);
    for (const double z : {0.3, 0.5}) {
        const CPose2D sensor(2, 1, DEG2RAD(90.0));
        EXPECT_EQ(nearestEcho(b->at(z), sensor, r), nearestEcho(fresh->at(z), sensor, r));
    }
}
