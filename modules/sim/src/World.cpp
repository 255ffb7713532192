#include <mrloc/common/KeyTable.h>
#include <mrloc/sim/World.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/core/format.h>

#include <algorithm>
#include <cmath>
#include <mutex>

namespace mrloc::sim {

using mrpt::math::TPoint3D;

namespace {

void loadObstacles(common::IniSection& s, WorldOptions& w) {
    s.allowPrefix("obstacle_");
    w.obstacles.clear();
    for (const auto& key : s.keys()) {
        if (key.rfind("obstacle_", 0) != 0) continue;
        const auto v = s.reals(key, {}, 6);
        if (v[0] >= v[3] || v[1] >= v[4] || v[2] >= v[5])
            s.fail(key, "expected xmin ymin zmin xmax ymax zmax with min < max");
        Box b{key.substr(9), {v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
        if (!w.contains(b.min, w.resolution) || !w.contains(b.max, w.resolution))
            s.fail(key, "the obstacle must lie inside the world (size)");
        w.obstacles.push_back(b);
    }
}

void saveObstacles(const WorldOptions& w, mrpt::config::CConfigFileBase& t,
                   const std::string& section) {
    for (const auto& b : w.obstacles)
        t.write(section, "obstacle_" + b.name,
                common::keyListText({b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z}));
}

void loadPillars(common::IniSection& s, WorldOptions& w) {
    s.allowPrefix("pillar_");
    w.pillars.clear();
    for (const auto& key : s.keys()) {
        if (key.rfind("pillar_", 0) != 0) continue;
        const auto v = s.reals(key, {}, 4);
        if (!(v[2] > 0) || !(v[3] > 0)) s.fail(key, "expected x y radius height, both positive");
        Pillar p{key.substr(7), v[0], v[1], v[2], v[3]};
        if (!w.contains({p.x - p.radius, p.y - p.radius, 0}, w.resolution) ||
            !w.contains({p.x + p.radius, p.y + p.radius, p.height}, w.resolution))
            s.fail(key, "the pillar must lie inside the world (size)");
        w.pillars.push_back(p);
    }
}

void savePillars(const WorldOptions& w, mrpt::config::CConfigFileBase& t,
                 const std::string& section) {
    for (const auto& p : w.pillars)
        t.write(section, "pillar_" + p.name, common::keyListText({p.x, p.y, p.radius, p.height}));
}

}  // namespace

const common::KeyTable<WorldOptions>& WorldOptions::keys() {
    using W = WorldOptions;
    static const auto table =
        common::KeyTable<W>("world")
            .custom(
                "size", "m", mrpt::format("at most %g x %g x %g", kMaxSide, kMaxSide, kMaxHeight),
                "room `x y height`; the room is [0, x] x [0, y] x [0, height]",
                [](common::IniSection& s, W& w) {
                    const auto size = s.reals("size", {w.sizeX, w.sizeY, w.height}, 3);
                    for (int i = 0; i < 3; ++i)
                        if (!(size[i] > 0)) s.fail("size", "every extent must be positive");
                    if (size[0] > kMaxSide || size[1] > kMaxSide || size[2] > kMaxHeight)
                        s.fail("size", mrpt::format("at most %g x %g x %g m", kMaxSide, kMaxSide,
                                                    kMaxHeight));
                    w.sizeX = size[0], w.sizeY = size[1], w.height = size[2];
                },
                [](const W& w) { return mrpt::format("%g %g %g", w.sizeX, w.sizeY, w.height); })
            .real("resolution", MRLOC_KEY_FIELD(resolution), {0.005, 1.0}, "m",
                  "OctoMap voxel size; walls and obstacles may fill at most 1e7 voxels, and the "
                  "room must lie within 32000 voxels of the origin")
            .family("obstacle_<name>", "m", "inside the room",
                    "box `xmin ymin zmin xmax ymax zmax`, blocks lines of sight", loadObstacles,
                    saveObstacles)
            .family("pillar_<name>", "m", "inside the room",
                    "vertical cylinder on the floor `x y radius height`: a column, a person, a "
                    "bin (framesync's sonars echo off it diffusely)",
                    loadPillars, savePillars);
    return table;
}

void WorldOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& src,
                                      const std::string& section) {
    *this = WorldOptions{};  // every key absent takes the struct's default: written once
    common::IniSection s(src, section);
    keys().load(s, *this);
    // OctoMap addresses a voxel with 16-bit keys centred on the origin.
    const double octomapReach = 32000 * resolution;
    if (std::max({sizeX, sizeY, height}) + resolution > octomapReach)
        s.fail("size", mrpt::format("beyond OctoMap's reach of %g m at resolution %g m: "
                                    "use a coarser resolution",
                                    octomapReach, resolution));
    if (filledVoxels() > kMaxVoxels)
        s.fail("resolution", mrpt::format("walls and obstacles would fill %.3g voxels, more than "
                                          "the %.3g allowed: use a coarser resolution",
                                          filledVoxels(), kMaxVoxels));
    s.finish();
}

void WorldOptions::saveToConfigFile(mrpt::config::CConfigFileBase& t,
                                    const std::string& section) const {
    keys().save(*this, t, section);
}

double WorldOptions::filledVoxels() const {
    const double r = resolution;
    auto cells = [r](double extent) { return std::ceil(extent / r) + 1; };
    double n = 2 * (cells(sizeX) + cells(sizeY)) * cells(height);  // the four walls
    for (const auto& b : obstacles)
        n += cells(b.max.x - b.min.x) * cells(b.max.y - b.min.y) * cells(b.max.z - b.min.z);
    for (const auto& p : pillars) n += cells(2 * p.radius) * cells(2 * p.radius) * cells(p.height);
    return n;
}

bool WorldOptions::contains(const TPoint3D& p, double m) const {
    return p.x >= -m && p.x <= sizeX + m && p.y >= -m && p.y <= sizeY + m && p.z >= -m &&
           p.z <= height + m;
}

World::World(WorldOptions options)
    : options_(std::move(options)), tree_(std::make_unique<octomap::OcTree>(options_.resolution)) {
    const double r = options_.resolution;
    const double X = options_.sizeX, Y = options_.sizeY, H = options_.height;
    // Side walls one voxel thick, just outside the room.
    fillBox({-r, -r, 0}, {X + r, 0 - 1e-9, H});
    fillBox({-r, Y + 1e-9, 0}, {X + r, Y + r, H});
    fillBox({-r, 0, 0}, {0 - 1e-9, Y, H});
    fillBox({X + 1e-9, 0, 0}, {X + r, Y, H});
    for (const auto& b : options_.obstacles) fillBox(b.min, b.max);
    for (const auto& p : options_.pillars) fillPillar(p);
    tree_->updateInnerOccupancy();
}

void World::fillPillar(const Pillar& p) {
    const double r = options_.resolution;
    // every voxel whose centre lies inside the circle
    for (double x = p.x - p.radius + r / 2; x < p.x + p.radius; x += r)
        for (double y = p.y - p.radius + r / 2; y < p.y + p.radius; y += r) {
            if (std::hypot(x - p.x, y - p.y) > p.radius) continue;
            for (double z = r / 2; z < p.height + r / 2; z += r)
                tree_->updateNode(
                    octomap::point3d(float(x), float(y), float(std::min(z, p.height))), true,
                    /*lazy_eval=*/true);
        }
}

void World::fillBox(const TPoint3D& min, const TPoint3D& max) {
    const double r = options_.resolution;
    for (double x = min.x + r / 2; x < max.x + r / 2; x += r)
        for (double y = min.y + r / 2; y < max.y + r / 2; y += r)
            for (double z = min.z + r / 2; z < max.z + r / 2; z += r)
                tree_->updateNode(
                    octomap::point3d(float(std::min(x, max.x)), float(std::min(y, max.y)),
                                     float(std::min(z, max.z))),
                    true, /*lazy_eval=*/true);
}

std::shared_ptr<const World> sharedWorld(const WorldOptions& options) {
    mrpt::config::CConfigFileMemory saved;  // every key, as effective.ini has them
    options.saveToConfigFile(saved, "world");
    std::string key;
    saved.getContent(key);
    static std::mutex mutex;
    static std::pair<std::string, std::shared_ptr<const World>> last;
    const std::lock_guard<std::mutex> lock(mutex);
    if (!last.second || last.first != key) last = {key, std::make_shared<const World>(options)};
    return last.second;
}

bool World::lineOfSight(const TPoint3D& a, const TPoint3D& b) const {
    const double length = std::sqrt((b - a).sqrNorm());
    // Beacons are mounted on walls and ceilings, so an end point may lie in (or touch) a wall
    // voxel: the ray is cast between points pulled one and a half voxels in from both ends.
    const double skip = 1.5 * options_.resolution;
    if (length <= 2 * skip) return true;
    const TPoint3D u = (b - a) * (1.0 / length);
    const TPoint3D start = a + u * skip;
    const octomap::point3d origin(float(start.x), float(start.y), float(start.z));
    const octomap::point3d dir(float(u.x), float(u.y), float(u.z));
    const double span = length - 2 * skip;
    octomap::point3d hit;
    // An unknown voxel is free space here: only walls and obstacles are in the tree.
    const bool blocked = tree_->castRay(origin, dir, hit, /*ignoreUnknownCells=*/true, span);
    return !blocked || (hit - origin).norm() > span;
}

}  // namespace mrloc::sim
