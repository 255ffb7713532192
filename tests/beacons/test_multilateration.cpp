// Multilateration (seed 001 eq. 4-10): exactness, statistics against the Cramer-Rao bound,
// degenerate geometry, mirror ambiguity.
#include <gtest/gtest.h>
#include <mrloc/beacons/Multilateration.h>
#include <mrpt/random/RandomGenerators.h>

#include <cmath>

using namespace mrloc::beacons;
using Eigen::Vector3d;

namespace {

std::vector<RangeMeasurement> exactRanges(const std::vector<Vector3d>& beacons, const Vector3d& x) {
    std::vector<RangeMeasurement> m;
    for (size_t i = 0; i < beacons.size(); ++i)
        m.push_back({beacons[i], (x - beacons[i]).norm(), int(i)});
    return m;
}

// Seed 001's room: 3 x 3 m, beacons on the 2.5 m ceiling.
const std::vector<Vector3d> kCeiling3 = {{0.2, 0.3, 2.5}, {2.8, 0.4, 2.5}, {1.5, 2.9, 2.5}};
const std::vector<Vector3d> kCeiling4 = {{0, 0, 2.5}, {3, 0, 2.5}, {3, 3, 2.5}, {0, 3, 2.5}};
// Not coplanar: two on the ceiling, two lower on the walls.
const std::vector<Vector3d> kMixed4 = {{0, 0, 2.5}, {3, 0, 1.2}, {3, 3, 2.5}, {0, 3, 0.8}};

}  // namespace

TEST(Multilateration, ExactOnNoiseFreeNonCoplanarBothResiduals) {
    const Vector3d truth(1.3, 0.7, 0.5);
    for (auto residual : {Residual::Range, Residual::SquaredRange}) {
        MultilaterationOptions o;
        o.residual = residual;
        const Fix f = multilaterate(exactRanges(kMixed4, truth), o);
        ASSERT_TRUE(f.ok()) << toString(f.status);
        EXPECT_LT((f.position - truth).norm(), 1e-9);
        EXPECT_FALSE(f.mirrorAmbiguous);
        EXPECT_LT(f.rmsResidual, 1e-9);
    }
}

TEST(Multilateration, ExactOnNoiseFreeCeilingBeaconsResolvesMirrorBelow) {
    // Seed 001 Table 2 test points at 500 mm height.
    const std::vector<Vector3d> points = {
        {0.5, 2.5, 0.5}, {0.5, 0.5, 0.5}, {2.5, 0.5, 0.5}, {2.5, 2.5, 0.5}, {1.5, 1.5, 0.5}};
    for (const auto& beacons : {kCeiling3, kCeiling4}) {
        for (const auto& truth : points) {
            for (auto residual : {Residual::Range, Residual::SquaredRange}) {
                MultilaterationOptions o;
                o.residual = residual;
                const Fix f = multilaterate(exactRanges(beacons, truth), o);
                ASSERT_TRUE(f.ok()) << toString(f.status);
                EXPECT_LT((f.position - truth).norm(), 1e-9) << truth.transpose();
                ASSERT_TRUE(f.mirrorAmbiguous);
                // The other solution is the reflection through the ceiling plane z = 2.5.
                EXPECT_NEAR(f.mirrorPosition.z(), 2.5 + (2.5 - truth.z()), 1e-9);
                EXPECT_NEAR(f.mirrorPosition.x(), truth.x(), 1e-9);
            }
        }
    }
}

TEST(Multilateration, MirrorRuleAboveAndHint) {
    const Vector3d truth(1.0, 1.2, 0.5), mirror(1.0, 1.2, 4.5);
    MultilaterationOptions o;
    o.mirror = MirrorRule::Above;
    EXPECT_LT((multilaterate(exactRanges(kCeiling3, truth), o).position - mirror).norm(), 1e-9);
    o.mirror = MirrorRule::NearestToHint;
    o.hint = Vector3d(1, 1, 0);
    EXPECT_LT((multilaterate(exactRanges(kCeiling3, truth), o).position - truth).norm(), 1e-9);
}

TEST(Multilateration, TwoDimensionalWithKnownHeight) {
    const Vector3d truth(2.1, 0.9, 0.5);
    MultilaterationOptions o;
    o.knownHeight = 0.5;
    for (const auto& beacons : {kCeiling3, kCeiling4, kMixed4}) {
        const Fix f = multilaterate(exactRanges(beacons, truth), o);
        ASSERT_TRUE(f.ok()) << toString(f.status);
        EXPECT_LT((f.position - truth).norm(), 1e-9);
        EXPECT_DOUBLE_EQ(f.position.z(), 0.5);
        EXPECT_EQ(f.covariance(2, 2), 0.0);
    }
}

