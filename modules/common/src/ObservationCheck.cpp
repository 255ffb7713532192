#include <mrloc/common/Trajectory.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/Names.h>
#include <mrloc/common/ObservationCheck.h>
#include <mrpt/core/format.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservationBeaconRanges.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CObservationComment.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CObservationRange.h>
#include <mrpt/serialization/CArchive.h>

#include <cmath>
#include <set>

namespace mrloc::common {

namespace {

using B = ObservationBounds;

void finite(double v, const char* what) {
    if (!std::isfinite(v)) throw Error(mrpt::format("%s is %g, not a finite number", what, v));
}

void range(double v, const char* what) {
    finite(v, what);
    if (v < 0 || v > B::kMaxRange)
        throw Error(mrpt::format("%s of %g m is outside [0, %g] m", what, v, B::kMaxRange));
}

void coordinate(double v, const char* what) {
    finite(v, what);
    if (std::abs(v) > B::kMaxCoordinate)
        throw Error(mrpt::format("%s of %g m is beyond %g m", what, v, B::kMaxCoordinate));
}

void count(size_t n, size_t max, const char* what) {
    if (n > max)
        throw Error(
            mrpt::format("%zu %s in one observation, more than the %zu allowed", n, what, max));
}

void sensorPose(const mrpt::poses::CPose3D& p) {
    coordinate(p.x(), "the sensor pose's x");
    coordinate(p.y(), "the sensor pose's y");
    coordinate(p.z(), "the sensor pose's z");
    finite(p.yaw(), "the sensor pose's yaw");
    finite(p.pitch(), "the sensor pose's pitch");
    finite(p.roll(), "the sensor pose's roll");
}

}  // namespace

void ObservationCheck::check(const mrpt::obs::CObservation& obs) {
    using namespace mrpt::obs;
    checkSensorLabel(obs.sensorLabel, "sensor label");
    const double seconds = stampSeconds(obs.timestamp);
    LabelState& label = labels_[obs.sensorLabel];
    // a comment is an on-board event (its label dropped by MRPT): no stream of its own
    if (!IS_CLASS(obs, CObservationComment)) {
        if (obs.timestamp == INVALID_TIMESTAMP)
            throw Error("no time stamp (0), and no sensory frame time to take");
        // 0 and on: a log whose clock starts at 0 is relative time (common::isRelativeTime)
        if (!std::isfinite(seconds) || seconds < 0)
            throw Error(mrpt::format("time stamp %.6f s is before 1970", seconds));
        if (label.stamp && obs.timestamp < *label.stamp)
            throw Error(mrpt::format("time runs backwards: %.6f s after %.6f s of the same label",
                                     seconds, stampSeconds(*label.stamp)));
        label.stamp = obs.timestamp;
        if (previousSeconds_ && std::abs(seconds - *previousSeconds_) > B::kMaxTimeJump)
            throw Error(
                mrpt::format("time jumps by %.6g s from the observation before (more "
                             "than the %g s allowed)",
                             seconds - *previousSeconds_, B::kMaxTimeJump));
        previousSeconds_ = seconds;
    }
    if (const auto* odo = dynamic_cast<const CObservationOdometry*>(&obs)) {
        coordinate(odo->odometry.x(), "odometry x");
        coordinate(odo->odometry.y(), "odometry y");
        finite(odo->odometry.phi(), "odometry phi");
        if (label.odometry) {
            const double step = (odo->odometry - *label.odometry).norm();
            const double dt = seconds - label.odometrySeconds;
            if (step > B::kMaxOdometryStep)
                throw Error(
                    mrpt::format("odometry moves %g m since its last reading, more "
                                 "than the %g m allowed",
                                 step, B::kMaxOdometryStep));
            // MRPT's older logs stamp a whole run within milliseconds: only a step of over a
            // metre is judged by its speed
            if (step > 1 && step > B::kMaxSpeed * dt)
                throw Error(
                    mrpt::format("odometry moves %g m in %g s since its last reading, "
                                 "faster than %g m/s",
                                 step, dt, B::kMaxSpeed));
        }
        label.odometry = odo->odometry;
        label.odometrySeconds = seconds;
    } else if (const auto* b = dynamic_cast<const CObservationBeaconRanges*>(&obs)) {
        count(b->sensedData.size(), B::kMaxRanges, "beacon ranges");
        for (const auto& m : b->sensedData) {
            range(m.sensedDistance, "a beacon range");
            coordinate(m.sensorLocationOnRobot.x(), "a beacon receiver's x");
            coordinate(m.sensorLocationOnRobot.y(), "a beacon receiver's y");
            coordinate(m.sensorLocationOnRobot.z(), "a beacon receiver's z");
        }
    } else if (const auto* br = dynamic_cast<const CObservationBearingRange*>(&obs)) {
        count(br->sensedData.size(), B::kMaxBearings, "bearings");
        sensorPose(br->sensorLocationOnRobot);
        std::set<int32_t> landmarks;
        for (const auto& m : br->sensedData) {
            finite(m.yaw, "a bearing's yaw");
            finite(m.pitch, "a bearing's pitch");
            range(m.range, "a bearing's range");
            // MRPT's own rule (CObservationBearingRange refuses to be written so): with IDs,
            // each landmark once an observation
            if (m.landmarkID != INVALID_LANDMARK_ID && !landmarks.insert(m.landmarkID).second)
                throw Error(mrpt::format("landmark %d is seen twice in one observation",
                                         int(m.landmarkID)));
        }
    } else if (const auto* r = dynamic_cast<const CObservationRange*>(&obs)) {
        count(r->sensedData.size(), B::kMaxSonars, "range sensors");
        finite(r->sensorConeApperture, "the cone's aperture");
        for (const auto& m : r->sensedData) {
            range(m.sensedDistance, "a sonar range");
            sensorPose(mrpt::poses::CPose3D(m.sensorPose));
        }
    } else if (const auto* scan = dynamic_cast<const CObservation2DRangeScan*>(&obs)) {
        count(scan->getScanSize(), B::kMaxScanRays, "scan rays");
        finite(scan->aperture, "the scan's aperture");
        sensorPose(scan->sensorPose);
        for (size_t i = 0; i < scan->getScanSize(); ++i)
            if (scan->getScanRangeValidity(i)) range(scan->getScanRange(i), "a scan range");
    }
}

bool ObservationCheck::isCopyOfTheOneBefore(const mrpt::obs::CObservation::Ptr& obs) {
    // comments are events (MRPT drops their label): two at one instant are two events
    if (IS_CLASS(*obs, mrpt::obs::CObservationComment)) return false;
    auto& p = previous_[{obs->sensorLabel, obs->GetRuntimeClass()->className}];
    std::vector<uint8_t> bytes;
    bool copy = false;
    if (p.obs && p.obs->timestamp == obs->timestamp) {  // rare: only then are bytes compared
        if (p.bytes.empty()) mrpt::serialization::ObjectToOctetVector(p.obs.get(), p.bytes);
        mrpt::serialization::ObjectToOctetVector(obs.get(), bytes);
        copy = bytes == p.bytes;
        if (!copy)
            throw Error(
                mrpt::format("a second, different reading of this sensor at the same "
                             "time stamp (%.6f s)",
                             stampSeconds(obs->timestamp)));
    }
    if (!copy) p = {obs, std::move(bytes)};
    return copy;
}

}  // namespace mrloc::common
