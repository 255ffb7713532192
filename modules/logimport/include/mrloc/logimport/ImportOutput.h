#pragma once
// What an import writes: the rawlog (observations only, in time order), each robot's ground
// truth as TUM beside it, and any side files (a beacon map INI). Nothing appears under a final
// name until commit(): a failed import leaves what was there before.
#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/ObservationCheck.h>
#include <mrloc/common/Rawlog.h>
#include <mrloc/common/Trajectory.h>
#include <mrloc/logimport/OdometryFit.h>
#include <mrpt/obs/CObservation.h>

#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace mrloc::logimport {

/** Per sensor label and class: how many, first and last time. */
struct StreamCount {
    size_t count = 0;
    double t0 = 0, t1 = 0;
};

/** What an import wrote, for its summary and for tests. */
struct ImportSummary {
    std::string rawlog;
    std::map<std::pair<std::string, std::string>, StreamCount> streams;  ///< label, class
    std::map<std::string, size_t> groundTruth;                           ///< robot -> poses
    std::vector<std::string> files;                                      ///< every file written
    std::vector<std::string> notes;  ///< what was dropped and why, counted
    /** What looks wrong in what was written: the odometry not fitting the truth. */
    std::vector<std::string> warnings;
    double t0 = 0, t1 = 0;
    size_t observations = 0;
};

class ImportOutput {
 public:
    /** `rawlogPath` must end in ".rawlog"; its folder must exist. */
    explicit ImportOutput(const std::string& rawlogPath);

    /** Observations arrive in time order (each format merges its files), or within the
     *  reorder window of it; one earlier than that is refused with `where` (a file and line)
     *  in the error. */
    void add(const mrpt::obs::CObservation::Ptr& obs, const std::string& where);
    /** s an observation may come after a later-stamped one (a bag's messages are in receive
     *  order, their stamps the sensors'); they are held and written in stamp order. */
    void setReorderWindow(double seconds) { window_ = seconds; }
    void addGroundTruth(const std::string& robot, double t, const mrpt::poses::CPose3D& pose,
                        const std::string& where);
    /** A text file beside the rawlog: "<stem><suffix>" (".beacons.ini"). */
    void addSideFile(const std::string& suffix, const std::string& content);
    /** A line for the summary: what was left out and why. */
    void note(const std::string& line) { summary_.notes.push_back(line); }

    /** The options to suggest when a robot's odometry does not fit its truth (OdometryFit.h),
     *  as "--opt key=value ..."; the format's own knowledge of its odometry. */
    void setOdometryAdvice(std::function<std::string(const OdometryFit&)> advice) {
        odometryAdvice_ = std::move(advice);
    }

    /** Writes the truth and the side files, then renames everything to its final name. */
    ImportSummary commit();
    const std::string& stem() const { return stem_; }

 private:
    std::string rawlogPath_, stem_;
    common::RawlogWriter writer_;
    std::map<std::string, common::Trajectory> truth_;
    std::map<std::string, common::Trajectory> odometry_;  ///< per robot, as written
    std::function<std::string(const OdometryFit&)> odometryAdvice_;
    void checkOdometryAgainstTruth();
    std::vector<std::pair<std::string, std::string>> sideFiles_;  ///< path, content
    /** Writes the held observations stamped before `limit`, in stamp order. */
    void writeHeldBefore(double limit);
    double lastTime_ = -INFINITY, window_ = 0, newest_ = -INFINITY;
    /** The reorder window: each observation with where it was read. */
    std::multimap<double, std::pair<mrpt::obs::CObservation::Ptr, std::string>> held_;
    /** What `mrloc localize` checks, checked as written: an import never writes a log
     *  that mrloc refuses (an observation over ObservationBounds, a sensor's two readings at
     *  one instant); the refusal names the input's file and line. */
    common::ObservationCheck check_;
    size_t copies_ = 0;  ///< exact copies of the observation before, left out
    ImportSummary summary_;
};

/** The summary as `mrloc import` prints it: files, time span, counts per label and class. */
std::string summaryText(const ImportSummary& s);

}  // namespace mrloc::logimport
