#include <mrloc/beacons/BeaconStudy.h>
#include <mrloc/common/KeyTable.h>
#include <mrpt/core/format.h>

#include <algorithm>
#include <cmath>

namespace mrloc::beacons {

const common::KeyTable<StudyOptions>& StudyOptions::keys() {
    using O = StudyOptions;
    const common::KeyList sides{1, kMaxSide, size_t(kMaxValues)};
    const common::KeyList beacons{3, kMaxBeacons, size_t(kMaxValues), 0, true};
    static const auto table =
        common::KeyTable<O>("beacons_study")
            .integer("choice_trials", MRLOC_KEY_FIELD(choiceTrials), 0, kMaxTrials, "",
                     "trials per test point (the run's robots' starts) for the method-choice "
                     "table (0: no table)")
            .real("grid", MRLOC_KEY_FIELD(grid), {0.1, kMaxSide}, "m", "between test points")
            .real("wall_margin", MRLOC_KEY_FIELD(wallMargin), {0, kMaxSide}, "m",
                  "from the walls to the first test points")
            .integer("trials", MRLOC_KEY_FIELD(trials), 1, kMaxTrials, "",
                     "trials per test point elsewhere (paper 001: 10)")
            .custom(
                "reception_min", "%", "0 .. 100",
                "a point is covered when at least this share of its trials gives a fix ...",
                [](common::IniSection& s, O& o) {
                    o.criteria.reception =
                        s.real("reception_min", 100 * o.criteria.reception, 0, 100) / 100;
                },
                [](const O& o) {
                    return common::keyValueText(
                        o.criteria.reception, [](double x) { return x / 100; },
                        [](double x) { return 100 * x; });
                })
            .real("error_bound", MRLOC_KEY_FIELD(criteria.errorBound), {1e-4, 10}, "m",
                  "... and no error exceeds this")
            .real("ceiling", MRLOC_KEY_FIELD(ceiling), {0.5, 100}, "m",
                  "the height of the study's beacons (spread layouts)")
            .real("receiver_height", MRLOC_KEY_FIELD(receiverHeight), {0, 100}, "m",
                  "at least 0.1 m below `ceiling`; the 2-D fix knows it")
            .integer("beacons_per_fix", MRLOC_KEY_FIELD(beaconsPerFix), 3, kMaxBeacons, "",
                     "beacons fired per trial: those the link predicts loudest at the receiver")
            .numbers("coverage_sizes", MRLOC_KEY_FIELD(coverageSizes), sides, "m",
                     "square rooms covered by one set of `coverage_beacons`")
            .integer("coverage_beacons", MRLOC_KEY_FIELD(coverageBeacons), 3, kMaxBeacons, "",
                     "beacons of that one set (paper 001: a section's)")
            .numbers("count_sizes", MRLOC_KEY_FIELD(countSizes), sides, "m",
                     "square rooms whose fewest covering beacons are searched, from 3 to "
                     "`count_max`")
            .integer("count_max", MRLOC_KEY_FIELD(countMax), 3, kMaxBeacons, "",
                     "the most beacons that search tries")
            .numbers("beam_angles", MRLOC_KEY_FIELD(beamAngles), {1, 180, size_t(kMaxValues)},
                     "deg", "the transducer's beam swept in the run's room with its beacons")
            .numbers("beacon_counts", MRLOC_KEY_FIELD(beaconCounts), beacons, "",
                     "spread beacons in the run's room")
            .numbers("speeds", MRLOC_KEY_FIELD(speeds), {0, 10, size_t(kMaxValues)}, "m/s",
                     "the receiver moving during its trial's shots")
            .numbers("agents", MRLOC_KEY_FIELD(agents),
                     {1, kMaxAgents, size_t(kMaxValues), 0, true}, "",
                     "agents served at once (at most 0.4 (agents_size - 1)^2: they stand 1 m "
                     "apart)")
            .real("agents_size", MRLOC_KEY_FIELD(agentsSize), {2, kMaxSide}, "m",
                  "the agents study's square room")
            .integer("agents_beacons", MRLOC_KEY_FIELD(agentsBeacons), 3, kMaxBeacons, "",
                     "spread beacons in that room")
            .real("agents_time", MRLOC_KEY_FIELD(agentsTime), {0.1, 3600}, "s",
                  "channel time per layout")
            .integer("agents_layouts", MRLOC_KEY_FIELD(agentsLayouts), 1, 1000, "",
                     "random layouts of the agents");
    return table;
}

void StudyOptions::load(const mrpt::config::CConfigFileBase& ini, const std::string& section) {
    *this = StudyOptions{};
    enabled = ini.sectionExists(section);
    if (!enabled) return;
    common::IniSection s(ini, section);
    keys().load(s, *this);
    if (receiverHeight > ceiling - 0.1)
        s.fail("receiver_height",
               mrpt::format("must be at least 0.1 m below ceiling = %g m", ceiling));
    // agents are placed at random 1 m apart: random placement jams near 0.4 of the densest
    // packing, so ask for no more than that
    const double fit = std::max(1.0, std::floor(0.4 * (agentsSize - 1) * (agentsSize - 1)));
    for (const double a : agents)
        if (a > fit)
            s.fail("agents", mrpt::format("%g agents do not fit 1 m apart in agents_size = %g m "
                                          "(at most %g)",
                                          a, agentsSize, fit));
    s.finish();
}

void StudyOptions::save(mrpt::config::CConfigFileBase& t, const std::string& section) const {
    if (enabled) keys().save(*this, t, section);
}

double StudyOptions::trialsAtMost(size_t runPoints, double roomX, double roomY) const {
    if (!enabled) return 0;
    const auto points = [&](double x, double y) {
        return double(testGrid(x, y, grid, wallMargin).size());
    };
    double n = double(choiceTrials) * double(runPoints) * 14;  // variants x aimings, at most
    for (const double size : coverageSizes) n += 2 * points(size, size) * trials;
    for (const double size : countSizes) n += 2 * points(size, size) * trials * (countMax - 2);
    const double sweepPoints = points(roomX, roomY);  // the sweeps run in the run's room
    n += 2 * sweepPoints * trials * double(beamAngles.size() + beaconCounts.size() + speeds.size());
    // agents: an epoch is at least 3 shots, each with every simultaneous burst
    for (const double a : agents) n += 2 * 2 * agentsLayouts * agentsTime / (3 * 0.03) * a;
    return n;
}

}  // namespace mrloc::beacons
