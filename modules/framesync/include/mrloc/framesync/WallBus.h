#pragma once
// Wall messages between robots (seed 004 sec. 4.2): every robot that finds a flat wall
// tells every robot, itself included. WallBus is the transport; InProcessBus delivers in
// the same process (the simulator, mrloc localize); a network transport (UDP, ROS, ...)
// implements the same two calls.
#include <mrloc/framesync/Wall.h>

#include <cstdint>
#include <deque>
#include <functional>
#include <string>
#include <vector>

namespace mrloc::framesync {

struct WallMessage {
    std::string sender;
    uint64_t id = 0;            ///< the sender's count of walls, from 1
    double time = 0;            ///< s, when the sender found the wall
    uint32_t frameVersion = 0;  ///< the sender's frame: 0 at the start, +1 per redefinition
    Wall wall;                  ///< in the sender's frame of that version
};

class WallBus {
 public:
    using Handler = std::function<void(const WallMessage&)>;
    virtual ~WallBus() = default;
    /** Sends to every subscriber, the sender included. */
    virtual void publish(const WallMessage& message) = 0;
    virtual void subscribe(const std::string& robot, Handler handler) = 0;
};

/** Delivers in publication order to every subscriber, in subscription order. A message
 *  published while one is being delivered (a handler that publishes) waits for it: no
 *  handler is re-entered. */
class InProcessBus : public WallBus {
 public:
    void publish(const WallMessage& message) override;
    void subscribe(const std::string& robot, Handler handler) override;
    size_t delivered() const { return delivered_; }

 private:
    std::vector<std::pair<std::string, Handler>> subscribers_;
    std::deque<WallMessage> queue_;
    bool delivering_ = false;
    size_t delivered_ = 0;
};

}  // namespace mrloc::framesync
