// `mrloc eval` on two TUM files: the table's figures are common::evaluate's (test_evaluation),
// the JSON is eval.json's, bad files and options are one line naming them.
#include <gtest/gtest.h>
#include <mrloc/common/JsonFile.h>
#include <mrloc/common/Trajectory.h>

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
