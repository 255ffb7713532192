#include <mrloc/framesync/Sonar.h>

#include <algorithm>
#include <cmath>

namespace mrloc::framesync {

FloorSlice::FloorSlice(const sim::World& world, double height)
    : resolution_(world.options().resolution), height_(height) {
    const auto& o = world.options();
    const double r = resolution_;
    // OctoMap's voxels are aligned on multiples of the resolution: cell i is [i r, (i + 1) r).
    // The room's walls are the cells -1 and size / r; one more cell of margin
    i0_ = j0_ = -2;
    nx_ = long(std::ceil(o.sizeX / r)) + 3 - i0_;
    ny_ = long(std::ceil(o.sizeY / r)) + 3 - j0_;
    cells_.assign(size_t(nx_ * ny_), 0);
    const auto& tree = world.octree();
    for (long j = 0; j < ny_; ++j)
        for (long i = 0; i < nx_; ++i) {
            const auto* node = tree.search(float((double(i + i0_) + 0.5) * r),
                                           float((double(j + j0_) + 0.5) * r), float(height));
            cells_[size_t(j * nx_ + i)] = node && tree.isNodeOccupied(node);
        }
}

bool FloorSlice::occupied(long i, long j) const {
    i -= i0_, j -= j0_;
    if (i < 0 || j < 0 || i >= nx_ || j >= ny_) return false;
    return cells_[size_t(j * nx_ + i)] != 0;
}

std::optional<FloorSlice::Hit> FloorSlice::cast(double x, double y, double direction,
                                                double reach) const {
    const double r = resolution_;
    const double ux = std::cos(direction), uy = std::sin(direction);
    long i = long(std::floor(x / r)), j = long(std::floor(y / r));
    if (occupied(i, j)) return std::nullopt;  // the sensor is inside something
    const long si = ux > 0 ? 1 : -1, sj = uy > 0 ? 1 : -1;
    const double dx = std::abs(ux) > 1e-12 ? r / std::abs(ux) : INFINITY;
    const double dy = std::abs(uy) > 1e-12 ? r / std::abs(uy) : INFINITY;
    double tx =
        std::abs(ux) > 1e-12 ? ((ux > 0 ? double(i + 1) * r : double(i) * r) - x) / ux : INFINITY;
    double ty =
        std::abs(uy) > 1e-12 ? ((uy > 0 ? double(j + 1) * r : double(j) * r) - y) / uy : INFINITY;
    while (true) {
        Hit h;
        if (tx < ty) {
            h.distance = tx, h.axis = 0, i += si, tx += dx;
        } else {
            h.distance = ty, h.axis = 1, j += sj, ty += dy;
        }
        if (h.distance > reach) return std::nullopt;
        if (!occupied(i, j)) continue;
        // exposed on the face entered (by construction) and on its neighbour face turned
        // towards the sensor along the other axis: the end of a wall, a corner
        h.corner = h.axis == 0 ? !occupied(i, j - sj) : !occupied(i - si, j);
        return h;
    }
}

std::optional<double> nearestEcho(const FloorSlice& slice, const mrpt::poses::CPose2D& sensor,
                                  const SonarRigOptions& rig) {
    const int rays = std::max(2, int(std::ceil(rig.aperture / rig.fanStep)) + 1);
    const double step = rig.aperture / (rays - 1);
    // a face reflects back only the ray along its normal: the fan's nearest ray to it
    const double specular = step / 2 + 1e-9;
    std::optional<double> best;
    for (int k = 0; k < rays; ++k) {
        const double dir = sensor.phi() - rig.aperture / 2 + k * step;
        const double reach = best ? *best : rig.maxRange;
        const auto hit = slice.cast(sensor.x(), sensor.y(), dir, reach);
        if (!hit) continue;
        const double along = hit->axis == 0 ? std::cos(dir) : std::sin(dir);
        const double incidence = std::acos(std::min(1.0, std::abs(along)));
        if (hit->corner || incidence <= specular) best = hit->distance;
    }
    return best;
}

mrpt::obs::CObservationRange::Ptr readSonars(const std::vector<const FloorSlice*>& slices,
                                             const mrpt::poses::CPose2D& robot,
                                             const SonarRigOptions& rig,
                                             mrpt::random::CRandomGenerator& rng) {
    auto obs = mrpt::obs::CObservationRange::Create();
    obs->minSensorDistance = float(rig.minRange);
    obs->maxSensorDistance = float(rig.maxRange);
    obs->sensorConeApperture = float(rig.aperture);
    for (size_t k = 0; k < rig.mounts.size(); ++k) {
        const auto& mount = rig.mounts[k];
        const mrpt::poses::CPose2D sensor =
            robot + mrpt::poses::CPose2D(mount.pose.x(), mount.pose.y(), mount.pose.yaw());
        const auto echo = nearestEcho(*slices.at(k), sensor, rig);
        const double noise = rng.drawGaussian1D(0, rig.sigma);
        double range = 0;  // MRPT's CObservationRange: 0 means no echo
        if (echo) range = *echo + noise;
        if (range <= rig.minRange || range >= rig.maxRange) range = 0;
        mrpt::obs::CObservationRange::TMeasurement m;
        m.sensorID = uint16_t(k);
        m.sensorPose = mrpt::math::TPose3D(mount.pose.asTPose());
        m.sensedDistance = float(range);
        obs->sensedData.push_back(m);
    }
    return obs;
}

}  // namespace mrloc::framesync
