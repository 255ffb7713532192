#pragma once
// The formation's on-board logic, which every robot of the team runs on the same messages
// (and the localizer runs again on the rawlog): the believed positions, the obstacles the
// robots found and shared, and the next move (seed 003 sec. 3). It advances on two kinds of
// observation only, so that the simulator's on-board part and `mrloc localize` reach the
// same moves from the same rawlog:
//   <robot>.obstacles   a CObservation2DRangeScan of the robot's obstacle sensor, placed
//                       where the robot believes it stands;
//   a CObservationComment "formation: <robot> arrived" (arrivalText): the moving robot
//                       reached its vertex (MRPT does not store a comment's label).
// The first move is planned once every robot has sent its first scan; each next move when
// the moving robot reports its arrival (after its scan from the new vertex).
#include <mrloc/formation/Formation.h>
#include <mrpt/obs/CObservation.h>
#include <mrpt/obs/CObservation2DRangeScan.h>

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace mrloc::formation {

struct TeamOptions {
    FormationOptions formation;
    std::vector<std::string> names;  ///< robot i's name
    std::vector<TPoint2D> start;     ///< robot i's position (world frame)
    std::vector<TPoint2D> route;     ///< waypoints (world frame), the last the destination
    size_t maxMoves = 10000;
    double obstacleCell = 0.1;  ///< m: one shared obstacle per cell of this size
};

/** A finished move, as the team believes it. */
struct MoveEvent {
    double time = 0;  ///< s since 1970, of the arrival message
    Move move;
};

/** The arrival message's text. */
std::string arrivalText(const std::string& robot);
/** An arrival message's text -> "<robot>.arrived" (the label MRPT drops); anything else "". */
std::string arrivedLabel(const std::string& text);
/** The text of the message a moving robot sends when its cameras lost the beacons and it
 *  finished the move by the belief (pixel mode), and its test. */
std::string lostBeaconsText(const std::string& robot);
bool isLostBeaconsText(const std::string& text);

class Team {
 public:
    enum class State { Waiting, Moving, Arrived, Stuck };

    /** Throws mrloc::Error if names and starts differ in number or there are fewer than 4. */
    explicit Team(TeamOptions options);
    /** Feeds one observation; returns true if it planned a new move. Throws mrloc::Error if an
     *  arrival does not come from the moving robot (a rawlog of another [formation]). */
    bool observe(const mrpt::obs::CObservation::Ptr& obs);

    State state() const { return state_; }
    /** The move under way (state Moving). */
    const std::optional<Move>& current() const { return current_; }
    const std::vector<TPoint2D>& believed() const { return believed_; }
    double believedHeading(size_t robot) const { return heading_.at(robot); }
    const std::vector<MoveEvent>& moves() const { return moves_; }
    /** Every shared detection, one per cell, in the order first seen. */
    const std::vector<Obstacle>& obstacles() const { return obstacles_; }
    /** Index of a robot's name, if it is one of the team's. */
    std::optional<size_t> indexOf(const std::string& name) const;
    const TeamOptions& options() const { return options_; }

 private:
    void addScan(size_t robot, const mrpt::obs::CObservation2DRangeScan& scan);
    void plan();

    TeamOptions options_;
    State state_ = State::Waiting;
    std::vector<TPoint2D> believed_;
    std::vector<double> heading_;  ///< rad: away from the anchor of each robot's last move
    std::vector<bool> scanned_;
    std::optional<Move> current_;
    std::vector<MoveEvent> moves_;
    RoutePlanner planner_;
    std::map<std::pair<long, long>, size_t> cells_;  ///< cell -> index in obstacles_
    std::vector<Obstacle> obstacles_;
};

}  // namespace mrloc::formation
