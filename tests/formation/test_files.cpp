// The formation method's run-directory files read back what was written, and a malformed
// line is an error naming the file and line.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/formation/FormationFiles.h>

#include <filesystem>
#include <fstream>

using namespace mrloc;

TEST(FormationFiles, RunAndExperimentFilesRoundTrip) {
    const std::string dir = testing::TempDir() + "/formation_files";
    std::filesystem::create_directories(dir);
    formation::FormationRunFile run;
    run.route = {{1.5, 0.65}, {20, 0.65}};
    run.start = {{0.75, 0}, {0, 1.3}};
    run.moves.push_back({1.7e9 + 0.05, "f2", {3, 1.3}, {3.01, 1.29}});
    run.moves.push_back({1.7e9 + 17.5, "f1", {3.75, 0}, {NAN, NAN}});
    run.obstacles.push_back({{9.7, 5.4}, 0.17});
    run.deadReckoningFinalError = 0.25;
    run.deadReckoningFinalTime = 1.7e9 + 41.8;
    run.write(dir);
    const auto back = formation::FormationRunFile::read(dir);
    ASSERT_EQ(back.moves.size(), 2u);
    EXPECT_EQ(back.moves[0].time, run.moves[0].time);
    EXPECT_EQ(back.moves[0].robot, "f2");
    EXPECT_EQ(back.moves[0].truth.x, 3.01);
    EXPECT_NEAR(back.moves[0].error(), std::hypot(0.01, 0.01), 1e-12);
    EXPECT_TRUE(std::isnan(back.moves[1].error()));
    EXPECT_EQ(back.route.size(), 2u);
    EXPECT_EQ(back.start[1].y, 1.3);
    ASSERT_EQ(back.obstacles.size(), 1u);
    EXPECT_EQ(back.obstacles[0].radius, 0.17);
    EXPECT_EQ(back.deadReckoningFinalError, 0.25);

    formation::FormationExperimentFile e;
    e.table.push_back({"many_turns", 5.8, 100, 153, 0.31, 3.2, 2523.4, 555.9});
    e.curves.push_back({"many_turns", "dr", 5.8, 5, 0.01});
    e.robots.push_back({4, 100, 0.3});
    e.steps.push_back({"camera", 0.003, 0.002, 0.0015, 0.001, 27});
    e.pixel.push_back({"patrol", 2.9, 20, 19, 1.12, 0.53, 1.97, 3.57, 0.05, 1344.9, 0.0324});
    e.write(dir);
    const auto eb = formation::FormationExperimentFile::read(dir);
    ASSERT_EQ(eb.table.size(), 1u);
    EXPECT_EQ(eb.table[0].moves, 153u);
    EXPECT_EQ(eb.table[0].deadReckoningTime, 555.9);
    EXPECT_EQ(eb.curves[0].kind, "dr");
    EXPECT_EQ(eb.robots[0].error, 0.3);
    EXPECT_EQ(eb.steps[0].count, 27u);
    ASSERT_EQ(eb.pixel.size(), 1u);
    EXPECT_EQ(eb.pixel[0].route, "patrol");
    EXPECT_EQ(eb.pixel[0].arrived, 19u);
    EXPECT_EQ(eb.pixel[0].formationMax, 1.97);
    EXPECT_EQ(eb.pixel[0].frames, 1344.9);
    EXPECT_EQ(eb.pixel[0].rotation, 0.0324);

    std::ofstream(formation::FormationRunFile::path(dir), std::ios::app) << "move 1 f1 2\n";
    try {
        formation::FormationRunFile::read(dir);
        FAIL() << "a short line was accepted";
    } catch (const Error& err) {
        EXPECT_NE(std::string(err.what()).find("formation.run.txt:"), std::string::npos)
            << err.what();
    }
}

TEST(FormationFiles, AnExperimentRouteThatIsAPathIsRefused) {
    // the route names a picture the report writes into the run folder (formation.fig14.<route>
    // .png): a crafted file's "../../x" must not reach it
    const std::string dir = testing::TempDir() + "/formation_route_path";
    std::filesystem::create_directories(dir);
    std::ofstream(formation::FormationExperimentFile::path(dir))
        << "curve ../../outside 5.8 dr 5 0.01\n";
    try {
        formation::FormationExperimentFile::read(dir);
        FAIL() << "a route named ../../outside was taken";
    } catch (const Error& err) {
        EXPECT_NE(std::string(err.what()).find("formation.experiment.txt:1"), std::string::npos)
            << err.what();
        EXPECT_NE(std::string(err.what()).find("../../outside"), std::string::npos) << err.what();
    }
}
