#include <mrloc/framesync/WallBus.h>

namespace mrloc::framesync {

void InProcessBus::subscribe(const std::string& robot, Handler handler) {
    subscribers_.emplace_back(robot, std::move(handler));
}

void InProcessBus::publish(const WallMessage& message) {
    queue_.push_back(message);
    if (delivering_) return;
    delivering_ = true;
    try {
        while (!queue_.empty()) {
            const WallMessage m = queue_.front();
            queue_.pop_front();
            for (auto& [robot, handler] : subscribers_) handler(m);
            ++delivered_;
        }
    } catch (...) {
        delivering_ = false;
        queue_.clear();
        throw;
    }
    delivering_ = false;
}

}  // namespace mrloc::framesync
