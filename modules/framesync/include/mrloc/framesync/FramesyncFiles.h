#pragma once
// The files between the framesync localizer / experiment and its report section, each a
// struct with write() and read() side by side:
//   framesync.run.txt         the walls every robot announced, the redefinitions, and the
//                             end figures (seed 004 sec. 5.2's measure) of the run;
//   framesync.experiment.txt  the same end figures over many seeds, sonar noises and
//                             odometry drifts.
#include <mrloc/common/Localizer.h>
#include <mrloc/framesync/Team.h>

#include <string>
#include <vector>

namespace mrloc::framesync {

/** Two robots at the end of a run: where robot b is as robot a sees it (b's position in
 *  a's body frame), estimated against true, with the shared frame and with odometry alone.
 *  A shared frame rotated as a whole (the reference robot's own drift) does not count;
 *  when both stand at the same goal (seed 004's experiment) the error is the distance
 *  between their estimates of the goal point. */
struct PairFigure {
    std::string a, b;
    double time = 0;           ///< s: the later of the two robots' last estimates
    double trueDistance = 0;   ///< m
    double sharedError = 0;    ///< m: |(e_b (-) e_a) - (t_b (-) t_a)|, shared frame
    double odometryError = 0;  ///< m: the same with odometry alone (no sharing)
};

/** Every pair of robots with estimates and truth, at each robot's last estimate. */
std::vector<PairFigure> endFigures(const common::Trajectories& shared,
                                   const common::Trajectories& odometry,
                                   const common::Trajectories& truth);

/** Means over pairs: {shared, odometry}; NaN without a pair. */
std::pair<double, double> meanPairErrors(const std::vector<PairFigure>& pairs);

struct FramesyncRunFile {
    std::vector<AnnouncedWall> walls;
    std::vector<RedefinitionEvent> events;
    std::vector<PairFigure> pairs;

    static std::string path(const std::string& dir) { return dir + "/framesync.run.txt"; }
    void write(const std::string& dir) const;
    static FramesyncRunFile read(const std::string& dir);
};

/** One simulated run of the experiment. */
struct ExperimentRun {
    std::string kind;  ///< "paper" (the INI as given), "noise", "drift"
    double value = 0;  ///< the sonar noise (m) or the drift factor; the INI's for paper
    unsigned long seed = 0;
    double sharedError = 0, odometryError = 0;  ///< m, mean over pairs (meanPairErrors)
    size_t walls = 0, redefinitions = 0;
};

struct FramesyncExperimentFile {
    std::vector<ExperimentRun> runs;

    static std::string path(const std::string& dir) { return dir + "/framesync.experiment.txt"; }
    void write(const std::string& dir) const;
    static FramesyncExperimentFile read(const std::string& dir);
};

}  // namespace mrloc::framesync
