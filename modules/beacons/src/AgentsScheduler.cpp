// The beacon study's agents: several receivers served by one room's beacons, on one shared
// channel or by firing different beacons at different agents at once (paper 001's central
// mechanism), agents standing still.
#include <mrloc/beacons/BeaconStudy.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/Seeds.h>
#include <mrpt/core/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "TrialRunner.h"

namespace mrloc::beacons {

using common::streamSeed;
using mrpt::math::TPoint3D;

const char* channelName(Channel c) {
    switch (c) {
        case Channel::Shared:
            return "shared";
        case Channel::Simultaneous:
            return "simultaneous";
        case Channel::Unchecked:
            return "simultaneous, zones unchecked";
    }
    return "";
}

namespace {

/** GDOP of a 2-D fix from these beacons at `rx` (the height known); infinite if singular. */
double planarGdop(const BeaconMap& beacons, const std::vector<int>& ids, const TPoint3D& rx) {
    Eigen::Matrix2d hth = Eigen::Matrix2d::Zero();
    for (const int id : ids) {
        const TPoint3D d = rx - TPoint3D(beacons.at(id));
        const double n = d.norm();
        if (!(n > 0)) continue;
        const Eigen::Vector2d u(d.x / n, d.y / n);
        hth += u * u.transpose();
    }
    if (std::abs(hth.determinant()) < 1e-12) return std::numeric_limits<double>::infinity();
    return std::sqrt(hth.inverse().trace());
}

/** Agents at random places, at least 1 m apart (a robot's footprint and some room). */
std::vector<TPoint3D> placeAgents(const StudyRoom& room, const StudyHardware& hw, int agents,
                                  mrpt::random::CRandomGenerator& rng) {
    std::vector<TPoint3D> at;
    for (int tries = 0; int(at.size()) < agents; ++tries) {
        if (tries > 100000)
            throw Error(
                mrpt::format("beacon study: %d agents do not fit 1 m apart in %.1f x %.1f m",
                             agents, room.sizeX, room.sizeY));
        const TPoint3D p{rng.drawUniform(0.5, room.sizeX - 0.5),
                         rng.drawUniform(0.5, room.sizeY - 0.5), hw.receiverHeight};
        if (std::all_of(at.begin(), at.end(),
                        [&](const TPoint3D& q) { return (p - q).norm() >= 1.0; }))
            at.push_back(p);
    }
    return at;
}

/** One epoch's schedule: the agents served, each with the beacons that fire for it. */
struct Epoch {
    std::vector<size_t> who;
    std::vector<std::vector<int>> beaconsOf;
};

/** The agents of one layout and what the scheduler knows of them. */
class AgentsScheduler {
 public:
    AgentsScheduler(TrialRunner& runner, const StudyRoom& room, const StudyHardware& hw,
                    Channel channel, std::vector<TPoint3D> at)
        : runner_(runner),
          room_(room),
          channel_(channel),
          at_(std::move(at)),
          perFix_(size_t(std::max(1, hw.beaconsPerFix))),
          quiet_(runner.link().detectionThresholdDb() - 3 * hw.ultrasonic.fadingSigmaDb),
          lastServed_(at_.size(), -1) {
        // the GDOP of each agent's own loudest set: agents stand still, so once per layout
        for (const auto& p : at_)
            ownGdop_.push_back(planarGdop(room.beacons, runner.loudest(p, perFix_), p));
    }

    const TPoint3D& at(size_t agent) const { return at_[agent]; }
    void served(size_t agent, double t) { lastServed_[agent] = t; }

    /** The longest waiting first (ties by index), each given the loudest beacons not yet
     *  taken; Shared serves one agent, Simultaneous only agents that no other served
     *  agent's burst is predicted audible to, Unchecked any. */
    Epoch schedule() const {
        std::vector<size_t> order(at_.size());
        std::iota(order.begin(), order.end(), 0);
        std::stable_sort(order.begin(), order.end(),
                         [&](size_t a, size_t b) { return lastServed_[a] < lastServed_[b]; });
        Epoch e;
        std::vector<int> taken;
        for (const size_t a : order) {
            if (!e.who.empty() && channel_ == Channel::Shared) break;
            auto mine = runner_.loudest(at_[a], perFix_, taken);
            // the leftovers of other agents may be in a line: not taken if the fix would
            // be much weaker than from the agent's own loudest set
            if (!taken.empty() && planarGdop(room_.beacons, mine, at_[a]) > 1.5 * ownGdop_[a])
                continue;
            mine.erase(std::remove_if(mine.begin(), mine.end(),
                                      [&](int id) {
                                          return runner_.predictedMargin(
                                                     id, runner_.aimOf(id, at_[a]), at_[a]) <
                                                 runner_.link().detectionThresholdDb();
                                      }),
                       mine.end());
            if (mine.size() < kFewestRanges) continue;
            if (channel_ == Channel::Simultaneous && !clearOfOthers(e, a, mine)) continue;
            e.who.push_back(a);
            e.beaconsOf.push_back(mine);
            taken.insert(taken.end(), mine.begin(), mine.end());
        }
        return e;
    }

 private:
    static constexpr size_t kFewestRanges = 3;  // BeaconTracker's fixes take no fewer

