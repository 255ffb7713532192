// ROS 1 bags, read with Debian's librosbag-storage (the reading half of librosbag-dev). The
// conversion runs in a child process (Format::isolated): the ROS reader is not hardened against
// hostile files, so a crafted bag that crashes it ends the child, not mrloc, and is reported
// as one line. doc/import.md#rosbag says what maps to what.
#include <mrloc/common/Error.h>
#include <mrloc/common/Names.h>
#include <mrloc/common/Trajectory.h>
#include <mrloc/logimport/Format.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/core/format.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CObservationRange.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/Range.h>
#include <tf2_msgs/TFMessage.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <queue>
#include <set>
#include <tuple>

namespace mrloc::logimport {

namespace {

using mrpt::poses::CPose2D;
using mrpt::poses::CPose3D;

/** The quaternion's heading (ROS: z up), as tf2::getYaw gives it. Not through MRPT's
 *  CQuaternion, which refuses a quaternion that is not of unit norm: bags from robots that
 *  never fill the orientation hold (0, 0, 0, 0), whose heading is read as 0. */
double yawOf(const geometry_msgs::Quaternion& q) {
    return std::atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z));
}

/** A transform as a pose. Its rotation is read as yawOf reads Odometry's: (0, 0, 0, 0), never
 *  filled, is no rotation, and another is normalized (MRPT's CQuaternion refuses one that is
 *  not of unit norm); a rotation or translation that is not a number is refused at `where`. */
CPose3D poseOf(const geometry_msgs::Transform& t, const std::string& where) {
    const auto& r = t.rotation;
    // each checked: std::max of several may drop a NaN, by where it stands
    for (const double v : {r.w, r.x, r.y, r.z, t.translation.x, t.translation.y, t.translation.z})
        if (!std::isfinite(v)) throw Error(where + ": a transform with a value that is not a number");
    const auto q = common::unitQuaternion(r.w, r.x, r.y, r.z, 0);
    if (!q) return CPose3D(t.translation.x, t.translation.y, t.translation.z, 0, 0, 0);
    return CPose3D(*q, t.translation.x, t.translation.y, t.translation.z);
}

/** A message's time: its header's stamp, or the bag's receive time when the stamp is 0. */
double timeOf(const ros::Time& stamp, const rosbag::MessageInstance& m) {
    return stamp.isZero() ? m.getTime().toSec() : stamp.toSec();
}

/** All of a bag's messages in time order (ties in file order), merged through a heap of one
 *  cursor per connection: O(M log C) for M messages on C connections. Built on the ranges
 *  rosbag::View keeps for its subclasses, because View itself is quadratic in connections
 *  twice (librosbag-storage 1.15, 20,000 topics took 10.6 s): its iterator sorts the C
 *  cursors again at every message, and building the ranges searches those made so far for
 *  each connection. That search is kept empty: the query, asked once per connection before
 *  it, parks the ranges made so far, and all are put back once built (each connection is
 *  met once, so the search never had anything to find). */
class TimeOrderedView : public rosbag::View {
 public:
    explicit TimeOrderedView(const rosbag::Bag& bag) {
        try {
            addQuery(bag, [this](const rosbag::ConnectionInfo*) {
                parked_.insert(parked_.end(), ranges_.begin(), ranges_.end());
                ranges_.clear();
                return true;
            });
        } catch (...) {
            unpark();  // ~View deletes them
            throw;
        }
        unpark();
    }

    template <typename Visit>
    void forEach(Visit&& visit) {
        using Cursor = std::pair<std::multiset<rosbag::IndexEntry>::const_iterator,
                                 const rosbag::MessageRange*>;
        const auto later = [](const Cursor& a, const Cursor& b) {
            const rosbag::IndexEntry &x = *a.first, &y = *b.first;
            return std::tie(x.time, x.chunk_pos, x.offset) > std::tie(y.time, y.chunk_pos, y.offset);
        };
        std::priority_queue<Cursor, std::vector<Cursor>, decltype(later)> heads(later);
        for (const rosbag::MessageRange* range : ranges_)
            if (range->begin != range->end) heads.emplace(range->begin, range);
        while (!heads.empty()) {
            auto [entry, range] = heads.top();
            heads.pop();
            const std::unique_ptr<rosbag::MessageInstance> m(
                newMessageInstance(range->connection_info, *entry, *range->bag_query->bag));
            visit(*m);
            if (++entry != range->end) heads.emplace(entry, range);
        }
    }

 private:
    void unpark() {
        ranges_.insert(ranges_.begin(), parked_.begin(), parked_.end());
        parked_.clear();
    }
    std::vector<rosbag::MessageRange*> parked_;
};

