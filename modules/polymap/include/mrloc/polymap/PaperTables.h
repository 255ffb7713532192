#pragma once
// Seed 002's published results (Dao and Ivanovskiy 2013, Tables 1 and 2): the steps map of
// n = 148 vertices (6 steps) and k = 12 hypotheses, numbered step by step from left to right.
// Columns: algorithm 1 (visibility cells), 2 at X = 100, 2 at X = 500, 3 (LUT), 4 (LUW).
// Path lengths are in the paper's (unstated) map units; times in seconds (Visual C++ 2010).
namespace mrloc::polymap::paper {

constexpr int kStarts = 12, kColumns = 5;
constexpr const char* kColumnNames[kColumns] = {"cells", "randomized:100", "randomized:500",
                                                "triangulation", "windows"};

/** Table 1: d, length of the way passed by the robot at localization. */
constexpr double kTravel[kStarts][kColumns] = {
    {52.8, 52.2, 51.3, 58.2, 52.4},      {118.0, 114.4, 113.8, 111.1, 109.9},
    {269.6, 268.3, 266.8, 274.1, 264.0}, {547.3, 539.4, 546.8, 541.0, 530.3},
    {910.7, 916.9, 904.5, 916.8, 897.6}, {920.8, 977.2, 911.3, 915.4, 899.9},
    {911.6, 930.6, 905.5, 916.8, 897.2}, {917.9, 934.7, 910.8, 916.3, 900.9},
    {536.1, 558.6, 531.3, 543.1, 526.7}, {277.3, 283.5, 274.0, 274.4, 266.7},
    {105.9, 105.4, 106.8, 113.4, 106.2}, {61.9, 64.6, 61.1, 57.6, 56.9}};

/** Table 2: t, the algorithm's operating time (s). */
constexpr double kSeconds[kStarts][kColumns] = {
    {201.5, 27.0, 36.8, 23.9, 4.5},  {249.5, 38.6, 68.7, 41.8, 6.8},
    {297.6, 46.6, 108.9, 61.8, 7.3}, {347.5, 58.0, 144.4, 82.9, 9.0},
    {384.5, 66.3, 172.8, 99.7, 9.4}, {403.0, 66.5, 173.1, 100.5, 10.1},
    {453.4, 67.0, 175.0, 98.4, 8.8}, {461.9, 66.4, 174.8, 100.5, 9.5},
    {683.3, 57.4, 144.4, 82.1, 8.0}, {486.2, 47.4, 102.8, 63.8, 7.6},
    {473.7, 38.7, 66.0, 44.8, 5.8},  {399.8, 27.1, 36.5, 26.5, 4.8}};

}  // namespace mrloc::polymap::paper
