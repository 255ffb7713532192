#pragma once
// One robot's database of walls (seed 004 sec. 4.2): its own and every other robot's, as
// announced. Old walls are useless, since the shared frame keeps drifting with odometry:
// they are purged once older than a maximum age. A sender's walls are in its frame of one
// version; when a newer version of that sender is heard of, its older walls are purged
// (their frame no longer exists).
#include <mrloc/framesync/WallBus.h>

#include <map>
#include <string>
#include <vector>

namespace mrloc::framesync {

class WallDatabase {
 public:
    explicit WallDatabase(double maxAge) : maxAge_(maxAge) {}
    /** Stores the message; false (and nothing stored) if its frame version is older than
     *  one already heard of from its sender. */
    bool add(const WallMessage& message);
    /** Drops walls older than the maximum age at `now` (s); returns how many. */
    size_t purge(double now);
    /** The owner redefined its frame by `f` (new = f (+) old): its own walls move with it
     *  and take the new version. */
    void reframe(const std::string& owner, const mrpt::poses::CPose2D& f, uint32_t version);
    const std::vector<WallMessage>& walls() const { return walls_; }
    double maxAge() const { return maxAge_; }
    size_t purged() const { return purged_; }

 private:
    double maxAge_;
    std::vector<WallMessage> walls_;
    std::map<std::string, uint32_t> versions_;  ///< newest frame version per sender
    size_t purged_ = 0;
};

}  // namespace mrloc::framesync
