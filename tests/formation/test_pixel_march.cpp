// The pixel march (every move from rendered frames, off the simulator's clock), the scene it
// builds once, and the camera model its frames go through.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/formation/CameraModel.h>
#include <mrloc/formation/CameraMove.h>
#include <mrloc/formation/FormationExperiment.h>
#include <mrloc/formation/PixelMarch.h>

#include <cmath>
#include <iostream>

using namespace mrloc;

namespace {

/** The pixel mode's default camera (640 x 200, f = 242.5 px). */
formation::PixelMarchOptions defaultPixelOptions() {
    formation::FormationConfig config;
    return formation::pixelMarchOptions(config, config.wheelSpeed);
}

/** The largest level difference of two grey pictures of one size, and the first's mean. */
double greyDifference(const mrpt::img::CImage& a, const mrpt::img::CImage& b) {
    double worst = 0;
    for (size_t v = 0; v < a.getHeight(); ++v)
        for (size_t u = 0; u < a.getWidth(); ++u)
            worst =
                std::max(worst, std::abs(double(*a(int(u), int(v))) - double(*b(int(u), int(v)))));
    return worst;
}
double greyMean(const mrpt::img::CImage& a) {
    double sum = 0;
    for (size_t v = 0; v < a.getHeight(); ++v)
        for (size_t u = 0; u < a.getWidth(); ++u) sum += double(*a(int(u), int(v)));
    return sum / double(a.getWidth() * a.getHeight());
}

using formation::MarkerSighting;

/** Six robots of the starting strip (believed poses, facing east) and what the rear camera of
 *  a robot at `truth` sees of them: each robot's front tag's centre, projected by MRPT's
 *  pose algebra (project), not by the fit's own model. */
struct LatticeView {
    std::vector<mrpt::poses::CPose2D> believed;
    std::vector<MarkerSighting> tags;
};
LatticeView latticeView(const mrpt::poses::CPose2D& truth, const mrpt::img::TCamera& k,
                        const formation::MarkerOptions& m) {
    LatticeView v;
    for (const auto& p : formation::initialStrip(6, 1.5)) v.believed.emplace_back(p.x, p.y, 0);
    const auto camera = formation::rearCameraPose(truth, m.bodySize, m.tagHeight);
    for (size_t r = 0; r < v.believed.size(); ++r) {
        const auto side = formation::Side::Front;
        if (const auto s =
                formation::project(k, camera, formation::markerCentre(v.believed[r], side, m))) {
            auto seen = *s;
            seen.id = formation::markerId(r, side);
            v.tags.push_back(seen);
        }
    }
    return v;
}
}  // namespace

TEST(LatticeFit, RecoversTheRearCamerasPoseFromTheLatticeAndDropsAWrongTag) {
    // A robot east of the strip, facing east (its rear camera on the six robots), 2 cm and
    // 1 degree off the pose the fit starts from.
    const formation::MarkerOptions m;
    const auto k = formation::cameraIntrinsics(485);
    const mrpt::poses::CPose2D start(6.0, 0.65, 0), truth(6.02, 0.63, 1 * M_PI / 180);
    auto view = latticeView(truth, k, m);
    ASSERT_EQ(view.tags.size(), 6u);  // all in the 105-degree view
    auto fit = formation::fitToLattice(view.tags, view.believed, 99, start, k, m, 4);
    ASSERT_TRUE(fit);
    EXPECT_EQ(fit->robots, 6u);
    EXPECT_NEAR(fit->pose.x(), truth.x(), 1e-6);
    EXPECT_NEAR(fit->pose.y(), truth.y(), 1e-6);
    EXPECT_NEAR(fit->pose.phi(), truth.phi(), 1e-7);
    EXPECT_LT(fit->rms, 1e-4);
    // one tag 10 px off (cut at another robot's edge): dropped, the pose still exact
    view.tags[2].u += 10;
    fit = formation::fitToLattice(view.tags, view.believed, 99, start, k, m, 4);
    ASSERT_TRUE(fit);
    EXPECT_EQ(fit->robots, 5u);
    EXPECT_NEAR(fit->pose.x(), truth.x(), 1e-6);
    EXPECT_NEAR(fit->pose.y(), truth.y(), 1e-6);
    // the mover's own tags and unknown robots are not evidence; too few robots: no fit
    view.tags.resize(3);
    view.tags.push_back(view.tags[0]);
    view.tags.back().id = formation::markerId(50, formation::Side::Left);
    EXPECT_FALSE(formation::fitToLattice(view.tags, view.believed, 99, start, k, m, 4));
    EXPECT_FALSE(formation::fitToLattice(view.tags, view.believed, 0, start, k, m, 3));
    EXPECT_TRUE(formation::fitToLattice(view.tags, view.believed, 99, start, k, m, 3));
}

