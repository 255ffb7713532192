#include <mrloc/common/Error.h>
#include <mrloc/framesync/FrameManager.h>

#include <cmath>
#include <map>
#include <optional>

namespace mrloc::framesync {

PriorityOrder::PriorityOrder(std::vector<std::string> highestFirst)
    : order_(std::move(highestFirst)) {
    for (size_t i = 0; i < order_.size(); ++i)
        if (!rank_.emplace(order_[i], i).second)
            throw Error("framesync: robot '" + order_[i] + "' is listed twice in the priority");
}

bool PriorityOrder::higher(const std::string& a, const std::string& b) const {
    const auto ia = rank_.find(a), ib = rank_.find(b);
    const size_t ra = ia == rank_.end() ? order_.size() : ia->second;
    const size_t rb = ib == rank_.end() ? order_.size() : ib->second;
    if (ra != rb) return ra < rb;
    return a < b;  // neither listed: by name
}

FrameManager::FrameManager(std::string robot, const PriorityOrder& priority, ManagerOptions options,
                           WallBus& bus)
    : robot_(std::move(robot)),
      priority_(priority),
      options_(options),
      bus_(bus),
      database_(options.maxAge) {
    bus_.subscribe(robot_, [this](const WallMessage& m) { receive(m); });
}

void FrameManager::announce(const Wall& wall) {
    WallMessage m;
    m.sender = robot_;
    m.id = ++announced_;
    m.time = time_;
    m.frameVersion = version_;
    m.wall = wall;
    bus_.publish(m);
}

namespace {

double score(const Redefinition& r, const MatchOptions& o) {
    return std::abs(r.rotation) / o.maxBearing + std::abs(r.shift) / o.maxDistance;
}

}  // namespace

void FrameManager::receive(const WallMessage& m) {
    database_.purge(time_);
    if (time_ - m.time > options_.maxAge) return;  // aged on the way
    if (!database_.add(m)) return;                 // from a frame its sender left
    const bool own = m.sender == robot_;
    if (!own && !priority_.higher(m.sender, robot_)) return;  // sec. 4.5: the sender moves
    // sec. 4.2: an own wall is matched among the others', another's among the own
    const TPoint2D here(pose_.x(), pose_.y());
    std::optional<Redefinition> best;
    const WallMessage *bestOwn = nullptr, *bestReference = nullptr;
    for (const auto& w : database_.walls()) {
        const WallMessage *mine, *reference;
        if (own) {
            if (w.sender == robot_ || !priority_.higher(w.sender, robot_)) continue;
            mine = &m, reference = &w;
        } else {
            if (w.sender != robot_) continue;
            mine = &w, reference = &m;
        }
        if (usedOwn_.count(mine->id)) continue;
        const auto r = matchWalls(mine->wall, reference->wall, here, options_.match);
        if (r && (!best || score(*r, options_.match) < score(*best, options_.match)))
            best = r, bestOwn = mine, bestReference = reference;
    }
    if (best) return redefine(*bestOwn, *bestReference, *best);
    if (options_.match.general) generalSearch(own ? nullptr : &m);
}

void FrameManager::generalSearch(const WallMessage* from) {
    // seed 004 sec. 3: the own walls against one reference robot's (the sender's, or, for an
    // own wall, each robot of higher priority in turn)
    std::vector<const WallMessage*> mine;
    std::map<std::string, std::vector<const WallMessage*>> theirs;
    for (const auto& w : database_.walls()) {
        if (w.sender == robot_) {
            if (!usedOwn_.count(w.id)) mine.push_back(&w);
        } else if (priority_.higher(w.sender, robot_) && (!from || w.sender == from->sender) &&
                   !tiedTo_.count(w.sender)) {
            theirs[w.sender].push_back(&w);
        }
    }
    if (mine.size() < options_.match.generalSupport) return;
    std::vector<const Wall*> own;
    for (const auto* w : mine) own.push_back(&w->wall);
    for (const auto& [sender, walls] : theirs) {
        std::vector<const Wall*> reference;
        for (const auto* w : walls) reference.push_back(&w->wall);
        size_t i = 0, k = 0;
        const auto r = generalMatch(own, reference, options_.match, &i, &k);
        // a transform the local tests would have passed is theirs to make
        if (!r || (std::abs(r->rotation) < options_.match.maxBearing &&
                   r->shift < options_.match.maxDistance))
            continue;
        return redefine(*mine[i], *walls[k], *r);
    }
}

void FrameManager::redefine(const WallMessage& own, const WallMessage& reference,
                            const Redefinition& r) {
    RedefinitionEvent e;
    e.robot = robot_;
    e.reference = reference.sender;
    e.time = time_;
    e.redefinition = r;
    e.ownWall = own.id;
    e.referenceWall = reference.id;
    usedOwn_.insert(own.id);
    tiedTo_.insert(reference.sender);
    correction_ = r.correction + correction_;  // seed 004 sec. 4.4
    pose_ = r.correction + pose_;
    e.version = ++version_;
    database_.reframe(robot_, r.correction, version_);
    for (auto* l : listeners_) l->onRedefinition(e);
}

}  // namespace mrloc::framesync
