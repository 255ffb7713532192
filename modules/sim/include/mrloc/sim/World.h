#pragma once
// The simulated world: a rectangular room [0, size_x] x [0, size_y] x [0, height] whose
// side walls, box obstacles and pillars (vertical cylinders) are occupied voxels of an
// octomap::OcTree. Line of sight
// between a beacon and a receiver is a ray cast in that tree.
#include <mrloc/common/KeyTable.h>
#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/math/TPoint3D.h>
#include <octomap/OcTree.h>

#include <memory>
#include <string>
#include <vector>

namespace mrloc::sim {

struct Box {
    std::string name;
    mrpt::math::TPoint3D min, max;
};

/** A vertical cylinder standing on the floor: a pillar, a person, a bin. */
struct Pillar {
    std::string name;
    double x = 0, y = 0, radius = 0, height = 0;
};

/** Section [world]. */
struct WorldOptions : public mrpt::config::CLoadableOptions {
    /** Upper bounds that keep building the world finite and quick (doc/errors.md): a room
     *  of at most 1 km x 1 km x 100 m, at most kMaxVoxels voxels filled (walls + obstacles,
     *  a few seconds), and every point inside OctoMap's 16-bit key range. */
    static constexpr double kMaxSide = 1000, kMaxHeight = 100;
    static constexpr double kMaxVoxels = 1e7;
    /** Voxels the walls and obstacles fill. */
    double filledVoxels() const;

    double sizeX = 5, sizeY = 5, height = 2.5;  ///< room extent (m)
    double resolution = 0.05;                   ///< OcTree voxel size (m)
    std::vector<Box> obstacles;                 ///< obstacle_<name> = xmin ymin zmin xmax ymax zmax
    std::vector<Pillar> pillars;                ///< pillar_<name> = x y radius height

    /** Every key of [world], declared once (loading, effective.ini, doc/ini.md). */
    static const common::KeyTable<WorldOptions>& keys();

    void loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                            const std::string& section) override;
    void saveToConfigFile(mrpt::config::CConfigFileBase& target,
                          const std::string& section) const override;
    bool contains(const mrpt::math::TPoint3D& p, double margin = 0) const;
};

class World {
 public:
    explicit World(WorldOptions options);
    const WorldOptions& options() const { return options_; }
    /** True if the segment a-b crosses no occupied voxel. */
    bool lineOfSight(const mrpt::math::TPoint3D& a, const mrpt::math::TPoint3D& b) const;
    const octomap::OcTree& octree() const { return *tree_; }

 private:
    void fillBox(const mrpt::math::TPoint3D& min, const mrpt::math::TPoint3D& max);
    void fillPillar(const Pillar& p);
    WorldOptions options_;
    std::unique_ptr<octomap::OcTree> tree_;
};

/** The world of `options`, built once while a process asks for the same options: a batch
 *  job's trials share it as the in-process experiment does. A world depends on the [world]
 *  keys alone, never on the seed. The last world asked for is kept; thread-safe. */
std::shared_ptr<const World> sharedWorld(const WorldOptions& options);

}  // namespace mrloc::sim