TEST(PixelMarch, LatticeRotationIsTheRotationBetweenTwoCopies) {
    const auto strip = formation::initialStrip(6, 1.5);
    for (const double angle : {0.0, 0.1, -0.7, 3.0}) {
        std::vector<formation::TPoint2D> turned;
        for (const auto& p : strip)
            turned.push_back({5 + std::cos(angle) * p.x - std::sin(angle) * p.y,
                              -2 + std::sin(angle) * p.x + std::cos(angle) * p.y});
        EXPECT_NEAR(formation::latticeRotation(strip, turned), angle, 1e-12);
    }
}

TEST(PixelMarch, NineMetresFromPixelsArriveNearTheLatticeAndRepeat) {
    // formation_pixel.ini's route: 4 robots, 9 m east, every move from the cameras
    const std::vector<formation::TPoint2D> route{{1.5, 0.65}, {10.5, 0.65}};
    const auto o = defaultPixelOptions();
    sim::PinholeCamera camera(formation::renderIntrinsics(o));
    mrpt::random::CRandomGenerator rng(3);
    const auto r = formation::pixelMarch(4, route, {}, o, camera, rng);
    ASSERT_TRUE(r.march.arrived);
    double worstStep = 0;
    for (size_t k = 0; k < r.lateral.size(); ++k)
        worstStep = std::max(worstStep, std::hypot(r.lateral[k], r.longitudinal[k]));
    std::cout << r.march.moves.size() << " moves, " << r.frames << " frames, lost " << r.lostMoves
              << ", final error " << r.march.finalError() << " m, worst step " << worstStep * 1000
              << " mm, rotation " << r.rotation.back() * 180 / M_PI << " deg\n";
    // Measured (seed 3): 11 moves, 116 frames, none lost, 0.096 m at the end, worst step
    // 20.8 mm. Bounds about 1.5 times those (another renderer's rounding moves a tag's
    // corners by a fraction of a pixel, and a march amplifies it).
    EXPECT_EQ(r.march.moves.size(), 11u);
    EXPECT_EQ(r.lostMoves, 0u);
    EXPECT_LT(r.march.finalError(), 0.15);
    EXPECT_LT(worstStep, 0.03);
    EXPECT_LT(double(r.frames) / double(r.march.moves.size()), 14);
    // the same seed, the same march
    mrpt::random::CRandomGenerator again(3);
    const auto s = formation::pixelMarch(4, route, {}, o, camera, again);
    ASSERT_EQ(s.march.moves.size(), r.march.moves.size());
    for (size_t k = 0; k < r.march.moves.size(); ++k) {
        EXPECT_EQ(s.march.moves[k].actual.x, r.march.moves[k].actual.x);
        EXPECT_EQ(s.march.moves[k].actual.y, r.march.moves[k].actual.y);
    }
}

TEST(CameraModel, TheRobotsUndistortionGivesBackTheIdealTags) {
    // fig. 3g from the vertex: five tags in the rear camera's view
    formation::MarkerOptions markers;
    const auto step = formation::buildingStep(1.5, markers);
    const auto k = defaultPixelOptions().camera.intrinsics;
    formation::CameraModelOptions barrel;  // a wide-angle lens
    barrel.k1 = -0.3, barrel.k2 = 0.08, barrel.p1 = 0.002;
    // the lens sees beyond the pinhole picture: the ideal picture is rendered larger
    const auto wide = formation::CameraModel(k, barrel).renderIntrinsics();
    EXPECT_GT(wide.ncols, k.ncols);
    EXPECT_GT(wide.nrows, k.nrows);
    sim::PinholeCamera camera(wide);
    const auto frame = camera.render(
        *step.scene, formation::rearCameraPose(step.vertex, markers.bodySize, markers.tagHeight));
    auto ideal = formation::detectMarkers(frame, 1);  // in the camera's own pinhole frame:
    for (auto& t : ideal) t.u -= wide.cx() - k.cx(), t.v -= wide.cy() - k.cy();
    ASSERT_GE(ideal.size(), 3u);
    mrpt::random::CRandomGenerator rng(1);
    const auto worstShift = [&](const formation::CameraModelOptions& lens) {
        const auto seen = formation::CameraModel(k, lens).see(frame, rng);
        double worst = 0;
        size_t matched = 0;
        for (const auto& t : seen)
            for (const auto& i : ideal)
                if (t.id == i.id)
                    worst = std::max(worst, std::hypot(t.u - i.u, t.v - i.v)), ++matched;
        EXPECT_EQ(matched, ideal.size());
        return worst;
    };
    const double calibrated = worstShift(barrel);
    barrel.calibrationError = 0.3;
    const double miscalibrated = worstShift(barrel);
    barrel.calibrationError = -1;  // the robot does not undistort
    const double raw = worstShift(barrel);
    std::cout << "tag centres off the ideal: calibrated " << calibrated << " px, 30 % off "
              << miscalibrated << " px, not undistorted " << raw << " px\n";
    // Measured: 0.49 px calibrated (the remap's resampling), 12.0 px with 30 % calibration
    // error, 20.8 px without undistortion.
    EXPECT_LT(calibrated, 0.75);
    EXPECT_GT(miscalibrated, 6);
    EXPECT_GT(raw, 10);
}