/** Labels of the topics: `[topics] /scan = robot.laser` in the option's INI, or by name. */
class TopicLabels {
 public:
    TopicLabels(const std::string& iniPath, const std::string& robot) : robot_(robot) {
        if (iniPath.empty()) return;
        common::checkReadableFile(iniPath, "rosbag topic map", 1 << 20);
        mrpt::config::CConfigFile ini(iniPath);
        std::vector<std::string> keys;
        ini.getAllKeys("topics", keys);
        if (keys.empty()) throw Error(iniPath + ": no [topics] entry (/topic = robot.sensor)");
        for (const auto& topic : keys) {
            const std::string label = ini.read_string("topics", topic, "");
            common::checkSensorLabel(label, iniPath + ": [topics] " + topic);
            if (label.find('.') == std::string::npos)
                throw Error(iniPath + ": [topics] " + topic + ": a label is <robot>.<sensor>");
            map_[topic] = label;
        }
        mapped_ = true;
    }
    /** The label, or nothing when a map is given and leaves the topic out. */
    std::optional<std::string> of(const std::string& topic) const {
        if (mapped_) {
            const auto it = map_.find(topic);
            return it == map_.end() ? std::nullopt : std::optional<std::string>(it->second);
        }
        std::string s;
        for (const char c : topic)
            if (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-')
                s += c;
            else if (c == '/' && !s.empty())
                s += '_';
        if (s.empty()) s = "topic";
        return robot_ + "." + s.substr(0, 200);
    }

 private:
    std::string robot_;
    std::map<std::string, std::string> map_;
    bool mapped_ = false;
};

void convertRosbag(const ImportRequest& req, ImportOutput& out) {
    const auto& o = req.options;
    const std::string robot = o.text("robot");
    common::checkRobotName(robot, "--opt robot");
    const std::string base = o.text("base_frame"), odomFrame = o.text("odom_frame");
    const TopicLabels labels(o.text("topics"), robot);
    out.setReorderWindow(o.number("reorder_window"));

    rosbag::Bag bag;
    bag.open(req.inputs[0], rosbag::bagmode::Read);
    // the sensors' poses on the robot: /tf_static, base_frame -> sensor frame, read first
    std::map<std::string, CPose3D> mounts;
    {
        rosbag::View statics(bag, rosbag::TopicQuery(std::vector<std::string>{"/tf_static"}));
        for (const auto& m : statics)
            if (const auto tf = m.instantiate<tf2_msgs::TFMessage>())
                for (const auto& t : tf->transforms)
                    if (t.header.frame_id == base)
                        mounts[t.child_frame_id] = poseOf(t.transform, req.inputs[0] + ": /tf_static");
    }
    std::map<std::string, size_t> unmounted, dropped;
    const auto mountOf = [&](const std::string& frame) {
        if (frame == base || frame.empty()) return CPose3D();
        const auto it = mounts.find(frame);
        if (it != mounts.end()) return it->second;
        ++unmounted[common::printable(frame.substr(0, 64))];
        return CPose3D();
    };
    const std::string where = req.inputs[0];
    TimeOrderedView(bag).forEach([&](const rosbag::MessageInstance& m) {
        const std::string topic = m.getTopic();
        if (topic == "/tf_static") return;
        const auto label = labels.of(topic);
        if (!label) {
            ++dropped[common::printable(topic.substr(0, 64)) + " (not in the topic map)"];
            return;
        }
        const std::string at = where + ": " + common::printable(topic.substr(0, 64));
        if (const auto odo = m.instantiate<nav_msgs::Odometry>()) {
            auto obs = mrpt::obs::CObservationOdometry::Create();
            obs->sensorLabel = *label;
            obs->timestamp = mrpt::Clock::fromDouble(timeOf(odo->header.stamp, m));
            const auto& p = odo->pose.pose;
            obs->odometry = CPose2D(p.position.x, p.position.y, yawOf(p.orientation));
            obs->hasVelocities = true;  // ROS: the twist is in the child (body) frame
            obs->velocityLocal = mrpt::math::TTwist2D(
                odo->twist.twist.linear.x, odo->twist.twist.linear.y, odo->twist.twist.angular.z);
            out.add(obs, at);
        } else if (const auto scan = m.instantiate<sensor_msgs::LaserScan>()) {
            const size_t n = scan->ranges.size();
            if (n < 2 || n > 100000 || !(std::abs(scan->angle_increment) > 0) ||
                !std::isfinite(scan->angle_min) || !std::isfinite(scan->angle_increment))
                throw Error(at + mrpt::format(": a LaserScan of %zu beams, increment %g rad", n,
                                              double(scan->angle_increment)));
            auto obs = mrpt::obs::CObservation2DRangeScan::Create();
            obs->sensorLabel = *label;
            obs->timestamp = mrpt::Clock::fromDouble(timeOf(scan->header.stamp, m));
            // MRPT's beams span `aperture` centred on the sensor's x axis: the sensor turned
            // to the middle of ROS's [angle_min, angle_max]
            const double span = (n - 1) * double(scan->angle_increment);
            obs->aperture = float(std::abs(span));
            obs->rightToLeft = true;
            obs->maxRange = std::isfinite(scan->range_max) ? scan->range_max : 1e4f;
            obs->sensorPose = mountOf(scan->header.frame_id) +
                              CPose3D(0, 0, 0, double(scan->angle_min) + span / 2, 0, 0);
            obs->resizeScan(n);
            for (size_t i = 0; i < n; ++i) {
                const size_t k = span > 0 ? i : n - 1 - i;  // MRPT's order: right to left
                const float r = scan->ranges[k];
                const bool valid = std::isfinite(r) && r >= scan->range_min && r <= scan->range_max;
                obs->setScanRange(i, valid ? r : 0.0f);
                obs->setScanRangeValidity(i, valid);
            }
            out.add(obs, at);
        } else if (const auto range = m.instantiate<sensor_msgs::Range>()) {
            auto obs = mrpt::obs::CObservationRange::Create();
            obs->sensorLabel = *label;
            obs->timestamp = mrpt::Clock::fromDouble(timeOf(range->header.stamp, m));
            obs->minSensorDistance = range->min_range;
            obs->maxSensorDistance = range->max_range;
            if (!(range->field_of_view > 0 && range->field_of_view < M_PI))
                throw Error(at +
                            mrpt::format(": field of view %g rad", double(range->field_of_view)));
            obs->sensorConeApperture = range->field_of_view;
            mrpt::obs::CObservationRange::TMeasurement s;
            s.sensorPose = mountOf(range->header.frame_id).asTPose();
            const float r = range->range;
            // ROS: -inf too close, +inf nothing in range; MRPT's no echo is 0
            s.sensedDistance =
                std::isfinite(r) && r >= range->min_range && r <= range->max_range ? r : 0.0f;
            obs->sensedData.push_back(s);
            out.add(obs, at);
        } else if (const auto tf = m.instantiate<tf2_msgs::TFMessage>()) {
            for (const auto& t : tf->transforms) {
                if (t.header.frame_id != odomFrame || t.child_frame_id != base) continue;
                auto obs = mrpt::obs::CObservationOdometry::Create();
                obs->sensorLabel = robot + ".tf_odometry";
                obs->timestamp = mrpt::Clock::fromDouble(timeOf(t.header.stamp, m));
                const CPose3D p = poseOf(t.transform, at);
                obs->odometry = CPose2D(p.x(), p.y(), p.yaw());
                out.add(obs, at);
            }
        } else {
            ++dropped[common::printable(topic.substr(0, 64)) + " (" +
                      common::printable(m.getDataType().substr(0, 64)) + ")"];
        }
    });
    for (const auto& [what, n] : dropped)
        out.note(mrpt::format("%zu messages of %s left out", n, what.c_str()));
    for (const auto& [frame, n] : unmounted)
        out.note(
            mrpt::format("%zu messages in frame '%s', which /tf_static does not place on "
                         "%s: taken at the robot's centre",
                         n, frame.c_str(), base.c_str()));
}

}  // namespace

void registerRosbag(FormatRegistry& r) {
    Format f{"rosbag",
             "ROS 1 bags: nav_msgs/Odometry -> CObservationOdometry, sensor_msgs/LaserScan -> "
             "CObservation2DRangeScan, sensor_msgs/Range -> CObservationRange, /tf odom_frame -> "
             "base_frame -> CObservationOdometry (<robot>.tf_odometry); sensors placed by "
             "/tf_static",
             "<file.bag>",
             1,
             1,
             {{"robot", "robot", "the robot's name: labels <robot>.<topic>"},
              {"topics", "", "an INI whose [topics] maps /topic = robot.sensor (only those)"},
              {"base_frame", "base_link", "the robot's frame"},
              {"odom_frame", "odom", "the odometry frame of /tf"},
              {"reorder_window", "1.0", "s: messages may arrive this far out of stamp order"}},
             convertRosbag};
    f.isolated = true;
    r.add(std::move(f));
}

}  // namespace mrloc::logimport
