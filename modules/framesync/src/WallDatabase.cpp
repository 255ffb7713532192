#include <mrloc/framesync/WallDatabase.h>

#include <algorithm>

namespace mrloc::framesync {

bool WallDatabase::add(const WallMessage& m) {
    auto [it, fresh] = versions_.emplace(m.sender, m.frameVersion);
    if (!fresh) {
        if (m.frameVersion < it->second) return false;
        if (m.frameVersion > it->second) {
            // the sender's older frame is gone: so are the walls measured in it
            const auto before = walls_.size();
            walls_.erase(std::remove_if(walls_.begin(), walls_.end(),
                                        [&](const WallMessage& w) {
                                            return w.sender == m.sender &&
                                                   w.frameVersion < m.frameVersion;
                                        }),
                         walls_.end());
            purged_ += before - walls_.size();
            it->second = m.frameVersion;
        }
    }
    walls_.push_back(m);
    return true;
}

size_t WallDatabase::purge(double now) {
    const auto before = walls_.size();
    walls_.erase(std::remove_if(walls_.begin(), walls_.end(),
                                [&](const WallMessage& w) { return now - w.time > maxAge_; }),
                 walls_.end());
    purged_ += before - walls_.size();
    return before - walls_.size();
}

void WallDatabase::reframe(const std::string& owner, const mrpt::poses::CPose2D& f,
                           uint32_t version) {
    for (auto& w : walls_)
        if (w.sender == owner) {
            w.wall = w.wall.transformed(f);
            w.frameVersion = version;
        }
    versions_[owner] = version;
}

}  // namespace mrloc::framesync
