#pragma once
// The files the formation method writes into the run directory for its report section, each
// defined once, write and read side by side:
//   formation.run.txt          the run: the route, every move (believed and true vertex),
//                              the shared obstacles, the dead-reckoning robot's final error
//   formation.experiment.txt   the Monte Carlo experiment (seed 003 Table 1, figs. 11, 14, 15)
#include <mrloc/common/Localizer.h>
#include <mrloc/formation/Team.h>

#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace mrloc::formation {

struct FormationRunFile {
    struct MoveRow {
        double time = 0;  ///< s since 1970
        std::string robot;
        TPoint2D believed;
        TPoint2D truth{std::numeric_limits<double>::quiet_NaN(),
                       std::numeric_limits<double>::quiet_NaN()};  ///< NaN: no ground truth
        /** The step's own error (seed 003 fig. 11): the true end against the true anchor
         *  reflected across the true base (the vertex of a perfect triangle on them), along
         *  the true base (lateral) and across it (longitudinal); NaN without ground truth. */
        double lateral = std::numeric_limits<double>::quiet_NaN();
        double longitudinal = std::numeric_limits<double>::quiet_NaN();
        double error() const { return (truth - believed).norm(); }
    };
    std::vector<TPoint2D> route;  ///< world frame
    std::vector<TPoint2D> start;  ///< the strip, robot order
    std::vector<MoveRow> moves;
    std::vector<Obstacle> obstacles;
    /** The dead-reckoning robot's last estimate against its truth (m); NaN without. */
    double deadReckoningFinalError = std::numeric_limits<double>::quiet_NaN();
    double deadReckoningFinalTime = std::numeric_limits<double>::quiet_NaN();  ///< s since 1970

    static FormationRunFile fromRun(const Team& team, const common::Trajectories& estimates,
                                    const common::Trajectories& truth);
    static std::string path(const std::string& dir) { return dir + "/formation.run.txt"; }
    void write(const std::string& dir) const;
    /** Throws mrloc::Error naming the file and line on a malformed line. */
    static FormationRunFile read(const std::string& dir);
};

/** Mean and standard deviation of |x| over the samples (seed 003 fig. 11's measures). */
std::pair<double, double> absMoments(const std::vector<double>& xs);

struct FormationExperimentFile {
    /** Seed 003 Table 1: the mean error at the destination over the runs. */
    struct TableRow {
        std::string route;
        double wheelSpeed = 0;  ///< rad/s
        size_t runs = 0, moves = 0;
        double formation = 0, deadReckoning = 0;          ///< m
        double formationTime = 0, deadReckoningTime = 0;  ///< s to the destination
    };
    /** Seed 003 fig. 14: mean error against time; kind "dr" (a sample every few seconds) or
     *  "formation" (at each move's end). */
    struct CurvePoint {
        std::string route, kind;
        double wheelSpeed = 0, time = 0, error = 0;
    };
    /** Seed 003 fig. 15: mean error at the destination against the number of robots. */
    struct RobotsRow {
        size_t robots = 0, runs = 0;
        double error = 0;
    };
    /** Seed 003 fig. 11: per-step vertex errors, mean absolute and sd (m); source "paper",
     *  "model" (the error model's draws) or "camera" (Algorithm 1 from rendered frames). */
    struct StepRow {
        std::string source;
        double lateralMean = 0, lateralSd = 0, longitudinalMean = 0, longitudinalSd = 0;
        size_t count = 0;
    };
    /** Table 1 from pixels: pixel marches (PixelMarch) per route and speed, each beside a
     *  dead-reckoned drive of the same route. Errors at the destination in m (mean, sd,
     *  worst), arrived marches, lost moves and frames per march, and the formation's
     *  rotation at the end (mean |angle|, rad). */
    struct PixelRow {
        std::string route;
        double wheelSpeed = 0;
        size_t runs = 0, arrived = 0;
        double formation = 0, formationSd = 0, formationMax = 0, deadReckoning = 0;
        double lostMoves = 0, frames = 0, rotation = 0;
    };
    std::vector<TableRow> table;
    std::vector<PixelRow> pixel;
    std::vector<CurvePoint> curves;
    std::vector<RobotsRow> robots;
    std::vector<StepRow> steps;

    static std::string path(const std::string& dir) { return dir + "/formation.experiment.txt"; }
    void write(const std::string& dir) const;
    static FormationExperimentFile read(const std::string& dir);
};

}  // namespace mrloc::formation
