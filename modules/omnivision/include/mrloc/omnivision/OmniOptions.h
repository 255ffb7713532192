#pragma once
// Section [omnivision] (seed 000): the method, the stopped pairs or the measured pair, the
// cameras, the tolerances and, optionally, a generated swarm and an accuracy sweep. The
// app hands the simulator the camera setup it implies (omnivision::OmniSetup); the localizer
// reads the same section. Every key: keys() (doc/ini.md is generated from it).
#include <mrloc/common/KeyTable.h>
#include <mrloc/common/Seeds.h>
#include <mrloc/omnivision/Panorama.h>
#include <mrpt/config/CLoadableOptions.h>

#include <string>
#include <utility>
#include <vector>

namespace mrloc::omnivision {

struct OmniOptions : public mrpt::config::CLoadableOptions {
    std::string method = "proposed";  ///< proposed | conventional
    /** Proposed: the pairs that stop, in order; round r stops pair r during
     *  [t_b + r * round_period, t_e + r * round_period]. The first pair that shares a
     *  moving witness gives L; the others are the paper's restarts. */
    std::vector<std::pair<std::string, std::string>> pairs{{"A", "B"}};
    double tb = 10, te = 12, roundPeriod = 10;  ///< s
    /** Proposed: the search at t_b. full: every image identified, as at t_e (the refinement
     *  then has every robot's odometer). localized: seed 000 eq. (11)-(12), only a
     *  triangle of A, B and one witness of t_e, confirmed without headings, the full search
     *  its fall-back (RestartSearch.h). localized_turn: the same, confirmed by the witness's
     *  odometer turn (beyond the paper). */
    enum class SearchAtTb { Full, Localized, LocalizedTurn };
    SearchAtTb searchAtTb = SearchAtTb::Full;
    bool localizedSearch() const { return searchAtTb != SearchAtTb::Full; }
    /** The INI's word for a search at t_b (`search_at_tb`). */
    static const std::string& wordOf(SearchAtTb search);
    /** Conventional: the pair whose distance a LiDAR measures, at `snapshot`. */
    std::pair<std::string, std::string> measuredPair{"A", "B"};
    double snapshot = 10;      ///< s
    double lidarSigma = 0.01;  ///< m
    // Cameras.
    bool render = true;             ///< camera = render | bearings
    omnivision::Panorama panorama;  ///< views, view_width, view_height
    double bearingSigma = 0.05;     ///< deg (bearings mode)
    double maxRange = 0;            ///< m (0: unlimited)
    double markerRadius = 0.15, markerHeight = 0.2, cameraHeight = 0.5;  ///< m
    // Method.
    double sumTolerance = 0;      ///< deg; 0: 6 x the bearing accuracy
    double bearingTolerance = 0;  ///< deg; 0: 4 x the bearing accuracy
    double odometerSigma = 0.02;  ///< relative (per metre) for the refinement
    bool refine = true;
    // Generated swarm (swarm > 0 replaces [scenario] robots).
    int swarm = 0;
    double swarmArea = 20, swarmSpeed = 0.3, swarmSeparation = 1.0;
    /** swarm_seed: the swarm's layout; drawn from the run's seed unless given
     *  (common/Seeds.h) */
    common::SubSeed swarmSeed;
    // Accuracy sweep in the report (Monte Carlo trials per noise level; 0: none).
    int accuracyTrials = 0;

    /** Every key of the section, declared once (loading, effective.ini, doc/ini.md). */
    static const common::KeyTable<OmniOptions>& keys();

    void loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                            const std::string& section) override;
    void saveToConfigFile(mrpt::config::CConfigFileBase& target,
                          const std::string& section) const override;

    /** The bearing accuracy the tolerances derive from (rad): the noise in bearings mode,
     *  a pixel-derived figure in render mode (see doc/omnivision.md). */
    double bearingAccuracy() const;
    /** The bearings' noise the refinement weighs them by (rad): the noise in bearings mode;
     *  in render mode the detector's, 1/sqrt(24) px (a marker's two edges each fall
     *  anywhere in a column: doc/omnivision.md). */
    double bearingNoise() const;
    double sumToleranceRad() const;
    double bearingToleranceRad() const;
    /** Every instant the cameras fire (s). */
    std::vector<double> snapshotTimes() const;
};

}  // namespace mrloc::omnivision
