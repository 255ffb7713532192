#pragma once
// Flat walls from one sonar's readings (seed 004 sec. 4.1). Each reading is paired with the
// newest earlier reading at least a baseline away; the pair gives the wall's normal (eq. (4),
// Erp.h) and its two ERPs. ERPs found one after another whose directions agree form a
// group; a group is fitted with a least-squares line (MRPT's getRegressionLine) and is a
// wall only if every ERP lies near the line and every sonar ray P_i -> R_i meets it at a
// right angle, which a pillar, a person or a corner does not give.
#include <mrloc/framesync/Erp.h>
#include <mrloc/framesync/Wall.h>
#include <mrpt/poses/CPose2D.h>

#include <cmath>
#include <deque>
#include <optional>
#include <vector>

namespace mrloc::framesync {

struct WallDetectorOptions {
    double baseline = 0.4;    ///< m between the two sensor positions of an ERP pair
    double maxPairGap = 1.0;  ///< m: a reading further than this from the next starts over
    double halfAperture = 12.5 * M_PI / 180;  ///< rad: the normal must lie in the cone ...
    double coneMargin = 5 * M_PI / 180;       ///< rad: ... give or take this (noise on it)
    double groupAngle =
        10 * M_PI / 180;        ///< rad: an ERP joins the group if its direction is this near
    double groupGap = 0.3;      ///< m: and it is this near the group's last ERP
    size_t minErps = 16;        ///< ERPs a wall needs (two per pair)
    double minLength = 0.5;     ///< m: the shortest wall reported
    double wallLength = 1.0;    ///< m: a group this long is reported and a new one starts
    double maxResidual = 0.04;  ///< m: every ERP this near the fitted line
    double maxRayAngle = 15 * M_PI / 180;  ///< rad: every ray this near the line's normal
};

/** One sonar reading in the robot's current frame. */
struct SonarReading {
    double t = 0;                 ///< s
    mrpt::poses::CPose2D sensor;  ///< the sensor's pose: position and axis
    double range = 0;             ///< m; meaningless without an echo
    bool echo = false;            ///< false: nothing within the sensor's range
};

/** Why ERPs and groups were turned down, for the report. */
struct WallDetectorCounts {
    size_t readings = 0, erps = 0;
    size_t noWall = 0;     ///< |r2 - r1| > |P1 P2|: no flat wall gives the pair
    size_t outOfCone = 0;  ///< neither root of eq. (4) in the cone
    size_t ambiguous = 0;  ///< both roots in the cone and far apart
    size_t walls = 0, tooShort = 0, offLine = 0, notPerpendicular = 0;
};

class WallDetector {
 public:
    explicit WallDetector(WallDetectorOptions options = {}) : options_(options) {}
    /** Feeds one reading; returns a wall when a group closes and passes the tests. */
    std::optional<Wall> add(const SonarReading& reading);
    /** The frame was redefined: forget every reading and ERP computed in the old frame
     *  (seed 004 sec. 5.1). */
    void drop();
    /** The frame was redefined by `f` (new = f (+) old): carry the readings and ERPs over. */
    void transform(const mrpt::poses::CPose2D& f);
    /** Closes the open group (the log ended). */
    std::optional<Wall> flush() { return close(); }
    const WallDetectorCounts& counts() const { return counts_; }
    /** Readings kept for pairing (at most kMaxHistory): bounded however long the robot
     *  stands or crawls, so that each reading costs the same. */
    size_t historySize() const { return history_.size(); }
    /** 100 s at the default 10 Hz within one baseline (0.4 m) of travel, 4 mm/s; a slower
     *  crawl pairs only its latest 1000 readings. */
    static constexpr size_t kMaxHistory = 1000;
    const WallDetectorOptions& options() const { return options_; }

 private:
    /** The pair's two ERPs (first reading's, this reading's), if the pair gives a wall. */
    std::optional<std::pair<Erp, Erp>> erpsOf(const SonarReading& reading);
    std::optional<Wall> close();
    std::optional<Wall> fit();

    WallDetectorOptions options_;
    std::deque<SonarReading> history_;  ///< echoes since the last gap, oldest first
    std::vector<Erp> group_;
    double sumCos_ = 0, sumSin_ = 0;  ///< the group's directions, for their mean
    WallDetectorCounts counts_;
};

}  // namespace mrloc::framesync
