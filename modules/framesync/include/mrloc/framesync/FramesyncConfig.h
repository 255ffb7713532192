#pragma once
// Section [framesync]: the method's options (keys and defaults in doc/ini.md): the on-board
// system (wall detector, matching, database, priority of reference), the sonars the
// simulator gives every robot, and the experiment (seed 004 sec. 5 over many seeds).
#include <mrloc/common/KeyTable.h>
#include <mrloc/framesync/Sonar.h>
#include <mrloc/framesync/Team.h>
#include <mrpt/config/CLoadableOptions.h>

#include <string>
#include <vector>

namespace mrloc::framesync {

struct FramesyncConfig : public mrpt::config::CLoadableOptions {
    /** Upper bounds (doc/errors.md). */
    static constexpr long kMaxSonars = 64, kMaxSeeds = 10000, kMaxSweep = 20;

    TeamOptions team;
    SonarRigOptions rig;
    // The experiment: seeds of the paper's measure; sweeps of sonar noise (m) and of the
    // odometry drift (factors on every robot's systematic errors). 0 seeds: none.
    size_t experimentSeeds = 50;
    size_t sweepSeeds = 20;
    std::vector<double> sweepNoise{0.0025, 0.005, 0.01, 0.02, 0.04};
    std::vector<double> sweepDrift{0.5, 1, 2, 4};

    /** Every key of [framesync], declared once (loading, effective.ini, doc/ini.md). */
    static const common::KeyTable<FramesyncConfig>& keys();

    void loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                            const std::string& section) override;
    void saveToConfigFile(mrpt::config::CConfigFileBase& target,
                          const std::string& section) const override;
};

}  // namespace mrloc::framesync
