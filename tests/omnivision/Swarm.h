#pragma once
// Synthetic swarms for the omnivision tests and benchmarks: random robots in a square,
// the views their cameras give (sim's bearings mode geometry) and the true labels.
#include <mrloc/omnivision/OmniCamera.h>
#include <mrloc/omnivision/TriangleSearch.h>
#include <mrpt/random/RandomGenerators.h>

#include <algorithm>

namespace mrloc::testing_omni {

struct Swarm {
    std::vector<mrpt::poses::CPose2D> poses;
    omnivision::Snapshot snapshot;
    omnivision::Labels truth;  ///< [robot][image] -> robot
};

/** Views of robots at `poses` with Gaussian bearing noise (deg). */
inline Swarm viewsOf(std::vector<mrpt::poses::CPose2D> poses, double sigmaDeg, unsigned seed,
                     double maxRange = 0, double markerRadius = 0.05) {
    mrpt::random::CRandomGenerator rng(seed);
    omnivision::OmniCameraOptions o;
    o.maxRange = maxRange;
    o.markerRadius = markerRadius;
    Swarm s;
    s.poses = std::move(poses);
    for (size_t i = 0; i < s.poses.size(); ++i) {
        const auto seen = omnivision::sightingsOf(s.poses, i, o);
        std::vector<std::pair<double, int>> bt;
        for (size_t k = 0; k < seen.bearings.size(); ++k)
            bt.push_back(
                {seen.bearings[k] + rng.drawGaussian1D(0, sigmaDeg * M_PI / 180), seen.robots[k]});
        std::vector<double> raw;
        for (const auto& [b, r] : bt) raw.push_back(b);
        auto view = omnivision::makeView(raw, "swarm");
        std::vector<int> labels(view.size(), -1);
        for (const auto& [b, r] : bt) {
            const auto wrapped = omnivision::makeView({b}, "swarm").bearings[0];
            const auto it = std::lower_bound(view.bearings.begin(), view.bearings.end(), wrapped);
            labels[size_t(it - view.bearings.begin())] = r;
        }
        s.snapshot.views.push_back(std::move(view));
        s.truth.push_back(std::move(labels));
    }
    return s;
}

/** n robots uniformly in a side x side square, at least minSeparation apart; markers of
 *  markerRadius block the lines of sight (the camera's band is 0.15 m). */
inline Swarm randomSwarm(size_t n, unsigned seed, double sigmaDeg, double side = 20,
                         double minSeparation = 1.0, double maxRange = 0,
                         double markerRadius = 0.05) {
    mrpt::random::CRandomGenerator rng(seed);
    std::vector<mrpt::poses::CPose2D> poses;
    while (poses.size() < n) {
        const double x = rng.drawUniform(0, side), y = rng.drawUniform(0, side);
        if (std::all_of(poses.begin(), poses.end(), [&](const auto& p) {
                return std::hypot(p.x() - x, p.y() - y) >= minSeparation;
            }))
            poses.emplace_back(x, y, rng.drawUniform(-M_PI, M_PI));
    }
    return viewsOf(std::move(poses), sigmaDeg, seed + 7919, maxRange, markerRadius);
}

/** Seed 000 section 3's two instants: a random swarm at t_b, and at t_e the same after every
 *  robot but A = 0 and B = 1 drove `step` m in a random direction (turning up to 0.2 rad).
 *  A's image of B and B's of A are the same image at both instants. */
constexpr double kThinMarker = 1e-3;  ///< m: every robot sees every other
struct StopAndGo {
    Swarm before, after;
    std::vector<double> travelled, turned;  ///< per robot: m, rad (the odometer's)
};
inline StopAndGo stopAndGo(size_t n, unsigned seed, double sigmaDeg, double side, double step,
                           double markerRadius = kThinMarker) {
    StopAndGo s;
    s.before = randomSwarm(n, seed, sigmaDeg, side, 1.0, 0, markerRadius);
    mrpt::random::CRandomGenerator rng(seed);
    auto moved = s.before.poses;
    s.travelled.assign(n, 0);
    s.turned.assign(n, 0);
    for (size_t r = 2; r < n; ++r) {
        const double dir = rng.drawUniform(-M_PI, M_PI);
        s.travelled[r] = step;
        s.turned[r] = rng.drawUniform(-0.2, 0.2);
        moved[r] =
            mrpt::poses::CPose2D(moved[r].x() + step * std::cos(dir),
                                 moved[r].y() + step * std::sin(dir), moved[r].phi() + s.turned[r]);
    }
    s.after = viewsOf(moved, sigmaDeg, seed + 100, 0, markerRadius);
    const auto imageOf = [](const Swarm& sw, size_t r, int who) {
        const auto& t = sw.truth[r];
        return size_t(std::find(t.begin(), t.end(), who) - t.begin());
    };
    for (size_t r : {0u, 1u}) {
        const size_t was = imageOf(s.before, r, int(1 - r)), is = imageOf(s.after, r, int(1 - r));
        if (was < s.before.truth[r].size() && is < s.after.truth[r].size())
            s.after.snapshot.views[r].bearings[is] = s.before.snapshot.views[r].bearings[was];
    }
    return s;
}

}  // namespace mrloc::testing_omni
