#include <mrloc/common/Error.h>
#include <mrloc/common/Names.h>
#include <mrloc/common/Trajectory.h>
#include <mrloc/logimport/ImportOutput.h>
#include <mrpt/core/format.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/system/datetime.h>

#include <cmath>
#include <filesystem>

namespace mrloc::logimport {

namespace fs = std::filesystem;

namespace {

/** Odometry readings kept per robot for the check against the truth: its first minute at
 *  up to 1 kHz */
constexpr size_t kOdometryKept = 60000;

std::string checkedRawlogPath(const std::string& path) {
    const fs::path p(path);
    for (const unsigned char c : path)
        if (c < 0x20 || c == 0x7f)
            throw Error("--out " + common::printable(path) +
                        ": a control character (a newline?) in the name");
    if (p.extension() != ".rawlog")
        throw Error("--out " + path + ": the output must be a .rawlog file");
    const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
    if (!fs::is_directory(dir))
        throw Error("--out " + common::pathInWords(path) + ": its folder does not exist");
    if (fs::is_directory(p)) throw Error("--out " + path + ": is a folder");
    return path;
}

}  // namespace

ImportOutput::ImportOutput(const std::string& rawlogPath)
    : rawlogPath_(checkedRawlogPath(rawlogPath)),
      stem_(rawlogPath.substr(0, rawlogPath.size() - std::string(".rawlog").size())),
      writer_(rawlogPath) {
    summary_.rawlog = rawlogPath;
}

void ImportOutput::add(const mrpt::obs::CObservation::Ptr& obs, const std::string& where) {
    if (obs->timestamp == INVALID_TIMESTAMP)
        throw Error(where + ": time 0, which MRPT takes for no time stamp");
    const double t = common::stampSeconds(obs->timestamp);
    if (t < lastTime_)
        throw Error(where + ": time goes back, from " + mrpt::format("%.6f", lastTime_) + " to " +
                    mrpt::format("%.6f", t) + " s" +
                    (window_ > 0 ? mrpt::format(" (beyond the %g s reorder window)", window_)
                                 : std::string()));
    held_.emplace(t, std::make_pair(obs, where));  // equal stamps keep their arrival order
    newest_ = std::max(newest_, t);
    writeHeldBefore(window_ > 0 ? newest_ - window_ : INFINITY);
}

void ImportOutput::writeHeldBefore(double limit) {
    for (; !held_.empty() && held_.begin()->first < limit; held_.erase(held_.begin())) {
        const auto& [t, held] = *held_.begin();
        const auto& [obs, where] = held;
        lastTime_ = t;
        try {
            check_.check(*obs);
            if (check_.isCopyOfTheOneBefore(obs)) {
                ++copies_;
                continue;
            }
        } catch (const Error& e) {
            throw Error(where + ": " + e.what());
        }
        writer_.write(*obs);
        if (const auto* odo = dynamic_cast<const mrpt::obs::CObservationOdometry*>(obs.get());
            odo && odometry_[common::robotOfLabel(odo->sensorLabel)].size() < kOdometryKept)
            odometry_[common::robotOfLabel(odo->sensorLabel)].push_back(
                {t, mrpt::poses::CPose3D(odo->odometry)});
        auto& s = summary_.streams[{obs->sensorLabel, obs->GetRuntimeClass()->className}];
        if (s.count++ == 0) s.t0 = t;
        s.t1 = t;
        if (summary_.observations++ == 0) summary_.t0 = t;
        summary_.t1 = t;
    }
}

void ImportOutput::addGroundTruth(const std::string& robot, double t,
                                  const mrpt::poses::CPose3D& pose, const std::string& where) {
    // the observations' stamps are mrpt::Clock's (100 ns): the truth on the same grid, so
    // that a first reading and the truth's first pose at one time are at one time
    common::checkTrajectoryPose(t, pose.x(), pose.y(), pose.z(), where + ": ground truth");
    t = common::stampSeconds(mrpt::Clock::fromDouble(t));
    auto& traj = truth_[robot];
    if (traj.size() >= common::TrajectoryLimits::kMaxPoses)
        throw Error(where + ": ground truth of more than 2,000,000 poses for robot " + robot);
    if (!traj.empty() && t < traj.back().t)
        throw Error(where + ": ground truth time goes back, from " +
                    mrpt::format("%.6f", traj.back().t) + " to " + mrpt::format("%.6f", t) + " s");
    traj.push_back({t, pose});
}

void ImportOutput::addSideFile(const std::string& suffix, const std::string& content) {
    sideFiles_.emplace_back(stem_ + suffix, content);
}

void ImportOutput::checkOdometryAgainstTruth() {
    for (const auto& [robot, odometry] : odometry_) {
        const auto truth = truth_.find(robot);
        if (truth == truth_.end()) continue;
        const auto fit = fitOdometry(odometry, truth->second);
        if (!fit) continue;
        if (const auto w =
                odometryWarning(robot, *fit, odometryAdvice_ ? odometryAdvice_(*fit) : ""))
            summary_.warnings.push_back(*w);
    }
}

ImportSummary ImportOutput::commit() {
    writeHeldBefore(INFINITY);
    checkOdometryAgainstTruth();
    if (copies_)
        note(mrpt::format("%zu observations left out: exact copies of the one before them", copies_));
    if (summary_.observations == 0)
        throw Error("no observation was converted: nothing to write to " + rawlogPath_);
    if (common::isRelativeTime(summary_.t0))
        note(
            mrpt::format("the log's clock starts at %.3f s: relative time, kept as it is (in "
                         "the rawlog, seconds after 1970-01-01 00:00 UTC; doc/import.md#time)",
                         summary_.t0));
    // every file under its temporary name first; then the renames, which do not fail on a
    // full disk
    std::vector<std::unique_ptr<common::PendingFile>> pending;
    for (const auto& [robot, traj] : truth_) {
        const std::string path = common::groundTruthPath(rawlogPath_, robot);
        pending.push_back(std::make_unique<common::PendingFile>(path, ".import.tmp"));
        common::saveTum(pending.back()->tempPath(), traj);
        summary_.groundTruth[robot] = traj.size();
    }
    for (const auto& [path, content] : sideFiles_) {
        pending.push_back(std::make_unique<common::PendingFile>(path, ".import.tmp"));
        common::writeFileAtomically(pending.back()->tempPath(), content);
    }
    writer_.commit();
    summary_.files.push_back(rawlogPath_);
    for (auto& p : pending) {
        p->commit();
        summary_.files.push_back(p->finalPath());
    }
    return summary_;
}

std::string summaryText(const ImportSummary& s) {
    std::string out;
    for (const auto& f : s.files) out += "wrote " + f + "\n";
    const auto utc = [](double t) { return common::timeInWords(t); };
    out += mrpt::format("%zu observations from %s to %s (%.3f s)\n", s.observations,
                        utc(s.t0).c_str(), utc(s.t1).c_str(), s.t1 - s.t0);
    out +=
        mrpt::format("%-20s %-34s %9s %10s %10s\n", "label", "class", "count", "start_s", "span_s");
    for (const auto& [key, c] : s.streams)
        out += mrpt::format("%-20s %-34s %9zu %10.3f %10.3f\n", key.first.c_str(),
                            key.second.c_str(), c.count, c.t0 - s.t0, c.t1 - c.t0);
    for (const auto& [robot, n] : s.groundTruth)
        out += mrpt::format("ground truth %s: %zu poses\n", robot.c_str(), n);
    for (const auto& n : s.notes) out += "note: " + n + "\n";
    for (const auto& w : s.warnings) out += "warning: " + w + "\n";
    return out;
}

}  // namespace mrloc::logimport
