// `mrloc import`: each format on real files (data/real, ../shared/data) against the source's
// own counts and span, the integration of odometry in closed form, bad input refused with its
// file and line and nothing written, and the beacon tracker on the imported libRSF log.
#include <mrloc/common/Error.h>
#include <mrloc/common/Rawlog.h>
#include <mrloc/common/Trajectory.h>
#include <mrloc/logimport/Format.h>
#include <mrloc/logimport/OdometryFit.h>
#include <mrloc/logimport/Unicycle.h>
#include <mrpt/core/format.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservationBeaconRanges.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CObservationRange.h>

#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>

#include "MrlocCli.h"

namespace {

using namespace mrloc::testing_cli;
namespace li = mrloc::logimport;
namespace fs = std::filesystem;

const std::string kReal = std::string(MRLOC_SOURCE_DIR) + "/data/real";
const std::string kShared = std::string(MRLOC_SOURCE_DIR) + "/../shared/data";

const li::Format& formatNamed(const std::string& name) {
    static li::FormatRegistry r = [] {
        li::FormatRegistry x;
        li::registerAllFormats(x);
        return x;
    }();
    return r.get(name);
}

std::vector<mrpt::obs::CObservation::Ptr> readAll(const std::string& path) {
    std::vector<mrpt::obs::CObservation::Ptr> out;
    mrloc::common::RawlogReader reader(path);
    for (mrpt::obs::CObservation::Ptr o; reader.next(o);) out.push_back(o);
    return out;
}

size_t streamCount(const li::ImportSummary& s, const std::string& label) {
    size_t n = 0;
    for (const auto& [key, c] : s.streams)
        if (key.first == label) n += c.count;
    return n;
}

TEST(ImportArc, StraightCircleAndSideways) {
    using mrpt::poses::CPose2D;
    // straight: 0.5 m/s for 2 s from (1, 2, 90 deg) ends at (1, 3)
    const CPose2D a = li::moveArc(CPose2D(1, 2, M_PI / 2), 0.5, 0, 0, 2);
    EXPECT_NEAR(a.x(), 1, 1e-12);
    EXPECT_NEAR(a.y(), 3, 1e-12);
    // a full circle of radius v / w returns to the start in one step of 2 pi / w
    const CPose2D c = li::moveArc(CPose2D(0, 0, 0), 1.0, 0, 0.5, 2 * M_PI / 0.5);
    EXPECT_NEAR(c.x(), 0, 1e-9);
    EXPECT_NEAR(c.y(), 0, 1e-9);
    // a quarter circle: radius 2, from heading 0, ends at (2, 2) heading 90 deg
    const CPose2D q = li::moveArc(CPose2D(0, 0, 0), 1.0, 0, 0.5, M_PI);
    EXPECT_NEAR(q.x(), 2, 1e-9);
    EXPECT_NEAR(q.y(), 2, 1e-9);
    EXPECT_NEAR(q.phi(), M_PI / 2, 1e-12);
    // one step equals many small ones (the arc is exact, not Euler's)
    CPose2D m(0, 0, 0);
    for (int i = 0; i < 1000; ++i) m = li::moveArc(m, 1.0, 0.2, 0.5, M_PI / 1000);
    const CPose2D one = li::moveArc(CPose2D(0, 0, 0), 1.0, 0.2, 0.5, M_PI);
    EXPECT_NEAR(m.x(), one.x(), 1e-9);
    EXPECT_NEAR(m.y(), one.y(), 1e-9);
}

TEST(Import, LibrsfLabyrinthAsTheSourceCountsIt) {
    const std::string dir = tmp("import_librsf");
    fs::create_directories(dir);
    const auto s = li::runImport(formatNamed("librsf"),
                                 {kReal + "/librsf-indoor-uwb/Indoor_UWB_Input.txt",
                                  kReal + "/librsf-indoor-uwb/Indoor_UWB_GT.txt"},
                                 {"wheel_base_scale=2", "swap_wheels=yes"}, dir + "/l.rawlog");
    // the source: 233 range2 lines, 233 odom2diff, 233 point2, from 0.127944 to 29.902198 s
    EXPECT_EQ(streamCount(s, "robot.uwb"), 233u);
    EXPECT_EQ(streamCount(s, "robot.odometry"), 233u);
    EXPECT_EQ(s.groundTruth.at("robot"), 233u);
    EXPECT_NEAR(s.t0, 0.127944, 1e-6);
    EXPECT_NEAR(s.t1, 29.902198, 1e-6);
    // the committed rawlog is exactly what the importer makes
    EXPECT_EQ(slurp(dir + "/l.rawlog"), slurp(kReal + "/librsf-indoor-uwb/labyrinth.rawlog"));
    EXPECT_EQ(slurp(dir + "/l.robot.gt.txt"),
              slurp(kReal + "/librsf-indoor-uwb/labyrinth.robot.gt.txt"));
    const std::string ini = slurp(dir + "/l.beacons.ini");
    EXPECT_NE(ini.find("beacon_108 = 2.385000 2.360000 0.000000"), std::string::npos) << ini;
    EXPECT_NE(ini.find("range_sigma = 0.100000"), std::string::npos) << ini;
    // the first range (line 1: 2.955 m to anchor 105) and the odometry's path length: 9.41 m
    // integrated from the wheel speeds (the same sum in Python over the file)
    const auto obs = readAll(dir + "/l.rawlog");
    const auto r = std::dynamic_pointer_cast<mrpt::obs::CObservationBeaconRanges>(obs[0]);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->sensedData.at(0).beaconID, 105);
    EXPECT_NEAR(r->sensedData.at(0).sensedDistance, 2.95522, 1e-5);
    double length = 0;
    std::optional<mrpt::poses::CPose2D> last;
    for (const auto& o : obs)
        if (auto odo = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(o)) {
            if (last) length += odo->odometry.distanceTo(*last);
            last = odo->odometry;
        }
    EXPECT_NEAR(length, 9.41, 0.02) << length;  // chords of the arcs: 9.399
}

