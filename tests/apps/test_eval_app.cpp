// `mrloc eval` on two TUM files: the table's figures are common::evaluate's (test_evaluation),
// the JSON is eval.json's, bad files and options are one line naming them.
#include <gtest/gtest.h>
#include <mrloc/common/JsonFile.h>
#include <mrloc/common/Trajectory.h>
#include <mrloc/report/Plots.h>

#include <fstream>

#include "MrlocCli.h"

using namespace mrloc;
using namespace mrloc::testing_cli;

namespace {

/** A drive along x at 1 m/s, a pose every 0.1 s from t0 to t1, offset by dy. */
std::string driveFile(const std::string& name, double t0, double t1, double dy) {
    common::Trajectory t;
    for (int k = 0; t0 + 0.1 * k <= t1 + 1e-9; ++k)
        t.push_back({1.7e9 + t0 + 0.1 * k, mrpt::poses::CPose3D(t0 + 0.1 * k, dy, 0, 0, 0, 0)});
    const std::string path = tmp(name);
    common::saveTum(path, t);
    return path;
}

}  // namespace

TEST(MrlocEval, ScoresOnTheTruthsStampsAndSaysWhatItCovered) {
    const std::string truth = driveFile("eval_truth.txt", 0, 10, 0);
    const std::string late = driveFile("eval_late.txt", 3, 10, 0.25);
    const auto r = mrlocCmd("eval " + late + " " + truth);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("coverage 70.3 % (71 of 101 truth stamps"), std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("longest gap 3.000 s"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("APE translation        rmse 0.25 "), std::string::npos) << r.output;
    const auto j = nlohmann::json::parse(mrlocCmd("eval " + late + " " + truth + " --json").output);
    EXPECT_EQ(j["coverage"]["covered"], 71);
    EXPECT_NEAR(j["ape"]["rmse_m"].get<double>(), 0.25, 1e-6);
    // origin alignment moves the first estimate onto the truth: no error left
    const auto o = nlohmann::json::parse(
        mrlocCmd("eval " + late + " " + truth + " --json --align origin").output);
    EXPECT_EQ(o["alignment"], "origin");
    EXPECT_NEAR(o["ape"]["max_m"].get<double>(), 0.0, 1e-6);
}

TEST(MrlocEval, BadFilesAndOptionsAreOneLineNamingThem) {
    const std::string truth = driveFile("eval_truth2.txt", 0, 2, 0);
    const std::string bad = tmp("eval_bad.txt");
    std::ofstream(bad) << "1.7e9 0 0 0 0 0 0 1\n1.7e9 zero 0 0 0 0 0 1\n";
    const std::string stepped = tmp("eval_stepped.txt");
    std::ofstream(stepped) << "0 1 2 0.5\n1 1 2 0.5\n";
    for (const auto& [args, says] : std::vector<std::pair<std::string, std::string>>{
             {bad + " " + truth, "eval_bad.txt"},
             {truth + " " + stepped, "counts odometry steps, not times"},
             {truth + " " + truth + " --align affine", "--align affine: none, se2 or origin"},
             {truth + " " + truth + " --delta 2km", "--delta 2km: a distance or a time"},
             {truth + " " + truth + " --max-gap 0", "--max-gap must be a time above 0 s"}}) {
        const auto r = mrlocCmd("eval " + args);
        EXPECT_EQ(r.code, 1) << args << ": " << r.output;
        EXPECT_NE(r.output.find(says), std::string::npos) << args << ": " << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    }
}

// --out: eval.json holds the table's figures, the four pictures are whole, and a second eval
// into the same folder replaces the first (the folder is the command's own, provenance says so)
TEST(MrlocEval, OutWritesEvalJsonAndThePictures) {
    const std::string truth = driveFile("eval_truth3.txt", 0, 10, 0);
    const std::string late = driveFile("eval_late3.txt", 3, 10, 0.25);
    const std::string dir = tmp("eval_out");
    std::filesystem::remove_all(dir);
    for (int run = 0; run < 2; ++run) {
        const auto r = mrlocCmd("eval " + late + " " + truth + " --out " + dir);
        ASSERT_EQ(r.code, 0) << r.output;
    }
    const auto j = common::readJsonFile(dir + "/eval.json");
    EXPECT_EQ(j["coverage"]["covered"], 71);
    EXPECT_EQ(j["coverage"]["truth_stamps"], 101);
    EXPECT_NEAR(j["ape"]["rmse_m"].get<double>(), 0.25, 1e-6);
    EXPECT_EQ(j["truth_file"], truth);
    for (const char* png :
         {"error_time.png", "error_cdf.png", "pose_time.png", "error_topview.png"})
        EXPECT_TRUE(report::isCompletePng(dir + "/" + png)) << png;
    const auto p = common::readJsonFile(dir + "/provenance.json");
    EXPECT_NE(p["steps"]["eval"].get<std::string>().find("eval_late3.txt"), std::string::npos);
}

// MRPT's ground truth of steps (x y z yaw pitch roll per step), timed by its rawlog's odometry:
// the file scored against itself covers every step with no error
TEST(MrlocEval, AFileOfStepsIsTimedByTheRawlogsOdometry) {
    const std::string data = "/usr/share/mrpt/datasets/";
    const std::string rawlog = data + "uwb_ro-localization_demo.rawlog";
    const std::string steps = data + "uwb_ro-localization_demo_GT.txt";  // i x y phi
    if (!std::filesystem::exists(rawlog) || !std::filesystem::exists(steps))
        GTEST_SKIP() << "MRPT's datasets (mrpt-common) are not installed";
    const auto r = mrlocCmd("eval " + steps + " " + steps + " --rawlog " + rawlog + " --json");
    ASSERT_EQ(r.code, 0) << r.output;
    const auto j = nlohmann::json::parse(r.output);
    EXPECT_EQ(j["coverage"]["truth_stamps"], 342);  // the log's 342 odometry steps
    EXPECT_EQ(j["coverage"]["covered"], 342);
    EXPECT_NEAR(j["ape"]["max_m"].get<double>(), 0.0, 1e-9);
    // a step at its sensory frame's time (--steps-at frame, where pf-localization's estimate
    // after the step is) or its odometry reading's: pf-localization's converged path of
    // localization_demo (data/real/mrpt-references) starts at step 8, whose action is stamped
    // 1137772795.033 s and whose scan 1137772795.138 s
    const std::string ref = std::string(MRLOC_SOURCE_DIR) +
                            "/data/real/mrpt-references/pf-localization.localization_demo.txt";
    for (const auto& [at, start] : std::vector<std::pair<std::string, double>>{
             {"odometry", 1137772795.033}, {"frame", 1137772795.138}}) {
        const auto p = mrlocCmd("eval " + ref + " " + ref + " --rawlog " + data +
                                "localization_demo.rawlog --json --steps-at " + at);
        ASSERT_EQ(p.code, 0) << p.output;
        const auto pj = nlohmann::json::parse(p.output);
        EXPECT_EQ(pj["coverage"]["covered"], 29) << at;
        EXPECT_NEAR(pj["coverage"]["start_s"].get<double>(), start, 0.001) << at;
    }
    // the kf-slam demo's odometry stamps its 249 steps within 8 ms, some within a microsecond:
    // refused, not scored against the wrong neighbour
    const auto k = mrlocCmd("eval " + data + "kf-slam_demo_ground_truth_robot_path.txt " + steps +
                            " --rawlog " + data + "kf-slam_demo.rawlog");
    EXPECT_EQ(k.code, 1) << k.output;
    EXPECT_NE(k.output.find("their order in time cannot be told"), std::string::npos) << k.output;
}
