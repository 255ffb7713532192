#pragma once
// The manager of seed 004 sec. 5.1: it keeps a robot's wall database, searches a matching
// pair whenever a wall is announced (sec. 4.2: for its own wall among the others', for
// another's among its own), redefines the robot's frame (sec. 4.4) when the other robot has
// the higher priority of reference (sec. 4.5), and tells its listeners (the wall detector,
// the decision layer) that the frame changed.
#include <mrloc/framesync/Matching.h>
#include <mrloc/framesync/WallBus.h>
#include <mrloc/framesync/WallDatabase.h>

#include <map>
#include <set>
#include <string>
#include <vector>

namespace mrloc::framesync {

/** Priority of reference (seed 004 sec. 4.5): a unique rank per robot. Only a robot of
 *  lower priority redefines its frame to match one of higher priority, so references
 *  form a tree under the highest, which never moves: no reference loop. */
class PriorityOrder {
 public:
    /** Highest first; robots not listed rank after every listed one, by name. Throws
     *  mrloc::Error for a name listed twice. */
    explicit PriorityOrder(std::vector<std::string> highestFirst = {});
    /** True if a's priority is higher than b's (a != b). */
    bool higher(const std::string& a, const std::string& b) const;
    const std::vector<std::string>& listed() const { return order_; }

 private:
    std::vector<std::string> order_;
    std::map<std::string, size_t> rank_;
};

struct ManagerOptions {
    MatchOptions match;
    double maxAge = 30;  ///< s a wall stays in the database
};

struct RedefinitionEvent {
    std::string robot, reference;  ///< who redefined, on whose wall
    double time = 0;               ///< s
    uint32_t version = 0;          ///< the robot's new frame version
    Redefinition redefinition;
    uint64_t ownWall = 0, referenceWall = 0;  ///< the matched pair's ids
};

class FrameListener {
 public:
    virtual ~FrameListener() = default;
    virtual void onRedefinition(const RedefinitionEvent& event) = 0;
};

class FrameManager {
 public:
    /** Subscribes to the bus as `robot`. */
    FrameManager(std::string robot, const PriorityOrder& priority, ManagerOptions options,
                 WallBus& bus);
    FrameManager(const FrameManager&) = delete;
    FrameManager& operator=(const FrameManager&) = delete;

    /** The robot's pose now, in its current frame: matching measures distances from it. */
    void setPose(double t, const mrpt::poses::CPose2D& pose) { time_ = t, pose_ = pose; }
    /** The wall detector found a wall (in the current frame): announce it. */
    void announce(const Wall& wall);
    void addListener(FrameListener* listener) { listeners_.push_back(listener); }

    /** The current frame: pose in it = correction (+) pose in the robot's first frame. */
    const mrpt::poses::CPose2D& correction() const { return correction_; }
    uint32_t version() const { return version_; }
    const WallDatabase& database() const { return database_; }
    const std::string& robot() const { return robot_; }
    size_t announced() const { return announced_; }

 private:
    void receive(const WallMessage& message);
    /** Among candidate pairs (own, reference), the best match by the thresholds' share. */
    void redefine(const WallMessage& own, const WallMessage& reference, const Redefinition& r);
    /** Seed 004 sec. 3, when no pair passed the local tests: generalMatch against the
     *  sender's walls (`from`), or every higher robot's when the new wall is the robot's own. */
    void generalSearch(const WallMessage* from);

    std::string robot_;
    const PriorityOrder& priority_;
    ManagerOptions options_;
    WallBus& bus_;
    WallDatabase database_;
    std::vector<FrameListener*> listeners_;
    mrpt::poses::CPose2D correction_, pose_;
    double time_ = 0;
    uint32_t version_ = 0;
    uint64_t announced_ = 0;
    std::set<uint64_t> usedOwn_;  ///< own walls that already redefined the frame once
    /** Robots whose walls have redefined this frame: from then on what is left between the
     *  two frames is drift, the local tests' to correct. A second general search could tie
     *  the frame to a wall one corridor module further (a corridor is self-similar). */
    std::set<std::string> tiedTo_;
};

}  // namespace mrloc::framesync