TEST(Import, LibrsfOdometryThatDoesNotFitItsTruthIsSaid) {
    // Labyrinth read as its readme labels the columns: the odometry turns the other way and
    // twice as fast as the truth (data/real/README.md); the import says so in one line with
    // the options that fix it, and with them says nothing. Measured: a course gain of -1.92
    // over the first 30 s (8.9 m, 20.5 rad of course turned); data/real/README.md found 2 by
    // the fit of the whole path (0.066 m at 1.92)
    const std::string dir = tmp("import_odometry_fit");
    fs::create_directories(dir);
    const std::string lab = kReal + "/librsf-indoor-uwb/";
    const std::string inputs = lab + "Indoor_UWB_Input.txt " + lab + "Indoor_UWB_GT.txt";
    auto r = mrlocCmd("import librsf " + inputs + " --out " + dir + "/a.rawlog");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("warning: robot's odometry does not fit its ground truth over the "
                            "first 30 s"),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("it turns the other way, 1.92 times as fast; try --opt "
                            "swap_wheels=yes --opt wheel_base_scale=1.92"),
              std::string::npos)
        << r.output;
    size_t warnings = 0;  // one line
    for (size_t at = r.output.find("warning:"); at != std::string::npos;
         at = r.output.find("warning:", at + 1))
        ++warnings;
    EXPECT_EQ(warnings, 1u) << r.output;
    r = mrlocCmd("import librsf " + inputs +
                 " --opt wheel_base_scale=2 --opt swap_wheels=yes --out " + dir + "/b.rawlog");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(r.output.find("warning:"), std::string::npos) << r.output;
    // the fit itself, in closed form: an odometry that is the truth mirrored and scaled
    mrloc::common::Trajectory truth, odometry;
    for (int k = 0; k <= 600; ++k) {
        const double t = 0.1 * k, a = 0.05 * t;  // a circle of 4 m radius at 0.2 m/s
        truth.push_back(
            {t, mrpt::poses::CPose3D(4 * std::sin(a), 4 - 4 * std::cos(a), 0, a, 0, 0)});
        odometry.push_back(
            {t, mrpt::poses::CPose3D(6 * std::sin(a), -6 + 6 * std::cos(a), 0, -a, 0, 0)});
    }
    const auto fit = li::fitOdometry(odometry, truth);
    ASSERT_TRUE(fit);
    EXPECT_NEAR(fit->scale, 1.5, 1e-3);
    EXPECT_NEAR(fit->turnGain, -1.0, 1e-9);
    EXPECT_TRUE(fit->mirrored());
    EXPECT_TRUE(fit->scaleOff());
    EXPECT_FALSE(fit->turnRateOff());
    const auto help = mrlocCmd("import librsf --help");
    EXPECT_NE(help.output.find("--opt wheel_base_scale=1"), std::string::npos) << help.output;
    EXPECT_EQ(help.output.find("  mrclam "), std::string::npos) << help.output;
}

