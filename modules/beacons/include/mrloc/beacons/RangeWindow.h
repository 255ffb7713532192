#pragma once
// Ranges read one at a time. A UWB tag ranges to one anchor per two-way exchange, a camera
// sees a landmark or two: no single observation holds the ranges a fix needs, so the
// tracker's start-up (which starts from fixes) would never start. The window keeps each
// beacon's newest range with the odometry at its time and, once enough beacons are in,
// gives them as one epoch read at the newest time: each range moved by how far the robot's
// odometry says the receiver went meanwhile (doc/beacons.md, "Ranges one at a time").
#include <mrloc/beacons/BeaconMap.h>
#include <mrpt/obs/CObservationBeaconRanges.h>
#include <mrpt/poses/CPose2D.h>

#include <map>
#include <optional>

namespace mrloc::beacons {

class RangeWindow {
 public:
    /** Keeps the observation's ranges (of beacons in the map) read at odometry pose `odo`. */
    void add(double t, const mrpt::obs::CObservationBeaconRanges& obs,
             const mrpt::poses::CPose2D& odo, const BeaconMap& map);

    /** The newest range of each beacon read within `span` s before t, as read at odometry
     *  pose `now`, once at least `needed` beacons are in; nothing otherwise. The receiver's
     *  pose and heading at `now` are solved from the ranges and the odometry between them
     *  (Gauss-Newton on x, y, phi), and each range is corrected by the change in its beacon's
     *  distance from its reading's receiver position to the newest. `receiverZ` is the
     *  receiver's height. */
    std::optional<mrpt::obs::CObservationBeaconRanges> epoch(double t,
                                                             const mrpt::poses::CPose2D& now,
                                                             const BeaconMap& map, size_t needed,
                                                             double span) const;

    /** Distinct ranges added so far (each counts once, however many epochs it joins). */
    size_t added() const { return added_; }

 private:
    struct Reading {
        double t;
        double range;
        mrpt::poses::CPoint3D sensor;  ///< on the robot
        mrpt::poses::CPose2D odo;
    };
    std::map<int32_t, Reading> newest_;  ///< beacon -> its newest range
    size_t added_ = 0;
};

}  // namespace mrloc::beacons
