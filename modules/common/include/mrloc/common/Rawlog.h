#pragma once
// Streaming rawlog I/O in both of MRPT's formats.
//
// Reading yields observations one at a time without loading the file. The older
// actions + sensory-frames format is flattened: each CSensoryFrame's observations are yielded
// in turn, and each CActionRobotMovement2D becomes a CObservationOdometry carrying the
// odometry pose integrated from the increments, so that consumers see one format only.
// Writing is observations-only, gz-compressed, to a temporary name renamed on commit().
#include <mrloc/common/AtomicFile.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/obs/CObservation.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose2D.h>

#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <string>

namespace mrloc::common {

enum class RawlogFormat { Unknown, ObservationsOnly, ActionsSensoryFrames };

/** Robot a sensor label belongs to: "r1.beacons" -> "r1"; a label with no dot (rawlogs
 *  recorded by other MRPT tools) -> "robot" (common::parseSensorLabel, Names.h). */
std::string robotOfLabel(const std::string& sensorLabel);
/** Sensor part of the label: "r1.beacons" -> "beacons"; no dot -> the whole label. */
std::string sensorOfLabel(const std::string& sensorLabel);

/** A bool member of a deserialized MRPT object, read safely. MRPT's deserializer copies the
 *  file's byte into the bool, and MRPT's own example rawlogs hold 8 or 249 there
 *  (hasEncodersInfo in localization_demo.rawlog and uwb_ro-localization_demo.rawlog).
 *  Loading such a bool is undefined behaviour; its byte is read instead, non-zero meaning
 *  true as the writer meant it. */
bool storedFlag(const bool& flag);

/** Label given to odometry synthesised from CActionRobotMovement2D. */
inline constexpr const char* kActionOdometryLabel = "odometry";

class RawlogReader {
 public:
    /** Opens the file after checking all of it (probeRawlog: gzip stream, every entry
     *  deserialized in an isolated process); throws mrloc::Error if it is missing, corrupt,
     *  truncated or not a rawlog. */
    explicit RawlogReader(const std::string& path);

    /** Opens the file without the check: the probe's own child, which is the isolation. */
    struct Unchecked {};
    static constexpr Unchecked kUnchecked{};
    RawlogReader(const std::string& path, Unchecked);

    /** Next observation in file order; false at the clean end of the file. Throws
     *  mrloc::Error naming the file and entry on a truncated or corrupt file or on an
     *  object that is neither an observation, a sensory frame nor an action collection. */
    bool next(mrpt::obs::CObservation::Ptr& obs);

    RawlogFormat format() const { return format_; }
    /** Observations stamped 0 (invalid) that were given their sensory frame's time (the
     *  frame's other observations', or the action's before it; an action's, the frame's
     *  after it), per label. */
    using LabelClass = std::pair<std::string, std::string>;  ///< sensor label, class name
    const std::map<LabelClass, size_t>& restamped() const { return restamped_; }
    /** Actions read so far, by class (each action of every CActionCollection). */
    const std::map<std::string, size_t>& actions() const { return actions_; }
    /** Serialized objects read so far (MRPT's "rawlog entry" counter). */
    size_t entriesRead() const { return entries_; }
    /** How much of the file has been read, in [0, 1] (of its compressed bytes, as
     *  CFileGZInputStream counts them): the progress of a pass over the log. */
    double fractionRead() const;
    const std::string& path() const { return path_; }

 private:
    void open();
    void absorbActions(const mrpt::serialization::CSerializable::Ptr& obj);
    void restampFrame(mrpt::obs::CSensoryFrame& sf);
    void releaseHeldAction();

    std::string path_;
    mrpt::io::CFileGZInputStream file_;
    std::deque<mrpt::obs::CObservation::Ptr> pending_;
    RawlogFormat format_ = RawlogFormat::Unknown;
    size_t entries_ = 0;
    mrpt::poses::CPose2D actionOdometry_;  // integrated CActionRobotMovement2D increments
    std::optional<mrpt::Clock::time_point> lastActionTime_;
    mrpt::obs::CObservation::Ptr heldAction_;  ///< odometry of an action stamped 0
    std::map<LabelClass, size_t> restamped_;
    std::map<std::string, size_t> actions_;
};

class RawlogWriter {
 public:
    /** Starts writing `path` (as path + ".tmp" until commit()). */
    explicit RawlogWriter(const std::string& path, int compressionLevel = 1);
    void write(const mrpt::serialization::CSerializable& obj);
    /** Closes and renames to the final name. Without it nothing appears under that name. */
    void commit();

 private:
    PendingFile pending_;
    mrpt::io::CFileGZOutputStream file_;
};

}  // namespace mrloc::common