TEST(Import, UdacitySonarTimeUnitInferredAndNoEchoes) {
    const std::string dir = tmp("import_sonar");
    fs::create_directories(dir);
    const auto r =
        mrlocCmd("import sonar-text " + kReal + "/udacity-sonar/measurement.txt " + kReal +
                 "/udacity-sonar/poses.txt --opt " +
                 "bearings=-90,-37.5,-22.5,-7.5,7.5,22.5,37.5,90 --out " + dir + "/u.rawlog");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(slurp(dir + "/u.rawlog"), slurp(kReal + "/udacity-sonar/udacity.rawlog"));
    EXPECT_EQ(slurp(dir + "/u.robot.gt.txt"), slurp(kReal + "/udacity-sonar/udacity.robot.gt.txt"));
    EXPECT_NE(r.output.find("time unit inferred from the poses' speed: ms"), std::string::npos);
    // per sonar, the readings outside 170..5000 mm in the file (counted with awk)
    EXPECT_NE(r.output.find("per sonar: 63 131 107 179 334 127 129 21"), std::string::npos)
        << r.output;
    // 413 lines each; first 1686487 ms, last 1779324 ms: 92.837 s
    EXPECT_NE(r.output.find("826 observations"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("(92.837 s)"), std::string::npos) << r.output;
    const auto obs = readAll(dir + "/u.rawlog");
    const auto sonar = std::dynamic_pointer_cast<mrpt::obs::CObservationRange>(obs.at(1));
    ASSERT_TRUE(sonar);
    // line 1: 5110 5110 2320 2360 5110 5110 2160 1190 (mm): 5110 is no echo
    ASSERT_EQ(sonar->sensedData.size(), 8u);
    EXPECT_EQ(sonar->sensedData[0].sensedDistance, 0.0f);
    EXPECT_NEAR(sonar->sensedData[2].sensedDistance, 2.32, 1e-6);
    EXPECT_NEAR(sonar->sensedData[7].sensedDistance, 1.19, 1e-6);
    EXPECT_NEAR(sonar->sensedData[7].sensorPose.yaw, M_PI / 2, 1e-12);
    EXPECT_NEAR(sonar->sensedData[1].sensorPose.yaw, -37.5 * M_PI / 180, 1e-12);
    const auto truth = mrloc::common::loadTum(dir + "/u.robot.gt.txt");
    ASSERT_EQ(truth.size(), 413u);
    // the last pose: 16889 mm, -8968 mm... whichever line is last: 1779324 is its time
    EXPECT_NEAR(truth.back().t, 1779.324, 1e-6);
}

TEST(Import, CarmenLinesToTheirClasses) {
    const std::string dir = tmp("import_carmen");
    fs::create_directories(dir);
    // tests/data/carmen/tiny.clf: a PARAM, an ODOM, a 3-beam FLASER, a 2-sonar SONAR, a TRUEPOS
    const auto s = li::runImport(formatNamed("carmen"),
                                 {std::string(MRLOC_SOURCE_DIR) + "/tests/data/carmen/tiny.clf"},
                                 {}, dir + "/c.rawlog");
    EXPECT_EQ(streamCount(s, "robot.odometry"), 1u);
    EXPECT_EQ(streamCount(s, "robot.laser"), 1u);
    EXPECT_EQ(streamCount(s, "robot.sonar"), 1u);
    EXPECT_EQ(s.groundTruth.at("robot"), 1u);
    ASSERT_EQ(s.notes.size(), 2u);
    EXPECT_NE(s.notes[0].find("1 PARAM lines left out"), std::string::npos);
    // its clock starts at 10 s: relative time, said so (issue 54)
    EXPECT_NE(s.notes[1].find("the log's clock starts at 10.000 s: relative time"),
              std::string::npos);
    const auto obs = readAll(dir + "/c.rawlog");
    ASSERT_EQ(obs.size(), 3u);
    const auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservation2DRangeScan>(obs[1]);
    ASSERT_TRUE(scan);
    EXPECT_EQ(scan->getScanSize(), 3u);
    EXPECT_TRUE(scan->getScanRangeValidity(0));
    EXPECT_FALSE(scan->getScanRangeValidity(2));  // 81.9: the maximum, no return
    // the laser 0.1 m ahead of the odometry pose (heading 0.5 rad): sensor at x = 0.1
    EXPECT_NEAR(scan->sensorPose.x(), 0.1, 1e-6) << scan->sensorPose;
    EXPECT_NEAR(scan->sensorPose.y(), 0.0, 1e-6);
    const auto sonar = std::dynamic_pointer_cast<mrpt::obs::CObservationRange>(obs[2]);
    ASSERT_TRUE(sonar);
    EXPECT_NEAR(sonar->sensedData[0].sensedDistance, 1.5, 1e-6);
    EXPECT_EQ(sonar->sensedData[1].sensedDistance, 0.0f);  // 5.0 m: the maximum, no echo
    EXPECT_NEAR(sonar->sensedData[1].sensorPose.yaw, 1.5708, 1e-9);
    EXPECT_NEAR(sonar->sensorConeApperture, 0.26, 1e-6);
}

TEST(Import, MrclamExcerptAsItsFilesCountIt) {
    // tests/data/mrclam-excerpt: robots 1 and 3, the dataset's first 20 s; counted with awk:
    // odometry 478 and 253 lines (no two at one time), measurement times 26 and 33 (22 and 30
    // of them with a landmark), ground truth 972 and 1005 poses; every barcode known
    const std::string dir = tmp("import_mrclam_excerpt");
    fs::create_directories(dir);
    const auto s = li::runImport(formatNamed("mrclam"),
                                 {std::string(MRLOC_SOURCE_DIR) + "/tests/data/mrclam-excerpt"},
                                 {"robots=1,3"}, dir + "/x.rawlog");
    EXPECT_EQ(streamCount(s, "r1.odometry"), 478u);
    EXPECT_EQ(streamCount(s, "r3.odometry"), 253u);
    EXPECT_EQ(streamCount(s, "r1.camera"), 26u);
    EXPECT_EQ(streamCount(s, "r3.camera"), 33u);
    // the camera's ranges are in its sightings: no copy as CObservationBeaconRanges (issue 54)
    EXPECT_EQ(streamCount(s, "r1.ranges"), 0u);
    EXPECT_EQ(streamCount(s, "r3.ranges"), 0u);
    EXPECT_EQ(s.groundTruth.at("r1"), 972u);
    EXPECT_EQ(s.groundTruth.at("r3"), 1005u);
    EXPECT_TRUE(s.notes.empty()) << s.notes.front();
    // r1's first measurement (1248444189.599: barcode 14, robot 2, 3.787 m, -0.257 rad; and
    // barcode 90, landmark 15 in Barcodes.dat, 6.758 m, -0.005 rad)
    bool firstSeen = false;
    for (const auto& o : readAll(dir + "/x.rawlog")) {
        auto camera = std::dynamic_pointer_cast<mrpt::obs::CObservationBearingRange>(o);
        if (!camera || camera->sensorLabel != "r1.camera") continue;
        EXPECT_NEAR(mrpt::Clock::toDouble(camera->timestamp), 1248444189.599, 1e-6);
        ASSERT_EQ(camera->sensedData.size(), 2u);
        EXPECT_EQ(camera->sensedData[0].landmarkID, 2);
        EXPECT_NEAR(camera->sensedData[0].range, 3.787, 1e-6);
        EXPECT_NEAR(camera->sensedData[0].yaw, -0.257, 1e-6);
        EXPECT_EQ(camera->sensedData[1].landmarkID, 15);
        firstSeen = true;
        break;
    }
    EXPECT_TRUE(firstSeen) << "no r1.camera observation";
    // the odometry integrated from the commands: r1's path length over the excerpt equals the
    // sum of |v| dt over the commands (zero-order hold), computed from the file with awk
    double length = 0;
    std::optional<mrpt::poses::CPose2D> last;
    for (const auto& o : readAll(dir + "/x.rawlog"))
        if (auto odo = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(o);
            odo && odo->sensorLabel == "r1.odometry") {
            if (last) length += odo->odometry.distanceTo(*last);
            last = odo->odometry;
        }
    EXPECT_NEAR(length, 0.291281, 0.002) << length;  // chords of the arcs: a little less
}

TEST(Import, MrclamSubjectSeenTwiceAtOneStampKeepsTheFirst) {
    // r1's first measurement time (1248444189.599) given barcode 14 (robot 2) a second time at
    // another range: MRPT writes no observation holding a landmark twice, and the import once
    // ended "cannot write rawlog (is the disk full?)". The first sighting is kept, and said.
    const std::string src = tmp("import_mrclam_twice");
    fs::remove_all(src);
    fs::copy(std::string(MRLOC_SOURCE_DIR) + "/tests/data/mrclam-excerpt", src);
    {
        std::ifstream in(src + "/Robot1_Measurement.dat");
        std::stringstream text;
        text << in.rdbuf();
        std::string s = text.str();
        const std::string line = "1248444189.599 \t  14 \t  3.787 \t -0.257\n";
        const auto at = s.find(line);
        ASSERT_NE(at, std::string::npos);
        s.insert(at + line.size(), "1248444189.599 \t  14 \t  4.500 \t -0.300\n");
        std::ofstream(src + "/Robot1_Measurement.dat") << s;
    }
    const std::string dir = tmp("import_mrclam_twice_out");
    fs::create_directories(dir);
    const auto s = li::runImport(formatNamed("mrclam"), {src}, {"robots=1,3"}, dir + "/x.rawlog");
    EXPECT_EQ(streamCount(s, "r1.camera"), 26u);  // as without the line
    ASSERT_EQ(s.notes.size(), 1u);
    EXPECT_EQ(s.notes[0],
              "1 sightings of a subject already seen at that time stamp left out: the first is "
              "kept");
    for (const auto& o : readAll(dir + "/x.rawlog")) {
        auto camera = std::dynamic_pointer_cast<mrpt::obs::CObservationBearingRange>(o);
        if (!camera || camera->sensorLabel != "r1.camera") continue;
        ASSERT_EQ(camera->sensedData.size(), 2u);
        EXPECT_EQ(camera->sensedData[0].landmarkID, 2);
        EXPECT_NEAR(camera->sensedData[0].range, 3.787, 1e-6);
        break;
    }
}

TEST(Import, MrclamDataset6AsTheSourceCountsIt) {
    const std::string src = kShared + "/mrclam-ds6";
    if (!fs::is_directory(src))
        GTEST_SKIP() << "../shared/data/mrclam-ds6 is absent: MRCLAM is not in the repository";
    const std::string dir = tmp("import_mrclam");
    fs::create_directories(dir);
    const auto s =
        li::runImport(formatNamed("mrclam"), {src}, {"robots=2", "duration=60"}, dir + "/m.rawlog");
    // robot 2's first 60 s from its earliest record (1248444175.103, a ground-truth line),
    // counted in the files with awk: 2745 odometry lines, 3182 poses, 24 measurement times
    EXPECT_EQ(streamCount(s, "r2.odometry"), 2745u);
    EXPECT_EQ(s.groundTruth.at("r2"), 3182u);
    EXPECT_EQ(streamCount(s, "r2.camera"), 24u);
    EXPECT_EQ(s.groundTruth.count("r1"), 0u);
    EXPECT_NE(slurp(dir + "/m.beacons.ini").find("beacon_6 = 0.588314 -4.282648 0"),
              std::string::npos);
}

TEST(Import, BadInputNamesFileAndLineAndWritesNothing) {
    const std::string dir = tmp("import_bad");
    fs::create_directories(dir);
    const std::string good = "range2 0.1 2.0 0.01 0 0 1 0\nodom2diff 0.1 0 0 0 0.1 0 0 0\n";
    const std::vector<std::pair<std::string, std::string>> cases = {
        {good + "range2 0.2 2.0 0.01 0 0\n", ":3: 6 fields where 7 are needed"},
        {good + "range2 0.2 nan 0.01 0 0 1 0\n", ":3: range (field 3) is not finite"},
        {good + "range2 0.05 2.0 0.01 0 0 1 0\n", ":3: time goes back"},
        {good + "range2 0.2 2.0 -0.01 0 0 1 0\n", ":3: range variance -0.01 m^2 cannot be"},
        {good + "odom2diff 0.2 0 0 0 -1 0 0 0\n", ":3: wheel base -1 m cannot be"},
        {good + "range2 0.2 2.0x 0.01 0 0 1 0\n", ":3: range (field 3) is '2.0x', not a number"},
    };
    for (const auto& [text, expected] : cases) {
        std::ofstream(dir + "/in.txt") << text;
        const auto r = mrlocCmd("import librsf " + dir + "/in.txt --out " + dir + "/o.rawlog");
        EXPECT_EQ(r.code, 1) << text;
        EXPECT_NE(r.output.find(dir + "/in.txt" + expected), std::string::npos) << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
        EXPECT_FALSE(fs::exists(dir + "/o.rawlog"));
        EXPECT_FALSE(fs::exists(dir + "/o.beacons.ini"));
    }
    // a unit that cannot be, an unknown option, an unknown format: one line each
    const auto unit = mrlocCmd("import sonar-text " + kReal + "/udacity-sonar/measurement.txt " +
                               kReal + "/udacity-sonar/poses.txt --opt bearings=0,1,2,3,4,5,6,7 " +
                               "--opt length_unit=furlong --out " + dir + "/o.rawlog");
    EXPECT_EQ(unit.code, 1);
    EXPECT_NE(unit.output.find("length_unit=furlong: expected one of m, cm, mm"), std::string::npos)
        << unit.output;
    const auto opt =
        mrlocCmd("import librsf " + dir + "/in.txt --opt robto=x --out " + dir + "/o.rawlog");
    EXPECT_NE(opt.output.find("did you mean 'robot'?"), std::string::npos) << opt.output;
    const auto fmt = mrlocCmd("import libsrf x --out " + dir + "/o.rawlog");
    EXPECT_NE(fmt.output.find("did you mean 'librsf'?"), std::string::npos) << fmt.output;
    EXPECT_FALSE(fs::exists(dir + "/o.rawlog"));
    const auto help = mrlocCmd("import --help");
    EXPECT_EQ(help.code, 0);
    for (const char* f : {"carmen", "librsf", "mrclam", "sonar-text"})
        EXPECT_NE(help.output.find(std::string("\n  ") + f + " "), std::string::npos) << f;
}

/** metrics.json of `mrloc localize <ini> <rawlog>` into a new folder. */
nlohmann::json localized(const std::string& ini, const std::string& rawlog,
                         const std::string& name) {
    const std::string out = tmp(name);
    const auto r = mrlocCmd("localize " + ini + " " + rawlog + " -q --out " + out);
    EXPECT_EQ(r.code, 0) << r.output;
    return nlohmann::json::parse(slurp(out + "/metrics.json"));
}

TEST(RealLogs, BeaconTrackerOnLibrsfLabyrinth) {
    // measured: RMSE 0.0819 m, max 0.339 m with odometry (0.0797 m, 0.332 m before issue 54's
    // random walk and Huber's loss; bounds 10 % above the older); the ranges
    // carry 7-15 cm of bias per anchor (their median residual against the ground truth), which
    // the tracker's offsets learn
    const auto m = localized(config("beacons_librsf"),
                             kReal + "/librsf-indoor-uwb/labyrinth.rawlog", "librsf_tracker");
    EXPECT_LT(m["rmse_m"].get<double>(), 0.088);
    EXPECT_LT(m["max_m"].get<double>(), 0.37);
    EXPECT_GE(m["n"].get<int>(), 220);
    const auto offsets = m["beacons"]["robots"]["robot"]["range_offsets_m"];
    for (const auto& [id, v] : offsets.items()) {
        EXPECT_GT(v.get<double>(), 0.03) << id;
        EXPECT_LT(v.get<double>(), 0.16) << id;
    }
    EXPECT_GT(m["use"]["used"].get<int>(), 150);
}

TEST(RealLogs, BeaconTrackerOnLibrsfWithoutOdometry) {
    // ranges alone (a tag on a person): the random-walk motion model; measured RMSE 0.143 m
    // (0.149 m before issue 54)
    const std::string dir = tmp("librsf_no_odometry");
    fs::create_directories(dir);
    li::runImport(formatNamed("librsf"),
                  {kReal + "/librsf-indoor-uwb/Indoor_UWB_Input.txt",
                   kReal + "/librsf-indoor-uwb/Indoor_UWB_GT.txt"},
                  {"odometry=no"}, dir + "/n.rawlog");
    const auto m = localized(config("beacons_librsf"), dir + "/n.rawlog", "librsf_no_odo_run");
    EXPECT_EQ(m["rawlog_content"].count("CObservationOdometry"), 0u);
    EXPECT_LT(m["rmse_m"].get<double>(), 0.165);
}

}  // namespace