TEST(Multilateration, DegenerateGeometryIsReportedNotGarbage) {
    const Vector3d truth(1, 1, 0.5);
    // Fewer than three ranges.
    EXPECT_EQ(multilaterate(exactRanges({kCeiling4[0], kCeiling4[1]}, truth)).status,
              FixStatus::TooFewRanges);
    // Collinear beacons: a whole circle of solutions around the line.
    const std::vector<Vector3d> line = {{0, 0, 2.5}, {1, 0, 2.5}, {2, 0, 2.5}, {3, 0, 2.5}};
    EXPECT_EQ(multilaterate(exactRanges(line, truth)).status, FixStatus::CollinearBeacons);
    // ... and in 2-D a mirror pair about the line that no rule can pick without a hint.
    MultilaterationOptions o2;
    o2.knownHeight = 0.5;
    EXPECT_EQ(multilaterate(exactRanges(line, truth), o2).status, FixStatus::CollinearBeacons);
    o2.hint = Vector3d(1, 2, 0.5);
    const Fix hinted = multilaterate(exactRanges(line, truth), o2);
    ASSERT_TRUE(hinted.ok());
    EXPECT_LT((hinted.position - truth).norm(), 1e-9);
    // Coincident beacons.
    const std::vector<Vector3d> same = {{1, 1, 2.5}, {1, 1, 2.5}, {1, 1, 2.5}};
    EXPECT_EQ(multilaterate(exactRanges(same, truth)).status, FixStatus::CoincidentBeacons);
    // Receiver in the plane of three beacons: no information across the plane.
    const Vector3d inPlane(1.2, 1.0, 2.5);
    EXPECT_EQ(multilaterate(exactRanges(kCeiling3, inPlane)).status, FixStatus::IllConditioned);
    // Coplanar beacons in a vertical plane: Below/Above cannot choose.
    const std::vector<Vector3d> wall = {{0, 0, 0.5}, {0, 3, 0.5}, {0, 1.5, 2.5}};
    EXPECT_EQ(multilaterate(exactRanges(wall, truth)).status, FixStatus::AmbiguousMirror);
}

TEST(Multilateration, InvalidInputIsRejected) {
    auto m = exactRanges(kMixed4, Vector3d(1, 1, 1));
    m[1].range = std::nan("");
    EXPECT_EQ(multilaterate(m).status, FixStatus::InvalidInput);
    m[1].range = -1;
    EXPECT_EQ(multilaterate(m).status, FixStatus::InvalidInput);
    m[1].range = 1;
    m[2].beacon.x() = INFINITY;
    EXPECT_EQ(multilaterate(m).status, FixStatus::InvalidInput);
}

TEST(Multilateration, GdopAndCovarianceMatchClosedForm) {
    // Receiver at the centre of a symmetric square of ceiling beacons, 2-D: H^T H = diag(a, a)
    // with a = sum cos^2 of the elevation-projected directions; GDOP = sqrt(2 / a).
    const Vector3d truth(1.5, 1.5, 0.5);
    MultilaterationOptions o;
    o.knownHeight = 0.5;
    o.rangeSigma = 0.02;
    const Fix f = multilaterate(exactRanges(kCeiling4, truth), o);
    ASSERT_TRUE(f.ok());
    const double horiz = std::hypot(1.5, 1.5), dist = std::hypot(horiz, 2.0);
    const double a = 4 * 0.5 * (horiz / dist) * (horiz / dist);  // each axis gets half
    EXPECT_NEAR(f.gdop, std::sqrt(2.0 / a), 1e-9);
    EXPECT_NEAR(f.covariance(0, 0), 0.02 * 0.02 / a, 1e-12);
    EXPECT_NEAR(f.covariance(0, 1), 0.0, 1e-12);
    EXPECT_NEAR(cramerRaoBound(kCeiling4, truth, 0.02, true), 0.02 * f.gdop, 1e-12);
}

// Over 10,000 noisy fixes the RMSE of the range-residual solver is within 10 % of the
// Cramer-Rao bound; so is the squared-range solver of the paper on this geometry.
TEST(Multilateration, MonteCarloRmseWithinTenPercentOfCramerRao) {
    const double sigma = 0.01;
    const Vector3d truth(2.2, 0.8, 0.5);
    struct Case {
        std::vector<Vector3d> beacons;
        bool knownHeight;
    };
    for (const Case& c : {Case{kMixed4, false}, Case{kCeiling4, false}, Case{kCeiling4, true}}) {
        for (auto residual : {Residual::Range, Residual::SquaredRange}) {
            mrpt::random::CRandomGenerator rng(1234);
            MultilaterationOptions o;
            o.residual = residual;
            if (c.knownHeight) o.knownHeight = truth.z();
            double sum2 = 0;
            const int n = 10000;
            for (int k = 0; k < n; ++k) {
                auto m = exactRanges(c.beacons, truth);
                for (auto& mi : m) mi.range += rng.drawGaussian1D(0, sigma);
                const Fix f = multilaterate(m, o);
                ASSERT_TRUE(f.ok()) << toString(f.status);
                sum2 += (f.position - truth).squaredNorm();
            }
            const double rmse = std::sqrt(sum2 / n);
            const double crb = cramerRaoBound(c.beacons, truth, sigma, c.knownHeight);
            EXPECT_NEAR(rmse / crb, 1.0, 0.10) << "rmse " << rmse << " crb " << crb;
        }
    }
}

