// The UTIAS Multi-Robot Cooperative Localization and Mapping datasets (Leung, Halpern, Barfoot,
// Liu, IJRR 2011): a folder of per-robot text files. doc/import.md#mrclam says what maps to what.
#include <mrloc/common/Error.h>
#include <mrloc/common/Names.h>
#include <mrloc/logimport/Format.h>
#include <mrloc/logimport/TextLog.h>
#include <mrloc/logimport/Unicycle.h>
#include <mrpt/core/format.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CObservationOdometry.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <set>

namespace mrloc::logimport {

namespace {

namespace fs = std::filesystem;

constexpr int kRobots = 5;  ///< subjects 1-5 are the robots (Barcodes.dat)

/** Subject -> barcode, and the surveyed landmarks. */
struct Landmark {
    double x, y;
};

std::map<long, long> readBarcodes(const std::string& path) {
    std::map<long, long> subjectOf;  // barcode -> subject
    TextLog log(path, "MRCLAM Barcodes.dat");
    while (log.next()) {
        log.expectExactly(2, "subject barcode");
        const long subject = log.integer(0, "subject", 1, 1000);
        const long barcode = log.integer(1, "barcode", 0, 1000000);
        if (!subjectOf.emplace(barcode, subject).second)
            log.fail(mrpt::format("barcode %ld is given twice", barcode));
    }
    if (subjectOf.empty()) throw Error(path + ": no barcode");
    return subjectOf;
}

std::map<long, Landmark> readLandmarks(const std::string& path) {
    std::map<long, Landmark> out;
    TextLog log(path, "MRCLAM Landmark_Groundtruth.dat");
    while (log.next()) {
        log.expectAtLeast(3, "subject x y [x_sd y_sd]");
        const long subject = log.integer(0, "subject", kRobots + 1, 1000);
        const Landmark l{log.number(1, "x"), log.number(2, "y")};
        if (std::abs(l.x) > 1e6 || std::abs(l.y) > 1e6) log.fail("a landmark beyond 1000 km");
        if (!out.emplace(subject, l).second) log.fail(mrpt::format("landmark %ld twice", subject));
    }
    return out;
}

/** One of a robot's three files, read a record ahead so that the files merge by time. */
struct Stream {
    enum Kind { Odometry, Measurement, Truth } kind = Odometry;
    int robot = 0;
    std::unique_ptr<TextLog> log;
    TimeOrder order;
    bool done = false;
    double t = 0;
    std::vector<std::array<double, 3>> rows;  ///< the record's rows (a measurement's: several)
    std::string where;
    // read-ahead of a measurement: its first line of the next time stamp
    bool held = false;
    double heldT = 0;
    std::array<double, 3> heldRow{};
    std::string heldWhere;