namespace {

TEST(RealLogs, BeaconTrackerOnMrclamDataset6) {
    // each of the 5 robots from its camera's sightings (range and bearing) of the 15 surveyed
    // landmarks and its odometry, against Vicon, with the INI import wrote, unchanged (the
    // shipped config/beacons_mrclam.ini has its keys). Measured on the truth's timeline: pooled
    // APE RMSE 0.244 m over 96.3 % of the stamps; per robot r1-r5 0.194 / 0.260 / 0.261 /
    // 0.281 / 0.206 m (coverage 92.0-98.0 %) against odometry alone 1.77-4.17 m. Before issue
    // 54 (ranges only, no particle start): 0.832 m over 48.1 %. Bounds 10 % above; the issue's
    // goal, 0.3 m for every robot, is asserted as it is
    const std::string src = kShared + "/mrclam-ds6";
    if (!fs::is_directory(src))
        GTEST_SKIP() << "../shared/data/mrclam-ds6 is absent: MRCLAM is not in the repository";
    const std::string dir = tmp("mrclam_whole");
    fs::create_directories(dir);
    li::runImport(formatNamed("mrclam"), {src}, {}, dir + "/m.rawlog");
    // the shipped INI's map is the one the import wrote
    const std::string written = slurp(dir + "/m.beacons.ini");
    const std::string shipped = slurp(config("beacons_mrclam"));
    for (size_t at = written.find("beacon_"); at != std::string::npos;
         at = written.find("beacon_", at + 1))
        EXPECT_NE(shipped.find(written.substr(at, written.find('\n', at) - at)), std::string::npos);
    const auto m = localized(dir + "/m.beacons.ini", dir + "/m.rawlog", "mrclam_tracker");
    EXPECT_LT(m["truth_timeline"]["ape"]["rmse_m"].get<double>(), 0.27);
    EXPECT_GT(m["truth_timeline"]["share"].get<double>(), 0.95);
    ASSERT_EQ(m["robots"].size(), 5u);
    for (const auto& [robot, r] : m["robots"].items()) {
        const auto& tt = r["truth_timeline"];
        EXPECT_LT(tt["ape"]["rmse_m"].get<double>(), 0.30) << robot;
        EXPECT_GT(tt["coverage"]["share"].get<double>(), 0.90) << robot;
        EXPECT_LT(tt["ape"]["rmse_m"].get<double>(),
                  r["odometry"]["truth_timeline"]["ape"]["rmse_m"].get<double>())
            << robot;
    }
    // the other robots the cameras saw are counted, not taken for landmarks
    EXPECT_GT(m["beacons"]["sightings_not_in_map"].get<int>(), 0);
    EXPECT_GT(m["beacons"]["bearings_used"].get<int>(), 10000);
}

}  // namespace