TEST(Multilateration, RobustFixDropsOneOutlier) {
    const Vector3d truth(1.0, 2.0, 0.5);
    const std::vector<Vector3d> five = {
        {0, 0, 2.5}, {3, 0, 2.5}, {3, 3, 2.5}, {0, 3, 2.5}, {1.5, 1.5, 2.5}};
    auto m = exactRanges(five, truth);
    m[2].range += 0.8;  // a late echo
    MultilaterationOptions o;
    o.knownHeight = 0.5;
    int rejected = -1;
    const Fix f = robustMultilaterate(m, o, 0.05, &rejected);
    ASSERT_TRUE(f.ok());
    EXPECT_EQ(rejected, 2);
    EXPECT_LT((f.position - truth).norm(), 1e-9);
}

TEST(Multilateration, RobustFixOfThousandsOfRangesFindsTheOutlierAmongTheSuspects) {
    // 2,000 beacons on a ceiling grid (one observation as a hostile log may hold), 1 mm
    // noise, one late echo of 0.8 m: beyond 12 ranges only the most suspect are refitted
    // (Multilateration.cpp), and the echo must be among them.
    const Vector3d truth(4.3, 7.1, 0.5);
    std::vector<Vector3d> grid;
    for (int i = 0; i < 2000; ++i)
        grid.push_back({0.25 * (i % 40), 0.25 * (i / 40), 2.5 + 0.1 * (i % 3)});
    auto m = exactRanges(grid, truth);
    mrpt::random::CRandomGenerator rng(3);
    for (auto& mi : m) mi.range += rng.drawGaussian1D(0, 0.001);
    m[1234].range += 0.8;
    MultilaterationOptions o;
    o.knownHeight = 0.5;
    int rejected = -1;
    // a threshold under the echo's share of the RMS (0.8 / sqrt(2000) = 18 mm) and above
    // the noise's 1 mm
    const Fix f = robustMultilaterate(m, o, 0.01, &rejected);
    ASSERT_TRUE(f.ok()) << toString(f.status);
    EXPECT_EQ(rejected, 1234);
    EXPECT_LT((f.position - truth).norm(), 1e-3);
}

TEST(Multilateration, RangesWithTheirOwnSigmaAreWeighted) {
    // 2-D, four ceiling beacons; beacon 0's range is 5 cm long.
    const Vector3d truth(1.1, 1.8, 0.5);
    MultilaterationOptions o;
    o.knownHeight = 0.5;
    o.rangeSigma = 0.01;
    auto m = exactRanges(kCeiling4, truth);
    m[0].range += 0.05;
    const Fix plain = multilaterate(m, o);
    ASSERT_TRUE(plain.ok());
    // every range given the options' sigma explicitly: the same fix, bit for bit
    auto same = m;
    for (auto& r : same) r.sigma = o.rangeSigma;
    const Fix equal = multilaterate(same, o);
    EXPECT_EQ(equal.position, plain.position);
    EXPECT_EQ(equal.covariance, plain.covariance);
    // the long range said to be 10 times less sure: the fix moves towards the truth, and the
    // covariance is (sum u u^T / sigma_i^2)^-1 at the solution
    auto weighted = m;
    weighted[0].sigma = 0.1;
    const Fix w = multilaterate(weighted, o);
    ASSERT_TRUE(w.ok());
    EXPECT_LT((w.position - truth).head<2>().norm(),
              0.1 * (plain.position - truth).head<2>().norm());
    Eigen::Matrix2d info = Eigen::Matrix2d::Zero();
    for (const auto& r : weighted) {
        const Vector3d d = w.position - r.beacon;
        const Eigen::Vector2d u = d.head<2>() / d.norm();
        const double s = r.sigma > 0 ? r.sigma : o.rangeSigma;
        info += u * u.transpose() / (s * s);
    }
    const Eigen::Matrix2d cov = info.inverse();
    EXPECT_NEAR(w.covariance(0, 0), cov(0, 0), 1e-12);
    EXPECT_NEAR(w.covariance(0, 1), cov(0, 1), 1e-12);
    EXPECT_NEAR(w.covariance(1, 1), cov(1, 1), 1e-12);
    // the weights do not change the geometry's GDOP
    EXPECT_NEAR(w.gdop, multilaterate(exactRanges(kCeiling4, w.position), o).gdop, 1e-9);
}
