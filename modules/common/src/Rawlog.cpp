#include <mrloc/common/Error.h>
#include <mrloc/common/Names.h>
#include <mrloc/common/Rawlog.h>
#include <mrloc/common/RawlogProbe.h>
#include <mrpt/maps/registerAllClasses.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/registerAllClasses.h>
#include <mrpt/serialization/CArchive.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>

namespace mrloc::common {

using mrpt::obs::CObservation;

bool storedFlag(const bool& flag) {
    unsigned char byte;
    std::memcpy(&byte, &flag, 1);
    return byte != 0;
}

std::string robotOfLabel(const std::string& label) { return parseSensorLabel(label).robot; }

std::string sensorOfLabel(const std::string& label) { return parseSensorLabel(label).sensor; }

RawlogReader::RawlogReader(const std::string& path) : path_(path) {
    open();
    probeRawlog(path);
}

RawlogReader::RawlogReader(const std::string& path, Unchecked) : path_(path) { open(); }

double RawlogReader::fractionRead() const {
    const double total = double(file_.getTotalBytesCount());
    return total > 0 ? std::min(1.0, double(file_.getPosition()) / total) : 0.0;
}

void RawlogReader::open() {
    // Every observation class, also those mrloc never names (a rawlog may hold any):
    // mrpt-maps holds some (CObservationRotatingScan, CObservationPointCloud).
    static const bool registered = (mrpt::obs::registerAllClasses_mrpt_obs(),
                                    mrpt::maps::registerAllClasses_mrpt_maps(), true);
    (void)registered;
    const std::string& path = path_;
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw Error("rawlog " + pathInWords(path) + ": is a folder; give a rawlog file");
    if (!std::filesystem::exists(path, ec))
        throw Error("rawlog " + pathInWords(path) + ": no such file");
    checkReadableFile(path, "rawlog", SIZE_MAX);  // not a FIFO nor a device
    if (std::filesystem::file_size(path, ec) == 0)
        throw Error("rawlog " + path + ": the file is empty");
    {
        // text (an INI, a TUM file) is not a rawlog: say so in words, not in MRPT's
        std::ifstream head(path, std::ios::binary);
        char bytes[64];
        head.read(bytes, sizeof bytes);
        const auto n = head.gcount();
        bool text = n > 0;
        for (std::streamsize i = 0; i < n && text; ++i) {
            const auto c = static_cast<unsigned char>(bytes[i]);
            text = std::isprint(c) || std::isspace(c);
        }
        if (text)
            throw Error("rawlog " + path +
                        ": a text file, not a rawlog (an INI or a trajectory?); rawlogs are "
                        "MRPT's binary .rawlog files");
    }
    if (!file_.open(path)) throw Error("rawlog " + path + ": cannot open");
}

void RawlogReader::absorbActions(const mrpt::serialization::CSerializable::Ptr& obj) {
    auto acts = std::dynamic_pointer_cast<mrpt::obs::CActionCollection>(obj);
    for (const auto& a : *acts)
        if (a) ++actions_[a->GetRuntimeClass()->className];
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
    releaseHeldAction();  // two actions in a row: the first keeps what it had
    if (odo->timestamp == INVALID_TIMESTAMP) {
        heldAction_ = odo;  // stamped by the sensory frame that follows
        return;
    }
    lastActionTime_ = odo->timestamp;
    pending_.push_back(odo);
}

void RawlogReader::releaseHeldAction() {
    if (!heldAction_) return;
    pending_.push_back(heldAction_);
    heldAction_.reset();
}

void RawlogReader::restampFrame(mrpt::obs::CSensoryFrame& sf) {
    // An observation stamped 0 (MRPT's INVALID_TIMESTAMP: the beacon ranges of MRPT's older
    // rawlogs) was taken with its frame: it gets the time of the frame's other observations,
    // or of the action before the frame.
    std::optional<mrpt::Clock::time_point> frameTime;
    for (const auto& o : sf)
        if (o && o->timestamp != INVALID_TIMESTAMP) {
            frameTime = o->timestamp;
            break;
        }
    if (!frameTime) frameTime = lastActionTime_;
    if (heldAction_ && frameTime) {  // an action stamped 0: the frame it led to
        heldAction_->timestamp = *frameTime;
        ++restamped_[{heldAction_->sensorLabel, heldAction_->GetRuntimeClass()->className}];
    }
    releaseHeldAction();
    for (const auto& o : sf)
        if (o && o->timestamp == INVALID_TIMESTAMP && frameTime) {
            o->timestamp = *frameTime;
            ++restamped_[{o->sensorLabel, o->GetRuntimeClass()->className}];
        }
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
            if (file_.getPosition() == before) {  // clean end between objects
                releaseHeldAction();              // still stamped 0: no sensory frame came after it
                if (pending_.empty()) return false;
                break;
            }
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
            restampFrame(*sf);
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
    try {
        archive << obj;
    } catch (const std::exception& e) {
        // MRPT's own checks throw here too (a landmark twice in one observation): its text
        // says the cause, which need not be the disk
        throw Error("cannot write rawlog " + pending_.finalPath() + ": " + oneLine(e.what()));
    }
}

void RawlogWriter::commit() {
    // gzip's trailer holds the stream's length mod 2^32: a close that failed (a full disk)
    // leaves a file whose trailer does not match what was written
    const uint64_t written = file_.getPosition();
    file_.close();
    std::ifstream in(pending_.tempPath(), std::ios::binary);
    in.seekg(-4, std::ios::end);
    unsigned char isize[4] = {};
    in.read(reinterpret_cast<char*>(isize), 4);
    const uint32_t trailer = uint32_t(isize[0]) | uint32_t(isize[1]) << 8 |
                             uint32_t(isize[2]) << 16 | uint32_t(isize[3]) << 24;
    if (in.gcount() != 4 || trailer != uint32_t(written & 0xffffffffu))
        throw Error("cannot write rawlog " + pending_.finalPath() +
                    ": the file is incomplete (is the disk full?)");
    pending_.commit();
}

}  // namespace mrloc::common