namespace {

const std::string kBag = std::string(MRLOC_SOURCE_DIR) + "/tests/data/rosbag/tiny.bag";

TEST(Import, RosbagMessagesToTheirClasses) {
    const std::string dir = tmp("import_rosbag");
    fs::create_directories(dir);
    const auto s = li::runImport(formatNamed("rosbag"), {kBag}, {}, dir + "/b.rawlog");
    // tests/data/rosbag/make_tiny_bag.py: 10 /odom, 5 /scan, 3 /sonar_front, 4 /tf, 1 /chatter
    EXPECT_EQ(streamCount(s, "robot.odom"), 10u);
    EXPECT_EQ(streamCount(s, "robot.scan"), 5u);
    EXPECT_EQ(streamCount(s, "robot.sonar_front"), 3u);
    EXPECT_EQ(streamCount(s, "robot.tf_odometry"), 4u);
    EXPECT_NEAR(s.t0, 1700000000.0, 1e-6);
    EXPECT_NEAR(s.t1, 1700000000.9, 1e-6);
    std::string notes;
    for (const auto& n : s.notes) notes += n + "\n";
    EXPECT_NE(notes.find("1 messages of /chatter (std_msgs/String) left out"), std::string::npos)
        << notes;
    EXPECT_NE(notes.find("3 messages in frame 'sonar_front'"), std::string::npos) << notes;
    double last = 0;
    size_t odometryChecked = 0, noEchoes = 0;  // the two checks below that pick one reading
    for (const auto& o : readAll(dir + "/b.rawlog")) {
        const double t = mrpt::Clock::toDouble(o->timestamp);
        EXPECT_GE(t, last);  // written in stamp order
        last = t;
        if (auto odo = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(o);
            odo && odo->sensorLabel == "robot.odom" && std::abs(t - 1700000000.2) < 1e-6) {
            EXPECT_NEAR(odo->odometry.x(), 0.2, 1e-9);
            EXPECT_NEAR(odo->odometry.phi(), 0.1, 1e-9);
            EXPECT_NEAR(odo->velocityLocal.vx, 1.0, 1e-9);
            EXPECT_NEAR(odo->velocityLocal.omega, 0.5, 1e-9);
            ++odometryChecked;
        }
        if (auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservation2DRangeScan>(o)) {
            ASSERT_EQ(scan->getScanSize(), 5u);
            EXPECT_NEAR(scan->aperture, M_PI, 1e-6);
            // 1, 2, inf (no return), 0.05 (under range_min), 3 + k
            EXPECT_TRUE(scan->getScanRangeValidity(0));
            EXPECT_FALSE(scan->getScanRangeValidity(2));
            EXPECT_FALSE(scan->getScanRangeValidity(3));
            EXPECT_NEAR(scan->getScanRange(1), 2.0, 1e-6);
            // /tf_static: the laser 0.2 m ahead, turned 0.1 rad; the beams centred on it
            EXPECT_NEAR(scan->sensorPose.x(), 0.2, 1e-9);
            EXPECT_NEAR(scan->sensorPose.yaw(), 0.1, 1e-9);
        }
        if (auto sonar = std::dynamic_pointer_cast<mrpt::obs::CObservationRange>(o)) {
            EXPECT_NEAR(sonar->sensorConeApperture, 0.5, 1e-6);
            const bool third = std::abs(t - 1700000000.61) < 1e-6;
            EXPECT_NEAR(sonar->sensedData.at(0).sensedDistance, third ? 0.0 : 1.5, 1e-6);
            noEchoes += third;
        }
    }
    EXPECT_EQ(odometryChecked, 1u);
    EXPECT_EQ(noEchoes, 1u);
}

TEST(Import, RosbagTopicsMappedByAnIni) {
    const std::string dir = tmp("import_rosbag_map");
    fs::create_directories(dir);
    std::ofstream(dir + "/topics.ini") << "[topics]\n/scan = r7.laser\n/odom = r7.odometry\n";
    const auto r = mrlocCmd("import rosbag " + kBag + " --opt topics=" + dir +
                            "/topics.ini --out " + dir + "/m.rawlog");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("r7.laser"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("3 messages of /sonar_front (not in the topic map) left out"),
              std::string::npos)
        << r.output;
    EXPECT_EQ(readAll(dir + "/m.rawlog").size(), 15u);  // 5 scans + 10 odometry readings
}

TEST(Import, RosbagScriptMakesTheCommittedBag) {
    // the committed bag is what its script writes (Debian's python3-rosbag)
    if (std::system("/usr/bin/python3 -c 'import rosbag, nav_msgs.msg' 2>/dev/null") != 0)
        GTEST_SKIP() << "Debian's python3-rosbag is not installed (scripts/install-deps.sh)";
    const std::string dir = tmp("rosbag_script");
    fs::create_directories(dir);
    ASSERT_EQ(std::system(("/usr/bin/python3 " + std::string(MRLOC_SOURCE_DIR) +
                           "/tests/data/rosbag/make_tiny_bag.py " + dir + "/t.bag")
                              .c_str()),
              0);
    EXPECT_EQ(slurp(dir + "/t.bag"), slurp(kBag));
}

TEST(Import, BrokenBagsAreOneLineAndWriteNothing) {
    const std::string dir = tmp("import_rosbag_bad");
    fs::create_directories(dir);
    const std::string bag = slurp(kBag);
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"truncated.bag", bag.substr(0, bag.size() / 2)},
        {"header.bag", bag.substr(0, 13)},
        {"garbage.bag", std::string(4096, '\x7f')},
        {"flipped.bag", [&] {
             std::string b = bag;
             for (size_t i = 4096; i < b.size(); i += 97) b[i] = char(b[i] ^ 0x5a);
             return b;
         }()}};
    for (const auto& [name, bytes] : cases) {
        std::ofstream(dir + "/" + name, std::ios::binary) << bytes;
        const auto r =
            mrlocCmd("import rosbag " + dir + "/" + name + " --out " + dir + "/o.rawlog");
        EXPECT_EQ(r.code, 1) << name << ": " << r.output;
        EXPECT_NE(r.output.find(dir + "/" + name), std::string::npos) << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
        for (const auto& e : fs::directory_iterator(dir))
            EXPECT_EQ(e.path().filename().string().rfind("o.", 0), std::string::npos)
                << name << " left " << e.path();
    }
}

}  // namespace

