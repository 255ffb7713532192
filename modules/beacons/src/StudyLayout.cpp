// The beacon study's rooms: the test grid, beacons spread by Lloyd's iteration, and their
// heads aimed straight down or at the receiver.
#include <mrloc/beacons/BeaconStudy.h>
#include <mrloc/common/Error.h>

#include <cmath>
#include <limits>

namespace mrloc::beacons {

using mrpt::math::TPoint2D;
using mrpt::math::TPoint3D;

std::vector<TPoint2D> testGrid(double sizeX, double sizeY, double spacing, double wallMargin) {
    if (!(spacing > 0)) throw Error("beacon study: the test grid's spacing must be positive");
    const auto axis = [&](double size) {
        std::vector<double> v;
        const double span = size - 2 * wallMargin;
        if (span < 0) {
            v.push_back(size / 2);
            return v;
        }
        const int n = int(std::floor(span / spacing + 1e-9)) + 1;
        const double start = size / 2 - (n - 1) * spacing / 2;
        for (int i = 0; i < n; ++i) v.push_back(start + i * spacing);
        return v;
    };
    std::vector<TPoint2D> out;
    for (const double y : axis(sizeY))
        for (const double x : axis(sizeX)) out.push_back({x, y});
    return out;
}

BeaconMap spreadBeacons(double sizeX, double sizeY, double ceiling, int n) {
    if (n < 1) throw Error("beacon study: a layout needs at least one beacon");
    // the floor sampled on a grid fine enough that a cell's centroid moves by rounding only
    constexpr int kSamples = 64;
    std::vector<Eigen::Vector2d> samples;
    for (int j = 0; j < kSamples; ++j)
        for (int i = 0; i < kSamples; ++i)
            samples.emplace_back((i + 0.5) * sizeX / kSamples, (j + 0.5) * sizeY / kSamples);
    const auto halton = [](int i, int base) {
        double f = 1, r = 0;
        for (; i > 0; i /= base) f /= base, r += f * (i % base);
        return r;
    };
    std::vector<Eigen::Vector2d> c;
    for (int k = 0; k < n; ++k) c.emplace_back(halton(k + 1, 2) * sizeX, halton(k + 1, 3) * sizeY);
    std::vector<size_t> cell(samples.size());
    for (int iteration = 0; iteration < 300; ++iteration) {  // Lloyd's iteration
        for (size_t s = 0; s < samples.size(); ++s) {
            double best = std::numeric_limits<double>::infinity();
            for (size_t k = 0; k < c.size(); ++k)
                if (const double d = (samples[s] - c[k]).squaredNorm(); d < best)
                    best = d, cell[s] = k;
        }
        std::vector<Eigen::Vector2d> sum(c.size(), Eigen::Vector2d::Zero());
        std::vector<int> count(c.size(), 0);
        for (size_t s = 0; s < samples.size(); ++s) sum[cell[s]] += samples[s], ++count[cell[s]];
        double moved = 0;
        for (size_t k = 0; k < c.size(); ++k)
            if (count[k]) {
                const Eigen::Vector2d m = sum[k] / count[k];
                moved = std::max(moved, (m - c[k]).norm());
                c[k] = m;
            }
        if (moved < 1e-6) break;
    }
    BeaconMap out;
    for (int k = 0; k < n; ++k) out[k + 1] = TPoint3D(c[size_t(k)].x(), c[size_t(k)].y(), ceiling);
    return out;
}

std::map<int, Eigen::Vector3d> straightDown(const BeaconMap& beacons) {
    std::map<int, Eigen::Vector3d> out;
    for (const auto& [id, b] : beacons) out[id] = {b.x, b.y, 0};
    return out;
}

StudyRoom spreadRoom(double sizeX, double sizeY, double ceiling, int n, bool active) {
    StudyRoom r;
    r.sizeX = sizeX;
    r.sizeY = sizeY;
    r.beacons = spreadBeacons(sizeX, sizeY, ceiling, n);
    r.active = active;
    r.fixedAim = straightDown(r.beacons);
    return r;
}

}  // namespace mrloc::beacons
