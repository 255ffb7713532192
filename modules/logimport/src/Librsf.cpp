// libRSF's text datasets (TU Chemnitz; "Labyrinth", Indoor_UWB): one measurement per line, led
// by its type. doc/import.md#librsf says what maps to what.
#include <mrloc/common/Error.h>
#include <mrloc/common/Names.h>
#include <mrloc/common/ShellWord.h>
#include <mrloc/logimport/Format.h>
#include <mrloc/logimport/TextLog.h>
#include <mrloc/logimport/Unicycle.h>
#include <mrpt/core/format.h>
#include <mrpt/obs/CObservationBeaconRanges.h>
#include <mrpt/obs/CObservationOdometry.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>

namespace mrloc::logimport {

namespace {

using mrpt::obs::CObservationBeaconRanges;
using mrpt::obs::CObservationOdometry;

constexpr size_t kMaxRecords = 50'000'000;  ///< a dataset's lines, held in memory to merge

struct Anchor {
    double x, y;
    std::string where;  ///< the line that first placed it
};

/** Anchors an import takes: the beacon map INI it writes must be one localize reads. */
constexpr size_t kMaxAnchors = 100000;

/** The beacons method's INI for the anchors the log names: ready to run on the rawlog. */
std::string beaconIni(const std::string& source, const std::string& stem,
                      const std::map<long, Anchor>& anchors, double anchorZ, double rangeSigma) {
    std::string s = "# Beacon map of " + common::printable(source) +
                    " (libRSF range2 anchors), written by mrloc import librsf.\n"
                    "# mrloc localize " +
                    common::shellWord(std::filesystem::path(stem).filename().string() +
                                      ".beacons.ini") +
                    " " +
                    common::shellWord(std::filesystem::path(stem).filename().string() +
                                      ".rawlog") +
                    "\n[scenario]\nmethod = beacons\n\n[beacons]\n";
    for (const auto& [id, a] : anchors)
        s += mrpt::format("beacon_%ld = %.6f %.6f %.6f\n", id, a.x, a.y, anchorZ);
    s += "# the median of the log's own range variances, as a standard deviation\n";
    s += mrpt::format("range_sigma = %.6f\n", rangeSigma);
    return s + realLogBeaconKeys();
}

void convertLibrsf(const ImportRequest& req, ImportOutput& out) {
    const std::string robot = req.options.text("robot");
    common::checkRobotName(robot, "--opt robot");
    const bool withOdometry = req.options.flag("odometry");
    const double anchorZ = req.options.number("anchor_z");
    const double tagZ = req.options.number("tag_z");
    const double baseScale = req.options.number("wheel_base_scale");
    if (!(baseScale > 0 && baseScale <= 100)) throw Error("--opt wheel_base_scale: 0 to 100");
    const bool swapWheels = req.options.flag("swap_wheels");
    // the odometry turns at (v_r - v_l) / wheel base: the wheels' columns the other way round
    // turn it the other way, a wheel base off by k turns it 1/k times as fast
    out.setOdometryAdvice([=](const OdometryFit& fit) {
        std::string advice;
        if (fit.mirrored())
            advice += std::string("--opt swap_wheels=") + (swapWheels ? "no" : "yes");
        if (fit.turnRateOff())
            advice +=
                (advice.empty() ? "" : " ") +
                mrpt::format("--opt wheel_base_scale=%.3g", baseScale * std::abs(fit.turnGain));
        return advice;
    });

    std::map<long, Anchor> anchors;
    std::vector<double> variances;
    std::map<std::string, size_t> dropped;
    // libRSF writes its file type by type (every range2, then every odom2diff): the records
    // are read whole, then merged by time (a stable sort keeps a type's order at equal times)
    struct Record {
        double t;
        size_t line;
        bool isRange;
        double range = 0, variance = 0;  ///< range2
        long anchor = 0;
        mrpt::math::TTwist2D twist;  ///< odom2diff: forward, lateral, turn
    };
    std::vector<Record> records;
    TextLog log(req.inputs[0], "librsf input");
    TimeOrder order;
    while (log.next()) {
        if (records.size() >= kMaxRecords)
            log.fail(mrpt::format("more than %zu records", kMaxRecords));
        const std::string_view type = log.field(0);
        if (type == "range2") {
            log.expectAtLeast(7, "range2 time range variance anchor_x anchor_y anchor_id [snr]");
            const double t = log.number(1, "time");
            order.check(log, "range2", t);
            const double r = log.number(2, "range");
            const double var = log.number(3, "range variance");
            if (r < 0 || r > 1e4) log.fail(mrpt::format("range %g m is outside [0, 10000]", r));
            if (var <= 0 || var > 1e4)
                log.fail(mrpt::format("range variance %g m^2 cannot be", var));
            const double ax = log.number(4, "anchor x"), ay = log.number(5, "anchor y");
            if (std::abs(ax) > 1e6 || std::abs(ay) > 1e6) log.fail("anchor beyond 1000 km");
            const long id = log.integer(6, "anchor id", 0, 2147483647);
            auto [it, added] = anchors.try_emplace(id, Anchor{ax, ay, log.where()});
            // the beacon map INI lists every anchor: 100,000 lines stay far inside the 16 MiB
            // an INI may hold (a 43 MB map was written once, and localize refused it)
            if (added && anchors.size() > kMaxAnchors)
                log.fail(mrpt::format("more than %zu anchors: not a map the beacons method "
                                      "can be given",
                                      kMaxAnchors));
            if (!added && std::hypot(it->second.x - ax, it->second.y - ay) > 1e-3)
                log.fail(mrpt::format("anchor %ld moved by %.3f m since ", id,
                                      std::hypot(it->second.x - ax, it->second.y - ay)) +
                         it->second.where + " (a map must hold still)");
            variances.push_back(var);
            records.push_back({t, log.lineNumber(), true, r, var, id, {}});
        } else if (type == "odom2diff") {
            log.expectAtLeast(6, "odom2diff time v_right v_left v_lateral wheel_base [variances]");
            const double t = log.number(1, "time");
            order.check(log, "odom2diff", t);
            double vr = log.number(2, "right wheel speed"), vl = log.number(3, "left wheel speed");
            if (swapWheels) std::swap(vr, vl);
            const double vy = log.number(4, "lateral speed");
            const double base = log.number(5, "wheel base") * baseScale;
            if (base <= 0 || base > 100) log.fail(mrpt::format("wheel base %g m cannot be", base));
            for (const double v : {vr, vl, vy})
                if (std::abs(v) > 100) log.fail(mrpt::format("a speed of %g m/s cannot be", v));
            // differential drive: v = (vr + vl) / 2, w = (vr - vl) / base
            records.push_back({t, log.lineNumber(), false, 0, 0, 0,
                               mrpt::math::TTwist2D((vr + vl) / 2, vy, (vr - vl) / base)});
        } else {
            ++dropped[common::printable(std::string(type.substr(0, 32)))];
        }
    }
    std::stable_sort(records.begin(), records.end(),
                     [](const Record& a, const Record& b) { return a.t < b.t; });

    mrpt::poses::CPose2D odo;
    std::optional<double> lastOdoTime;
    CObservationBeaconRanges::Ptr epoch;  // ranges of one time stamp, one observation
    double epochTime = 0;
    std::string epochWhere;
    const auto flush = [&] {
        if (epoch) out.add(epoch, epochWhere);
        epoch.reset();
    };
    const auto where = [&](const Record& r) {
        return req.inputs[0] + ":" + std::to_string(r.line);
    };
    for (const Record& rec : records) {
        if (rec.isRange) {
            if (epoch && epochTime != rec.t) flush();
            if (!epoch) {
                epoch = CObservationBeaconRanges::Create();
                epoch->sensorLabel = robot + ".uwb";
                epoch->timestamp = mrpt::Clock::fromDouble(rec.t);
                epoch->maxSensorDistance = 1e4f;
                epoch->stdError = float(std::sqrt(rec.variance));
                epochTime = rec.t;
                epochWhere = where(rec);
            }
            CObservationBeaconRanges::TMeasurement m;
            m.sensorLocationOnRobot = mrpt::poses::CPoint3D(0, 0, tagZ);
            m.sensedDistance = float(rec.range);
            m.beaconID = int32_t(rec.anchor);
            epoch->sensedData.push_back(m);
            continue;
        }
        // the speeds are what the wheels turned at over the interval this reading closes
        const auto& w = rec.twist;
        if (lastOdoTime) odo = moveArc(odo, w.vx, w.vy, w.omega, rec.t - *lastOdoTime);
        lastOdoTime = rec.t;
        if (!withOdometry) continue;
        flush();
        auto obs = CObservationOdometry::Create();
        obs->sensorLabel = robot + ".odometry";
        obs->timestamp = mrpt::Clock::fromDouble(rec.t);
        obs->odometry = odo;
        obs->hasVelocities = true;
        obs->velocityLocal = w;
        out.add(obs, where(rec));
    }
    flush();
    if (anchors.empty()) throw Error(req.inputs[0] + ": no range2 line: not a libRSF UWB log?");
    for (const auto& [type, n] : dropped)
        out.note(mrpt::format("%zu lines of type '%s' left out (not a range2 or odom2diff)", n,
                              type.c_str()));
    if (!withOdometry) out.note("odometry left out (--opt odometry=no)");

    if (req.inputs.size() > 1) {
        TextLog gt(req.inputs[1], "librsf ground truth");
        size_t other = 0;
        while (gt.next()) {
            if (gt.field(0) != "point2") {
                ++other;
                continue;
            }
            gt.expectAtLeast(4, "point2 time x y [covariance]");
            const double t = gt.number(1, "time");
            out.addGroundTruth(
                robot, t, mrpt::poses::CPose3D(gt.number(2, "x"), gt.number(3, "y"), 0, 0, 0, 0),
                gt.where());
        }
        if (other) out.note(mrpt::format("%zu ground-truth lines not point2 left out", other));
        out.note("ground truth has positions only (point2): its headings are written as 0");
    }
    std::nth_element(variances.begin(), variances.begin() + variances.size() / 2, variances.end());
    out.addSideFile(".beacons.ini", beaconIni(req.inputs[0], out.stem(), anchors, anchorZ,
                                              std::sqrt(variances[variances.size() / 2])));
}

}  // namespace

void registerLibrsf(FormatRegistry& r) {
    r.add({"librsf",
           "libRSF's text datasets: range2 -> CObservationBeaconRanges (<robot>.uwb), odom2diff "
           "-> CObservationOdometry (<robot>.odometry, integrated from the wheel speeds), point2 "
           "(the GT file) -> ground truth; the anchors -> <out>.beacons.ini",
           "<input.txt> [<ground-truth.txt>]",
           1,
           2,
           {{"robot", "robot", "the robot's name, the labels' first part"},
            {"odometry", "yes", "no: leave the odometry out (ranges alone, as a tag carries)"},
            {"anchor_z", "0", "the anchors' height, m (range2 is planar)"},
            {"tag_z", "0", "the robot's tag height, m"},
            {"wheel_base_scale", "1", "the wheel base is this times the file's (Labyrinth: 2)"},
            {"swap_wheels", "no",
             "yes: the right-wheel column is the left wheel's (Labyrinth: yes)"}},
           convertLibrsf});
}

}  // namespace mrloc::logimport