// issue 51, items 7, 12 and 13: an import writes nothing mrloc would refuse (what localize
// checks, checked as written), the truth is bounded where it enters, and names are names
TEST(Import, WritesNothingLocalizeWouldRefuse) {
    const std::string dir = tmp("import_bounds");
    fs::create_directories(dir);
    const std::string in = dir + "/in.txt", gt = dir + "/gt.txt", out = dir + "/o.rawlog";
    std::string many = "odom2diff 0.1 0 0 0 0.1 0 0 0\n";
    for (int i = 0; i < 1001; ++i)  // 1,001 anchors heard at one stamp: one observation
        many += "range2 0.2 2.0 0.01 " + std::to_string(i) + " 0 " + std::to_string(i) + " 0\n";
    std::ofstream(in) << many;
    auto r = mrlocCmd("import librsf " + in + " --out " + out);
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find(in + ":2: 1001 beacon ranges in one observation, more than the 1000"),
              std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(out));

    std::string anchors;  // 100,001 anchors: a beacon map INI localize would refuse
    for (int i = 0; i <= 100000; ++i)
        anchors += "range2 " + std::to_string(1 + i) + " 2.0 0.01 " + std::to_string(i % 1000) +
                   " " + std::to_string(i / 1000) + " " + std::to_string(i) + " 0\n";
    std::ofstream(in) << anchors;
    r = mrlocCmd("import librsf " + in + " --out " + out);
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find(in + ":100001: more than 100000 anchors"), std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(out));

    std::ofstream(in) << "range2 0.1 2.0 0.01 0 0 1 0\nodom2diff 0.1 0 0 0 0.1 0 0 0\n";
    std::ofstream(gt) << "point2 0.1 0 0\npoint2 0.2 1e19 0\n";
    r = mrlocCmd("import librsf " + in + " " + gt + " --out " + out);
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find(gt + ":2: ground truth: position (1e+19, 0, 0) m is not within 1,000 km"),
              std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(out));

    r = mrlocCmd("import librsf " + in + " --out '" + dir + "/o\nx.rawlog'");
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("a control character (a newline?) in the name"), std::string::npos)
        << r.output;
    // the beacon map's comment gives a command a user may paste: its names quoted
    r = mrlocCmd("import librsf " + in + " --out '" + dir + "/o $(touch PWNED).rawlog'");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(slurp(dir + "/o $(touch PWNED).beacons.ini")
                  .find("# mrloc localize 'o $(touch PWNED).beacons.ini' 'o $(touch "
                        "PWNED).rawlog'\n"),
              std::string::npos);
}