TEST(CameraModel, NoiseBlurAndExposureAreSeededAndBounded) {
    formation::MarkerOptions markers;
    const auto step = formation::buildingStep(1.5, markers);
    const auto k = defaultPixelOptions().camera.intrinsics;
    sim::PinholeCamera camera(k);
    const auto frame = camera.render(
        *step.scene, formation::rearCameraPose(step.vertex, markers.bodySize, markers.tagHeight));
    formation::CameraModelOptions o;
    o.noise = 6, o.blur = 0.8, o.exposure = 0.8;
    const formation::CameraModel lens(k, o);
    mrpt::random::CRandomGenerator a(5), b(5);
    const auto pa = lens.degrade(frame, a), pb = lens.degrade(frame, b);
    EXPECT_EQ(greyDifference(pa, pb), 0);  // the same seed, the same picture
    mrpt::random::CRandomGenerator c(6);
    EXPECT_GT(greyDifference(pa, lens.degrade(frame, c)), 0);
    // the exposure darkens: the mean level scales by it
    formation::CameraModelOptions dark;
    dark.exposure = 0.5;
    mrpt::random::CRandomGenerator d(1);
    const double ratio = greyMean(formation::CameraModel(k, dark).degrade(frame, d)) /
                         greyMean(formation::CameraModel(k, {}).degrade(frame, d));
    EXPECT_NEAR(ratio, 0.5, 0.01);
    formation::CameraModelOptions bad;
    bad.blur = 11;
    try {
        formation::CameraModel(k, bad);
        FAIL() << "a blur of 11 px was taken";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("camera_blur = 11"), std::string::npos) << e.what();
    }
}

TEST(PixelMarch, TableOneFromPixelsBeatsDeadReckoningAndRepeats) {
    // [formation] pixel_runs on the patrol route at 5.8 rad/s: two pixel marches, each beside
    // a dead-reckoned drive, on every core
    formation::FormationConfig c;
    c.runs = 0, c.cameraStarts = 0, c.pixelRuns = 2;
    c.experimentRoutes = {"patrol"}, c.experimentSpeeds = {5.8};
    const auto e = formation::runFormationExperiment(c);
    ASSERT_EQ(e.pixel.size(), 1u);
    const auto& row = e.pixel[0];
    std::cout << "pixel patrol: " << row.formation << " m (worst " << row.formationMax
              << "), dead reckoning " << row.deadReckoning << " m, lost " << row.lostMoves
              << ", frames " << row.frames << ", rotation " << row.rotation * 180 / M_PI
              << " deg\n";
    EXPECT_EQ(row.runs, 2u);
    EXPECT_EQ(row.arrived, 2u);
    EXPECT_EQ(row.lostMoves, 0);
    // Measured (experiment seed 1): 0.93 m (worst 1.33 m) against dead reckoning's 1.74 m;
    // 20 marches per case: 1.09 m against 1.92 m (doc/formation.md). Bounds: the formation
    // below dead reckoning, and under 2.5 m (the worst of the 20 was 2.09 m).
    EXPECT_LT(row.formation, row.deadReckoning);
    EXPECT_LT(row.formationMax, 2.5);
    ASSERT_EQ(e.steps.size(), 1u);  // every step of the marches, beside fig. 11
    EXPECT_EQ(e.steps[0].source, "pixel_march");
    EXPECT_EQ(e.steps[0].count, 2u * 126u);
    EXPECT_LT(e.steps[0].lateralMean, 0.015);
    // each march draws from its own generator, seeded from its place in the table
    const auto again = formation::runFormationExperiment(c);
    EXPECT_EQ(again.pixel[0].formation, row.formation);
    EXPECT_EQ(again.pixel[0].frames, row.frames);
}