    void advance() {
        rows.clear();
        if (kind != Measurement) {
            if (!log->next()) return void(done = true);
            log->expectAtLeast(kind == Odometry ? 3 : 4,
                               kind == Odometry ? "time v w" : "time x y heading");
            t = log->number(0, "time");
            order.check(*log, "records", t);
            rows.push_back({log->number(1, kind == Odometry ? "forward velocity" : "x"),
                            log->number(2, kind == Odometry ? "angular velocity" : "y"),
                            kind == Odometry ? 0.0 : log->number(3, "heading")});
            where = log->where();
            return;
        }
        if (!held && !readMeasurement()) return void(done = true);
        t = heldT, where = heldWhere;
        rows.push_back(heldRow);
        held = false;
        while (readMeasurement()) {
            if (heldT != t) return;
            rows.push_back(heldRow);
            held = false;
        }
    }
    bool readMeasurement() {
        if (!log->next()) return false;
        log->expectAtLeast(4, "time subject range bearing");
        heldT = log->number(0, "time");
        order.check(*log, "measurements", heldT);
        heldRow = {double(log->integer(1, "barcode", 0, 1000000)), log->number(2, "range"),
                   log->number(3, "bearing")};
        if (heldRow[1] <= 0 || heldRow[1] > 1e4)
            log->fail(mrpt::format("range %g m cannot be", heldRow[1]));
        if (std::abs(heldRow[2]) > 2 * M_PI)
            log->fail(mrpt::format("bearing %g rad beyond a turn", heldRow[2]));
        heldWhere = log->where();
        return held = true;
    }
};

std::string beaconIni(const std::map<long, Landmark>& landmarks) {
    std::string s =
        "# MRCLAM's surveyed landmarks (Landmark_Groundtruth.dat) as the beacons method's map,\n"
        "# written by mrloc import mrclam; the camera's sightings (range and bearing) are\n"
        "# <robot>.camera, other robots' ids (1-5) are not landmarks.\n"
        "[scenario]\nmethod = beacons\n\n[beacons]\n";
    for (const auto& [id, l] : landmarks)
        s += mrpt::format("beacon_%ld = %.6f %.6f 0\n", id, l.x, l.y);
    s += "# MRCLAM's camera against Vicon (dataset 6, all robots; doc/beacons.md): ranges robust\n"
         "# sd 0.131 m (0.06 m under 2 m, 0.19 m beyond 4 m); bearings robust sd 0.34-0.66 deg\n"
         "# per robot with tails to 3 deg, which 0.02 rad (1.15 deg) keeps in the gate.\n"
         "range_sigma = 0.13\nbearing_sigma = 0.02\n"
         "# what the tracker takes of a sighting: range_bearing, range or bearing\n"
         "sightings = range_bearing\n";
    return s + realLogBeaconKeys();
}

void convertMrclam(const ImportRequest& req, ImportOutput& out) {
    const fs::path dir = req.inputs[0];
    if (!fs::is_directory(dir))
        throw Error(common::pathInWords(dir.string()) +
                    ": not a folder (format 'mrclam' reads a dataset's folder)");
    const auto subjectOf = readBarcodes((dir / "Barcodes.dat").string());
    const auto landmarks = readLandmarks((dir / "Landmark_Groundtruth.dat").string());
    const double duration = req.options.number("duration");
    if (duration < 0) throw Error("--opt duration: must be >= 0 (0: the whole log)");
    const bool withOdometry = req.options.flag("odometry");
    std::set<int> robots;
    for (const double r : req.options.numbers("robots")) {
        if (r != std::floor(r) || r < 1 || r > kRobots)
            throw Error(mrpt::format("--opt robots: %g is not a robot (1 to %d)", r, kRobots));
        robots.insert(int(r));
    }
    if (robots.empty()) throw Error("--opt robots: none given");

    std::vector<Stream> streams;
    for (const int r : robots)
        for (const auto& [kind, file] : {std::pair{Stream::Odometry, "Odometry"},
                                         {Stream::Measurement, "Measurement"},
                                         {Stream::Truth, "Groundtruth"}}) {
            const std::string path = (dir / mrpt::format("Robot%d_%s.dat", r, file)).string();
            Stream s;
            s.kind = kind;
            s.robot = r;
            s.log = std::make_unique<TextLog>(path, std::string("MRCLAM ") + file + " file");
            s.advance();
            streams.push_back(std::move(s));
        }
    double start = INFINITY;
    for (const auto& s : streams)
        if (!s.done) start = std::min(start, s.t);
    const double end = duration > 0 ? start + duration : INFINITY;

    std::map<int, mrpt::poses::CPose2D> odo;
    std::map<int, std::pair<double, std::array<double, 3>>> lastCommand;  // time, (v, w)
    std::map<long, size_t> unknownBarcodes;
    size_t sameTimeCommands = 0, repeatedSightings = 0;
    for (;;) {
        Stream* next = nullptr;
        for (auto& s : streams)
            if (!s.done && s.t < end && (!next || s.t < next->t)) next = &s;
        if (!next) break;
        const std::string name = mrpt::format("r%d", next->robot);
        const auto stamp = mrpt::Clock::fromDouble(next->t);
        if (next->kind == Stream::Truth) {
            const auto& row = next->rows[0];
            out.addGroundTruth(name, next->t, mrpt::poses::CPose3D(row[0], row[1], 0, row[2], 0, 0),
                               next->where);
        } else if (next->kind == Stream::Odometry) {
            // a command holds from its time to the next one's (zero-order hold)
            auto& pose = odo[next->robot];
            const auto it = lastCommand.find(next->robot);
            const bool sameTime = it != lastCommand.end() && it->second.first == next->t;
            if (it != lastCommand.end())
                pose = moveArc(pose, it->second.second[0], 0, it->second.second[1],
                               next->t - it->second.first);
            lastCommand[next->robot] = {next->t, next->rows[0]};
            if (sameTime || !withOdometry) {
                // two commands at one time stamp: the later holds from it; one reading there
                sameTimeCommands += sameTime;
                next->advance();
                continue;
            }
            auto obs = mrpt::obs::CObservationOdometry::Create();
            obs->sensorLabel = name + ".odometry";
            obs->timestamp = stamp;
            obs->odometry = pose;
            obs->hasVelocities = true;
            obs->velocityLocal = mrpt::math::TTwist2D(next->rows[0][0], 0, next->rows[0][1]);
            out.add(obs, next->where);
        } else {
            auto camera = mrpt::obs::CObservationBearingRange::Create();
            camera->sensorLabel = name + ".camera";
            camera->timestamp = stamp;
            std::set<long> seen;  // an observation holds each subject once (MRPT's rule)
            for (const auto& row : next->rows) {
                const long barcode = long(row[0]);
                const auto it = subjectOf.find(barcode);
                if (it == subjectOf.end()) {
                    ++unknownBarcodes[barcode];
                    continue;
                }
                if (!seen.insert(it->second).second) {
                    ++repeatedSightings;
                    continue;
                }
                camera->sensedData.push_back(
                    {float(row[1]), float(row[2]), 0.0f, int32_t(it->second), {}});
            }
            if (!camera->sensedData.empty()) out.add(camera, next->where);
        }
        next->advance();
    }
    for (const auto& [barcode, n] : unknownBarcodes)
        out.note(mrpt::format("%zu measurements of barcode %ld, which no subject has, left out", n,
                              barcode));
    if (sameTimeCommands)
        out.note(
            mrpt::format("%zu odometry commands at the time stamp of the one before: the "
                         "later holds from there, one reading written",
                         sameTimeCommands));
    if (repeatedSightings)
        out.note(mrpt::format("%zu sightings of a subject already seen at that time stamp left "
                              "out: the first is kept",
                              repeatedSightings));
    if (!withOdometry) out.note("odometry left out (--opt odometry=no)");
    if (duration > 0) out.note(mrpt::format("the first %g s only (--opt duration)", duration));
    out.addSideFile(".beacons.ini", beaconIni(landmarks));
}

}  // namespace

void registerMrclam(FormatRegistry& r) {
    r.add({"mrclam",
           "UTIAS MRCLAM datasets: per robot rN, odometry commands -> CObservationOdometry "
           "(rN.odometry, integrated), measurements -> CObservationBearingRange (rN.camera, "
           "range and bearing, subjects through Barcodes.dat: robots 1-5, landmarks 6-20), "
           "Groundtruth -> ground truth; the landmarks -> <out>.beacons.ini",
           "<dataset folder>",
           1,
           1,
           {{"robots", "1,2,3,4,5", "which robots to import"},
            {"duration", "0", "s from the log's start to import; 0: all of it"},
            {"odometry", "yes", "no: leave the odometry out (the camera alone)"}},
           convertMrclam});
}

}  // namespace mrloc::logimport