// issue 54: one time rule from import to localize. Every format, its times moved so that the
// log's clock starts at exactly 0 (most datasets' clocks: 0 was refused as "before 1970"), is
// imported, said to be relative time, and localized with the same figures as at its own times.
namespace {

/** `from`'s lines with the number in field `field` (0-based, whitespace-separated) less
 *  `offset`, printed with 9 decimals; '#' lines and other fields as they were. */
void shiftTimes(const std::string& from, const std::string& to, size_t field, double offset,
                size_t fieldFromEnd = 0) {
    std::ifstream in(from);
    std::ofstream out(to);
    for (std::string line; std::getline(in, line);) {
        std::istringstream words(line);
        std::vector<std::string> w{std::istream_iterator<std::string>(words), {}};
        if (w.empty() || w[0][0] == '#' || w[0] == "PARAM") {  // a CARMEN PARAM has no time
            out << line << "\n";
            continue;
        }
        const size_t i = fieldFromEnd ? w.size() - fieldFromEnd : field;
        w.at(i) = mrpt::format("%.9f", std::stod(w.at(i)) - offset);
        for (size_t k = 0; k < w.size(); ++k) out << (k ? " " : "") << w[k];
        out << "\n";
    }
}

double firstTime(const std::vector<std::string>& files, size_t field) {
    double first = INFINITY;
    for (const auto& f : files) {
        std::ifstream in(f);
        for (std::string line; std::getline(in, line);) {
            std::istringstream words(line);
            std::vector<std::string> w{std::istream_iterator<std::string>(words), {}};
            if (!w.empty() && w[0][0] != '#') first = std::min(first, std::stod(w.at(field)));
        }
    }
    return first;
}

/** Imports and localizes, expecting both to succeed; the metrics. */
nlohmann::json importedAndLocalized(const std::string& command, const std::string& rawlog,
                                    const std::string& ini, const std::string& out) {
    const auto imported = mrlocCmd(command + " --out " + rawlog);
    EXPECT_EQ(imported.code, 0) << imported.output;
    const auto r = mrlocCmd("localize " + ini + " " + rawlog + " -q --out " + out);
    EXPECT_EQ(r.code, 0) << r.output;
    if (r.code != 0) return {};
    return nlohmann::json::parse(slurp(out + "/metrics.json"));
}

}  // namespace

TEST(Import, EveryFormatFromTimeZeroLocalizes) {
    const std::string dir = tmp("time_zero");
    fs::create_directories(dir);
    // librsf: Labyrinth, its first range at 0.128 s moved to 0
    const std::string lab = kReal + "/librsf-indoor-uwb/";
    const double t0 = firstTime({lab + "Indoor_UWB_Input.txt"}, 1);
    shiftTimes(lab + "Indoor_UWB_Input.txt", dir + "/in.txt", 1, t0);
    shiftTimes(lab + "Indoor_UWB_GT.txt", dir + "/gt.txt", 1, t0);
    const std::string opts = " --opt wheel_base_scale=2 --opt swap_wheels=yes";
    const auto zero =
        importedAndLocalized("import librsf " + dir + "/in.txt " + dir + "/gt.txt" + opts,
                             dir + "/l0.rawlog", config("beacons_librsf"), dir + "/l0");
    const auto own = importedAndLocalized(
        "import librsf " + lab + "Indoor_UWB_Input.txt " + lab + "Indoor_UWB_GT.txt" + opts,
        dir + "/l1.rawlog", config("beacons_librsf"), dir + "/l1");
    ASSERT_FALSE(zero.empty());
    ASSERT_FALSE(own.empty());
    EXPECT_NEAR(zero["rmse_m"].get<double>(), own["rmse_m"].get<double>(), 1e-3);
    EXPECT_EQ(zero["n"], own["n"]);
    const auto info = mrlocCmd("info " + dir + "/l0.rawlog");
    EXPECT_NE(info.output.find("start: t = 0.000 s (relative clock)"), std::string::npos)
        << info.output;
    const auto note = mrlocCmd("import librsf " + dir + "/in.txt --out " + dir + "/n.rawlog");
    EXPECT_NE(note.output.find("note: the log's clock starts at 0.000 s: relative time"),
              std::string::npos)
        << note.output;

    // mrclam: the excerpt's five files per robot, all moved by the earliest time
    const std::string ex = std::string(MRLOC_SOURCE_DIR) + "/tests/data/mrclam-excerpt/";
    fs::create_directories(dir + "/mrclam");
    std::vector<std::string> timed;
    for (const auto& e : fs::directory_iterator(ex))
        if (e.path().filename().string().rfind("Robot", 0) == 0) timed.push_back(e.path());
    const double m0 = firstTime(timed, 0);
    for (const auto& e : fs::directory_iterator(ex)) {
        const std::string to = dir + "/mrclam/" + e.path().filename().string();
        if (e.path().filename().string().rfind("Robot", 0) == 0)
            shiftTimes(e.path(), to, 0, m0);
        else
            fs::copy_file(e.path(), to, fs::copy_options::overwrite_existing);
    }
    const auto mz = importedAndLocalized("import mrclam " + dir + "/mrclam --opt robots=1,3",
                                         dir + "/m0.rawlog", dir + "/m0.beacons.ini", dir + "/m0");
    const auto mo = importedAndLocalized("import mrclam " + ex + " --opt robots=1,3",
                                         dir + "/m1.rawlog", dir + "/m1.beacons.ini", dir + "/m1");
    ASSERT_FALSE(mz.empty());
    ASSERT_FALSE(mo.empty());
    EXPECT_GT(mz["n"].get<int>(), 0);
    EXPECT_EQ(mz["n"], mo["n"]);
    EXPECT_NEAR(mz["rmse_m"].get<double>(), mo["rmse_m"].get<double>(), 1e-3);

    // sonar-text: Udacity's poses and readings, 1686487 ms moved to 0
    const std::string ud = kReal + "/udacity-sonar/";
    shiftTimes(ud + "measurement.txt", dir + "/meas.txt", 0, 1686487);
    shiftTimes(ud + "poses.txt", dir + "/poses.txt", 0, 1686487);
    const std::string bearings = " --opt bearings=-90,-37.5,-22.5,-7.5,7.5,22.5,37.5,90";
    const auto uz =
        importedAndLocalized("import sonar-text " + dir + "/meas.txt " + dir +
                                 "/poses.txt --opt time_unit=ms" + bearings,
                             dir + "/u0.rawlog", config("framesync_udacity"), dir + "/u0");
    const auto uo =
        importedAndLocalized("import sonar-text " + ud + "measurement.txt " + ud +
                                 "poses.txt --opt time_unit=ms" + bearings,
                             dir + "/u1.rawlog", config("framesync_udacity"), dir + "/u1");
    ASSERT_FALSE(uz.empty());
    ASSERT_FALSE(uo.empty());
    EXPECT_EQ(uz["n"], uo["n"]);
    EXPECT_NEAR(uz["rmse_m"].get<double>(), uo["rmse_m"].get<double>(), 1e-3);

    // carmen: the tiny log, its stamps from 0; too short for a method, localize reads it whole
    // and stops only at what the method finds (not at a time stamp)
    shiftTimes(std::string(MRLOC_SOURCE_DIR) + "/tests/data/carmen/tiny.clf", dir + "/c.clf", 0,
               10.0, 3);
    auto c = mrlocCmd("import carmen " + dir + "/c.clf --out " + dir + "/c.rawlog");
    ASSERT_EQ(c.code, 0) << c.output;
    EXPECT_NE(c.output.find("relative time"), std::string::npos) << c.output;
    c = mrlocCmd("localize " + config("polymap_file") + " " + dir + "/c.rawlog -q --out " + dir +
                 "/c");
    EXPECT_EQ(c.output.find("time stamp"), std::string::npos) << c.output;
    EXPECT_EQ(c.output.find("1970"), std::string::npos) << c.output;

    // rosbag: the tiny bag's script with its clock at 0
    if (std::system("/usr/bin/python3 -c 'import rosbag, nav_msgs.msg' 2>/dev/null") != 0)
        GTEST_SKIP() << "Debian's python3-rosbag is not installed (scripts/install-deps.sh)";
    ASSERT_EQ(std::system(("/usr/bin/python3 " + std::string(MRLOC_SOURCE_DIR) +
                           "/tests/data/rosbag/make_tiny_bag.py " + dir + "/z.bag 0")
                              .c_str()),
              0);
    auto b = mrlocCmd("import rosbag " + dir + "/z.bag --out " + dir + "/z.rawlog");
    ASSERT_EQ(b.code, 0) << b.output;
    EXPECT_NE(b.output.find("relative time"), std::string::npos) << b.output;
    b = mrlocCmd("localize " + config("framesync_udacity") + " " + dir + "/z.rawlog -q --out " +
                 dir + "/z");
    EXPECT_EQ(b.output.find("time stamp"), std::string::npos) << b.output;
    EXPECT_EQ(b.output.find("1970"), std::string::npos) << b.output;
}

