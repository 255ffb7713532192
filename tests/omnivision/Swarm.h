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

}  // namespace mrloc::testing_omni
