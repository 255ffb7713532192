#include <mrloc/common/Error.h>
#include <mrloc/common/Rawlog.h>
#include <mrloc/common/RawlogProbe.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/maps/registerAllClasses.h>
#include <mrpt/obs/registerAllClasses.h>
#include <mrpt/serialization/CArchive.h>

#include <cstring>
#include <filesystem>

namespace mrloc::common {

using mrpt::obs::CObservation;

bool storedFlag(const bool& flag) {
    unsigned char byte;
    std::memcpy(&byte, &flag, 1);
    return byte != 0;
}

std::string robotOfLabel(const std::string& label) {
    const auto dot = label.find('.');
    return dot == std::string::npos ? "robot" : label.substr(0, dot);
}

std::string sensorOfLabel(const std::string& label) {
    const auto dot = label.find('.');
    return dot == std::string::npos ? label : label.substr(dot + 1);
}

RawlogReader::RawlogReader(const std::string& path) : path_(path) {
    open();
    probeRawlog(path);
}

RawlogReader::RawlogReader(const std::string& path, Unchecked) : path_(path) { open(); }

void RawlogReader::open() {
    // Every observation class, also those mrloc never names (a rawlog may hold any):
    // mrpt-maps holds some (CObservationRotatingScan, CObservationPointCloud).
    static const bool registered =
        (mrpt::obs::registerAllClasses_mrpt_obs(), mrpt::maps::registerAllClasses_mrpt_maps(), true);
    (void)registered;
    const std::string& path = path_;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw Error("rawlog " + path + ": no such file");
    if (std::filesystem::file_size(path, ec) == 0)
        throw Error("rawlog " + path + ": the file is empty");
    if (!file_.open(path)) throw Error("rawlog " + path + ": cannot open");
}

void RawlogReader::absorbActions(const mrpt::serialization::CSerializable::Ptr& obj) {
    auto acts = std::dynamic_pointer_cast<mrpt::obs::CActionCollection>(obj);
    auto move = acts->getBestMovementEstimation();
    if (!move) return;  // e.g. only 3-D actions: nothing a 2-D odometry stream can carry
    const bool raw = move->estimationMethod == mrpt::obs::CActionRobotMovement2D::emOdometry;
    const mrpt::poses::CPose2D increment =
        raw ? move->rawOdometryIncrementReading : move->poseChange->getMeanVal();
    actionOdometry_ = actionOdometry_ + increment;

    auto odo = mrpt::obs::CObservationOdometry::Create();
    odo->sensorLabel = kActionOdometryLabel;
    odo->timestamp = move->timestamp;
    odo->odometry = actionOdometry_;
    if (storedFlag(move->hasEncodersInfo)) {
        odo->hasEncodersInfo = true;
        odo->encoderLeftTicks = move->encoderLeftTicks;
        odo->encoderRightTicks = move->encoderRightTicks;
    }
    if (storedFlag(move->hasVelocities)) {
        odo->hasVelocities = true;
        odo->velocityLocal = move->velocityLocal;
    }
    pending_.push_back(odo);
}

bool RawlogReader::next(CObservation::Ptr& obs) {
    auto archive = mrpt::serialization::archiveFrom(file_);
    while (pending_.empty()) {
        mrpt::serialization::CSerializable::Ptr obj;
        const uint64_t before = file_.getPosition();
        try {
            obj = archive.ReadObject();
        } catch (const std::bad_alloc&) {
            throw;  // a corrupt size: the probe names the entry and the memory cap
        } catch (const mrpt::serialization::CExceptionEOF&) {
            if (file_.getPosition() == before) return false;  // clean end between objects
            throw Error("rawlog " + path_ + ": truncated inside entry " +
                        std::to_string(entries_ + 1));
        } catch (const std::exception& e) {
            throw Error("rawlog " + path_ + ": cannot read entry " + std::to_string(entries_ + 1) +
                        " (truncated or not a rawlog): " + oneLine(e.what()));
        }
        ++entries_;
        if (!obj) continue;
        if (auto o = std::dynamic_pointer_cast<CObservation>(obj)) {
            format_ = format_ == RawlogFormat::Unknown ? RawlogFormat::ObservationsOnly : format_;
            pending_.push_back(o);
        } else if (auto sf = std::dynamic_pointer_cast<mrpt::obs::CSensoryFrame>(obj)) {
            format_ = RawlogFormat::ActionsSensoryFrames;
            for (const auto& o : *sf) pending_.push_back(o);
        } else if (std::dynamic_pointer_cast<mrpt::obs::CActionCollection>(obj)) {
            format_ = RawlogFormat::ActionsSensoryFrames;
            absorbActions(obj);
        } else {
            throw Error("rawlog " + path_ + ": entry " + std::to_string(entries_) + " is a " +
                        obj->GetRuntimeClass()->className +
                        ", expected observations, sensory frames or actions");
        }
    }
    obs = pending_.front();
    pending_.pop_front();
    return true;
}

RawlogWriter::RawlogWriter(const std::string& path, int compressionLevel) : pending_(path) {
    if (!file_.open(pending_.tempPath(), compressionLevel))
        throw Error("cannot write rawlog " + pending_.tempPath());
}

void RawlogWriter::write(const mrpt::serialization::CSerializable& obj) {
    auto archive = mrpt::serialization::archiveFrom(file_);
    archive << obj;
}

void RawlogWriter::commit() {
    file_.close();
    pending_.commit();
}

}  // namespace mrloc::common
