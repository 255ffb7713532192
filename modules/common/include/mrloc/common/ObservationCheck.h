#pragma once
// What a localizer is given is checked first: a rawlog is a file from a stranger, and a NaN,
// an infinite or impossible value, a missing or backward time stamp or an oversized
// observation would otherwise be taken as data (a NaN in the estimates, an RMSE of 1e38
// reported as a success, minutes of work on one observation).
#include <mrpt/obs/CObservation.h>
#include <mrpt/poses/CPose2D.h>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace mrloc::common {

/** The bounds, one place: doc/errors.md lists them. */
struct ObservationBounds {
    static constexpr size_t kMaxRanges = 1000;       ///< beacon ranges in one observation
    static constexpr size_t kMaxBearings = 1000;     ///< bearings in one observation
    static constexpr size_t kMaxSonars = 256;        ///< range sensors in one observation
    static constexpr size_t kMaxScanRays = 100000;   ///< rays in one 2-D scan
    static constexpr double kMaxRange = 1e4;         ///< m, any range reading
    static constexpr double kMaxCoordinate = 1e6;    ///< m, an odometry or sensor pose
    static constexpr double kMaxOdometryStep = 100;  ///< m between two odometry readings
    static constexpr double kMaxSpeed = 50;          ///< m/s, over a step of more than 1 m
    static constexpr double kMaxTimeJump = 1e6;      ///< s between two observations (11.6 days)
};

/** Checks the observations of one rawlog in file order. */
class ObservationCheck {
 public:
    /** Throws mrloc::Error saying what is wrong (the caller names the entry): a sensor label
     *  mrloc cannot take (Names.h), no time stamp, a stamp before 1970, a stamp earlier than
     *  the one before it of the same label, a jump of over kMaxTimeJump from the observation
     *  before (of any label), a value that is not finite or beyond
     *  ObservationBounds in odometry, beacon ranges, bearings, sonar ranges or 2-D scans. */
    void check(const mrpt::obs::CObservation& obs);
    /** True when `obs` (already check()ed) is an exact copy of the observation before it of
     *  the same label and class, time stamp included: left out and counted by the caller.
     *  Throws mrloc::Error when it has that one's time stamp but other readings (one sensor
     *  cannot read two values at one instant). */
    bool isCopyOfTheOneBefore(const mrpt::obs::CObservation::Ptr& obs);

 private:
    struct Previous {
        mrpt::obs::CObservation::Ptr obs;
        std::vector<uint8_t> bytes;  ///< serialized only when one more has the same stamp
    };
    std::map<std::pair<std::string, std::string>, Previous> previous_;
    /** What a label's latest observation leaves for its next one to be checked against. */
    struct LabelState {
        std::optional<mrpt::Clock::time_point> stamp;  ///< its latest time stamp
        std::optional<mrpt::poses::CPose2D> odometry;  ///< its latest odometry reading
        double odometrySeconds = 0;                    ///< that reading's time stamp
    };
    std::map<std::string, LabelState> labels_;
    std::optional<double> previousSeconds_;  ///< the stamp of the one before, of any label
};

}  // namespace mrloc::common