// issue 51, item 10: a /tf rotation never filled, (0, 0, 0, 0), is read as Odometry's is (no
// rotation), not refused in MRPT's quaternion words; a rotation that is not a number is one line
TEST(Import, RosbagTransformRotationsReadAsOdometrysAre) {
    if (std::system("/usr/bin/python3 -c 'import rosbag, tf2_msgs.msg' 2>/dev/null") != 0)
        GTEST_SKIP() << "Debian's python3-rosbag is not installed (scripts/install-deps.sh)";
    const std::string dir = tmp("import_rosbag_tf");
    fs::create_directories(dir);
    std::ofstream(dir + "/make.py")
        << "import sys, rosbag, rospy\n"
           "from geometry_msgs.msg import TransformStamped\n"
           "from tf2_msgs.msg import TFMessage\n"
           "with rosbag.Bag(sys.argv[1], 'w') as bag:\n"
           "    for k in range(3):\n"
           "        t = TransformStamped()\n"
           "        t.header.stamp = rospy.Time.from_sec(1000 + k)\n"
           "        t.header.frame_id, t.child_frame_id = 'odom', 'base_link'\n"
           "        t.transform.translation.x = 0.5 * k\n"
           "        t.transform.rotation.w = float(sys.argv[2])\n"
           "        bag.write('/tf', TFMessage(transforms=[t]), t.header.stamp)\n";
    ASSERT_EQ(std::system(("/usr/bin/python3 " + dir + "/make.py " + dir + "/zero.bag 0").c_str()),
              0);
    ASSERT_EQ(std::system(("/usr/bin/python3 " + dir + "/make.py " + dir + "/nan.bag nan").c_str()),
              0);
    auto r = mrlocCmd("import rosbag " + dir + "/zero.bag --out " + dir + "/z.rawlog");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("robot.tf_odometry    mrpt::obs::CObservationOdometry            3"),
              std::string::npos)
        << r.output;
    r = mrlocCmd("import rosbag " + dir + "/nan.bag --out " + dir + "/n.rawlog");
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("nan.bag: /tf: a transform with a value that is not a number"),
              std::string::npos)
        << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_FALSE(fs::exists(dir + "/n.rawlog"));
}

namespace {

// issue 51, item 9: the bag read in time order through one heap of per-topic cursors
// (rosbag::View's iterator was quadratic in topics). 300 topics written one after the other,
// each 40 s long: read in file order, time would go back far beyond the reorder window; two
// topics at one stamp keep the bag's file order
TEST(Import, RosbagOfManyTopicsIsReadInTimeOrder) {
    if (std::system("/usr/bin/python3 -c 'import rosbag, nav_msgs.msg' 2>/dev/null") != 0)
        GTEST_SKIP() << "Debian's python3-rosbag is not installed (scripts/install-deps.sh)";
    const std::string dir = tmp("import_rosbag_topics");
    fs::create_directories(dir);
    std::ofstream(dir + "/make.py")
        << "import sys, rosbag, rospy\n"
           "from nav_msgs.msg import Odometry\n"
           "def odometry(bag, topic, t, x):\n"
           "    o = Odometry()\n"
           "    o.header.stamp = rospy.Time.from_sec(t)\n"
           "    o.pose.pose.position.x, o.pose.pose.orientation.w = x, 1.0\n"
           "    bag.write(topic, o, o.header.stamp)\n"
           "with rosbag.Bag(sys.argv[1], 'w') as bag:\n"
           "    odometry(bag, '/tie_b', 999.5, -2.0)\n"
           "    odometry(bag, '/tie_a', 999.5, -1.0)\n"
           "    for i in range(300):\n"
           "        for j in range(5):\n"
           "            odometry(bag, '/odom%d' % i, 1000 + 10 * j + 0.01 * i, i + 0.1 * j)\n";
    ASSERT_EQ(std::system(("/usr/bin/python3 " + dir + "/make.py " + dir + "/t.bag").c_str()), 0);
    const auto r = mrlocCmd("import rosbag " + dir + "/t.bag --out " + dir + "/t.rawlog");
    ASSERT_EQ(r.code, 0) << r.output;
    std::vector<double> xs;
    double last = 0;
    for (const auto& o : readAll(dir + "/t.rawlog")) {
        const double t = mrpt::Clock::toDouble(o->timestamp);
        EXPECT_GE(t, last);
        last = t;
        if (auto odo = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(o))
            xs.push_back(odo->odometry.x());
    }
    ASSERT_EQ(xs.size(), 2u + 300 * 5);
    EXPECT_EQ(xs[0], -2.0);  // the stamp's tie in the bag's file order
    EXPECT_EQ(xs[1], -1.0);
    for (size_t k = 2; k < xs.size(); ++k) {  // time 1000 + 10 j + 0.01 i
        const size_t j = (k - 2) / 300, i = (k - 2) % 300;
        EXPECT_NEAR(xs[k], double(i) + 0.1 * double(j), 1e-9) << k;
    }
}

}  // namespace
