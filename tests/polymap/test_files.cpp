// The file between the polymap localizer and its report section round-trips.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/polymap/EliminationExperiment.h>
#include <mrloc/polymap/PolymapFiles.h>

#include <filesystem>
#include <fstream>

using namespace mrloc;

TEST(PolymapFiles, HypothesesFileRoundTripsAndNamesABadLine) {
    const std::string dir = testing::TempDir() + "/polymap_files";
    std::filesystem::create_directories(dir);
    polymap::HypothesesFile f;
    f.time = 1700000000.25;
    f.sensed = {{1.5, -2.25}, {0.1, 1e-7}, {-3, 4}};
    for (int i = 0; i < 3; ++i) {
        polymap::Hypothesis h;
        h.point = {1.0 / 3 + i, 2.0 / 7 - i};
        h.translation = {0.5 * i, -0.25 * i};
        h.mismatch = 1e-3 * i;
        f.hypotheses.push_back(h);
    }
    f.write(dir, "r1");
    const auto g = polymap::HypothesesFile::read(dir, "r1");
    EXPECT_EQ(g.time, f.time);  // 17 digits: the same double
    ASSERT_EQ(g.sensed.size(), 3u);
    ASSERT_EQ(g.hypotheses.size(), 3u);
    for (size_t i = 0; i < 3; ++i) {
        EXPECT_NEAR(g.sensed[i].x, f.sensed[i].x, 1e-9);
        EXPECT_NEAR(g.sensed[i].y, f.sensed[i].y, 1e-9);
        EXPECT_NEAR(g.hypotheses[i].point.x, f.hypotheses[i].point.x, 1e-9);
        EXPECT_NEAR(g.hypotheses[i].point.y, f.hypotheses[i].point.y, 1e-9);
        EXPECT_NEAR(g.hypotheses[i].translation.y, f.hypotheses[i].translation.y, 1e-9);
        EXPECT_NEAR(g.hypotheses[i].mismatch, f.hypotheses[i].mismatch, 1e-12);
    }
    std::ofstream(polymap::HypothesesFile::path(dir, "r2")) << "t 1\nH 1 2 3\n";
    try {
        polymap::HypothesesFile::read(dir, "r2");
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("hypotheses.r2.txt:2: expected 6 fields"),
                  std::string::npos)
            << e.what();
    }
}

// Tables 1-2 count the probes an algorithm took beyond its own candidates (issue 55): the
// count per start round-trips, a file written before it (6 fields) reads as none, and the
// report's table says which start fell back and how many probes each algorithm took so.
TEST(PolymapFiles, EliminationFileKeepsEachStartsFallBacksAndTheTableShowsThem) {
    const std::string dir = testing::TempDir() + "/polymap_elimination_file";
    std::filesystem::create_directories(dir);
    polymap::EliminationFile f;
    f.columns.push_back({"cells", {2.5, 3.0}, {1, 2}, {1, 1}, {0, 0}, {}, {}, {}, {}});
    f.columns.push_back({"windows", {4.0, 5.5}, {1, 2}, {1, 1}, {1, 2}, {}, {}, {}, {}});
    f.write(dir);
    const auto g = polymap::EliminationFile::read(dir);
    ASSERT_EQ(g.columns.size(), 2u);
    EXPECT_EQ(g.columns[0].fallbacks, (std::vector<int>{0, 0}));
    EXPECT_EQ(g.columns[1].fallbacks, (std::vector<int>{1, 2}));
    polymap::EliminationTimes times;
    times.seconds = {{0.001, 0.002}, {0.003, 0.004}};
    times.write(dir);
    const std::string html = polymap::eliminationSection(dir, g).markup();
    EXPECT_NE(html.find("5.50 (2 fell back)"), std::string::npos) << html;
    EXPECT_NE(html.find("probes beyond the algorithm's own candidates</td><td>0</td><td>3"),
              std::string::npos)
        << html;
    // before issue 55: "R column start travel probes survivors"
    std::ofstream(polymap::EliminationFile::path(dir)) << "C 0 cells\nR 0 0 2.5 1 1\n";
    EXPECT_EQ(polymap::EliminationFile::read(dir).columns[0].fallbacks, std::vector<int>{0});
}

// Where the ranking by path is not the paper's, the table says at which probe each algorithm's
// elimination from the run's start first parts from algorithm 1's: the first probe after
// which another number of hypotheses is left (the probes' positions, a few centimetres apart,
// are not a parting), with both probes and what each left. The counts survive the file.
TEST(PolymapFiles, TheTableSaysWhereEachAlgorithmPartsFromTheFirst) {
    const std::string dir = testing::TempDir() + "/polymap_first_branching";
    std::filesystem::create_directories(dir);
    polymap::EliminationFile f;
    f.trueStart = 3;
    const std::vector<double> shorter(12, 5.0), longer(12, 9.0);
    const std::vector<int> ones(12, 1), zeros(12, 0), probes(12, 3);
    f.columns.push_back({"cells", shorter, probes, ones, zeros, {}, {}, {}, {}});
    f.columns.push_back({"windows", longer, probes, ones, zeros, {}, {}, {}, {}});
    f.columns[0].stops = {{1, 1}, {2, 2}, {3, 3}};
    f.columns[0].stopsLeft = {7, 4, 1};
    f.columns[1].stops = {{1.02, 1}, {2, 2.5}, {8, 8}};  // parts at the second probe
    f.columns[1].stopsLeft = {7, 5, 1};
    f.write(dir);
    const auto g = polymap::EliminationFile::read(dir);
    EXPECT_EQ(g.columns[1].stopsLeft, (std::vector<int>{7, 5, 1}));
    polymap::EliminationTimes times;
    times.seconds = {std::vector<double>(12, 0.001), std::vector<double>(12, 0.002)};
    times.write(dir);
    const std::string html = polymap::eliminationSection(dir, g).markup();
    EXPECT_NE(html.find("From the run's start (start 4) the algorithms first part from cells as "
                        "follows: windows at probe 2: (2.00, 2.50) m, leaving 5 hypotheses, "
                        "where cells took (2.00, 2.00) m, leaving 4 hypotheses."),
              std::string::npos)
        << html;
    // a file from before the counts: the probes without them
    std::ofstream(polymap::EliminationFile::path(dir)) << "C 0 cells\nQ 0 1 2\n";
    EXPECT_EQ(polymap::EliminationFile::read(dir).columns[0].stopsLeft, std::vector<int>{-1});
}