    /** No burst of one served agent predicted audible at another's receiver. */
    bool clearOfOthers(const Epoch& e, size_t a, const std::vector<int>& mine) const {
        bool clear = true;
        for (size_t k = 0; k < e.who.size() && clear; ++k) {
            const size_t b = e.who[k];
            for (const int j : e.beaconsOf[k])
                clear =
                    clear && runner_.predictedMargin(j, runner_.aimOf(j, at_[b]), at_[a]) < quiet_;
            for (const int i : mine)
                clear =
                    clear && runner_.predictedMargin(i, runner_.aimOf(i, at_[a]), at_[b]) < quiet_;
        }
        return clear;
    }

    TrialRunner& runner_;
    const StudyRoom& room_;
    Channel channel_;
    std::vector<TPoint3D> at_;
    size_t perFix_;
    double quiet_;  ///< a level not heard (dB)
    std::vector<double> lastServed_, ownGdop_;
};

/** Fires one epoch's schedule, slot by slot (every served agent's beacon of a slot at once;
 *  a receiver's decoder triggers on the first burst it hears); counts shots and interfered
 *  readings in `out`. Returns each served agent's ranges and the slots it took. */
std::pair<std::vector<mrpt::obs::CObservationBeaconRanges>, size_t> fireEpoch(
    TrialRunner& runner, const AgentsScheduler& agents, const Epoch& e, const StudyHardware& hw,
    int shotsPerBeacon, mrpt::random::CRandomGenerator& rng, AgentsResult& out) {
    size_t slots = 0;
    for (const auto& b : e.beaconsOf) slots = std::max(slots, b.size() * size_t(shotsPerBeacon));
    std::vector<mrpt::obs::CObservationBeaconRanges> obs(e.who.size());
    for (size_t s = 0; s < slots; ++s) {
        std::vector<std::pair<size_t, int>> firing;  // (served index, beacon)
        for (size_t k = 0; k < e.who.size(); ++k)
            if (s < e.beaconsOf[k].size() * size_t(shotsPerBeacon))
                firing.emplace_back(k, e.beaconsOf[k][s % e.beaconsOf[k].size()]);
        for (const auto& [k, id] : firing) {
            const TPoint3D& rx = agents.at(e.who[k]);
            auto reading = runner.shoot(id, runner.aimOf(id, rx), rx, rng);
            ++out.shots;
            bool fromOther = false;
            for (const auto& [k2, id2] : firing) {
                if (k2 == k) continue;
                const auto other =
                    runner.shoot(id2, runner.aimOf(id2, agents.at(e.who[k2])), rx, rng);
                if (other.detected && (!reading.detected || other.range < reading.range)) {
                    reading.detected = true;
                    reading.range = other.range;
                    fromOther = true;
                }
            }
            out.interfered += fromOther;
            if (reading.detected)
                obs[k].sensedData.push_back(
                    TrialRunner::measurement(id, reading.range, hw.receiverHeight));
        }
    }
    return {std::move(obs), slots};
}

}  // namespace

AgentsResult serveAgents(const StudyRoom& room, const StudyHardware& hw, const StudyMethod& method,
                         int agents, Channel channel, double seconds, int layouts, uint64_t seed,
                         double errorBound) {
    AgentsResult out;
    out.agents = agents;
    out.channel = channel;
    out.seconds = seconds;
    out.layouts = layouts;
    TrialRunner runner(room, hw, method);
    double sumError = 0, sumRate = 0, minRate = std::numeric_limits<double>::infinity();
    size_t epochs = 0, served = 0;
    for (int layout = 0; layout < layouts; ++layout) {
        mrpt::random::CRandomGenerator rng(streamSeed(seed, uint64_t(layout)));
        AgentsScheduler scheduler(runner, room, hw, channel, placeAgents(room, hw, agents, rng));
        std::vector<size_t> fixes(size_t(agents), 0);
        for (double t = 0; t < seconds;) {
            const Epoch e = scheduler.schedule();
            if (e.who.empty()) break;  // nobody can be served: nothing changes later
            ++epochs;
            served += e.who.size();
            const auto [obs, slots] =
                fireEpoch(runner, scheduler, e, hw, method.shotsPerBeacon, rng, out);
            t += double(slots) * hw.shotInterval;
            for (size_t k = 0; k < e.who.size(); ++k) {
                scheduler.served(e.who[k], t);
                if (const auto f = runner.fix(obs[k])) {
                    const TPoint3D& truth = scheduler.at(e.who[k]);
                    const double err =
                        std::hypot(f->position.x() - truth.x, f->position.y() - truth.y);
                    ++fixes[e.who[k]];
                    ++out.fixes;
                    sumError += err;
                    out.maxError = std::max(out.maxError, err);
                    out.overBound += err > errorBound;
                }
            }
        }
        for (const size_t f : fixes) {
            const double rate = double(f) / seconds;
            sumRate += rate;
            minRate = std::min(minRate, rate);
        }
    }
    out.meanRate = agents && layouts ? sumRate / (double(agents) * layouts) : 0.0;
    out.minRate = std::isfinite(minRate) ? minRate : 0.0;
    out.meanError = out.fixes ? sumError / double(out.fixes) : 0.0;
    out.meanAgentsPerEpoch = epochs ? double(served) / double(epochs) : 0.0;
    return out;
}

}  // namespace mrloc::beacons
