#pragma once
// Every ultrasonic shot the simulator fired, written beside the rawlog as
// `<stem>.shots.txt` (one line per shot, '#' comments). The rawlog holds what the receivers
// heard; this log holds what happened: it gives the reception rate per beacon and robot
// (seed 001 Tables 3 and 4) and lets tests check the channel timing.
#include <string>
#include <vector>

namespace mrloc::beacons {

struct ShotRecord {
    double start = 0;  ///< s since the start of the run: the burst leaves the transmitter
    double end = 0;    ///< the channel is free again (start + shot_interval)
    std::string robot, section;
    int beacon = 0;
    double pan = 0, tilt = 0;  ///< head joint angles (rad)
    double offAxis = 0;        ///< angle between beam and receiver (rad)
    double distance = 0;       ///< true transmitter-receiver distance (m)
    double marginDb = 0;       ///< level above the decoder threshold, fading included
    bool lineOfSight = true;
    bool detected = false;
    double range = 0;  ///< reported range (m), 0 when not detected
};

using ShotLog = std::vector<ShotRecord>;

/** "x/run.rawlog" -> "x/run.shots.txt". */
std::string shotLogPath(const std::string& rawlogPath);
void saveShotLog(const std::string& path, const ShotLog& log);
/** Throws mrloc::Error naming the file and line on a malformed line. */
ShotLog loadShotLog(const std::string& path);

}  // namespace mrloc::beacons
