#include <mrloc/beacons/BeaconStudy.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/ParallelFor.h>
#include <mrloc/common/Seeds.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <numeric>

namespace mrloc::beacons {

using mrpt::math::TPoint2D;
using mrpt::math::TPoint3D;

std::string StudyMethod::describe() const {
    std::string out = threeD ? "3-D" : "2-D (height known)";
    out += residual == Residual::Range ? ", range residual" : ", squared residual";
    if (delayCompensation) out += ", delay compensation";
    if (jitterWeights) out += ", jitter weights";
    out += mrpt::format(", %d shot%s per beacon", shotsPerBeacon, shotsPerBeacon > 1 ? "s" : "");
    return out;
}

namespace {

/** A generator seed per point or layout, whatever the thread. */
using common::streamSeed;

Eigen::Vector3d vec(const TPoint3D& p) { return {p.x, p.y, p.z}; }

/** The beacons' shots and the receiver's fix for many trials in one room: the link, the
 *  heads and the fix's tracker are built once. */
class TrialRunner {
 public:
    TrialRunner(const StudyRoom& room, const StudyHardware& hw, const StudyMethod& method)
        : room_(room), hw_(hw), method_(method), link_(hw.ultrasonic) {
        for (const auto& [id, b] : room.beacons)
            heads_.emplace(id, PanTiltHead(b, hw.ultrasonic.head));
        TrackerOptions o = hw.tracker;
        o.estimateBias = false;  // a fix alone: no filter state
        o.startPose.reset();
        o.fix.residual = method.residual;
        o.fix.knownHeight = method.threeD ? std::nullopt : std::optional<double>(0.0);
        o.rangeDelay = nullptr;
        o.jitterWeights = method.jitterWeights;
        if (method.delayCompensation)
            o.rangeDelay = decoderDelayModel(
                hw.ultrasonic, room.active ? std::map<int, Eigen::Vector3d>{} : aimsOf(room));
        tracker_.emplace(room.beacons, o);
    }

    /** Where beacon `id`'s head points when the receiver reports `reported`. */
    TPoint3D aimOf(int id, const TPoint3D& reported) const {
        if (room_.active) return reported;
        if (const auto a = room_.fixedAim.find(id); a != room_.fixedAim.end())
            return {a->second.x(), a->second.y(), a->second.z()};
        const TPoint3D& b = room_.beacons.at(id);
        return {b.x, b.y, b.z - 1};  // straight down
    }

    /** The link's mean level of beacon `id`'s burst at `rx` with its head aimed at `aim`. */
    double predictedMargin(int id, const TPoint3D& aim, const TPoint3D& rx) const {
        const PanTiltHead& head = heads_.at(id);
        const auto angles = head.aimAt(aim);
        const TPoint3D b = room_.beacons.at(id);
        return link_.marginDb(std::sqrt((b - rx).sqrNorm()), head.offAxisAngle(angles, rx));
    }

    /** The `k` beacons the link predicts loudest at `reported` (not in `taken`), ascending id. */
    std::vector<int> loudest(const TPoint3D& reported, size_t k,
                             const std::vector<int>& taken = {}) const {
        std::vector<std::pair<double, int>> level;
        for (const auto& [id, b] : room_.beacons)
            if (std::find(taken.begin(), taken.end(), id) == taken.end())
                level.emplace_back(-predictedMargin(id, aimOf(id, reported), reported), id);
        k = std::min(k, level.size());
        std::partial_sort(level.begin(), level.begin() + long(k), level.end());
        std::vector<int> out;
        for (size_t i = 0; i < k; ++i) out.push_back(level[i].second);
        std::sort(out.begin(), out.end());
        return out;
    }

    ShotRecord shoot(int id, const TPoint3D& aim, const TPoint3D& rx,
                     mrpt::random::CRandomGenerator& rng) const {
        const PanTiltHead& head = heads_.at(id);
        return simulateShot(
            link_, hw_.sensors, head, head.aimAt(aim), id, rx, [] { return true; },
            [] { return 0.0; }, rng);  // an empty room: every path in sight
    }

    std::optional<Fix> fix(const mrpt::obs::CObservationBeaconRanges& obs) {
        if (obs.sensedData.empty()) return std::nullopt;
        return tracker_->fixOnly(obs);
    }

    static mrpt::obs::CObservationBeaconRanges::TMeasurement measurement(int id, double range,
                                                                         double height) {
        mrpt::obs::CObservationBeaconRanges::TMeasurement m;
        m.beaconID = id;
        m.sensedDistance = float(range);
        m.sensorLocationOnRobot = mrpt::poses::CPoint3D(0, 0, height);
        return m;
    }

    TrialOutcome trial(const TPoint2D& at, mrpt::random::CRandomGenerator& rng) {
        const TPoint3D p0{at.x, at.y, hw_.receiverHeight};
        const double heading = rng.drawUniform(-M_PI, M_PI);
        const TPoint3D dir{std::cos(heading), std::sin(heading), 0};
        const auto fired = loudest(p0, size_t(std::max(1, hw_.beaconsPerFix)));
        mrpt::obs::CObservationBeaconRanges obs;
        size_t shot = 0;
        TPoint3D rx = p0;
        for (int round = 0; round < method_.shotsPerBeacon; ++round)
            for (const int id : fired) {
                rx = p0 + dir * (hw_.speed * hw_.shotInterval * double(shot++));
                const auto r = shoot(id, aimOf(id, p0), rx, rng);
                if (r.detected)
                    obs.sensedData.push_back(measurement(id, r.range, hw_.receiverHeight));
            }
        TrialOutcome out;
        if (const auto f = fix(obs)) {
            out.fixed = true;
            out.error = std::hypot(f->position.x() - rx.x, f->position.y() - rx.y);
        }
        return out;
    }

    const UltrasonicLink& link() const { return link_; }

 private:
    static std::map<int, Eigen::Vector3d> aimsOf(const StudyRoom& room) {
        std::map<int, Eigen::Vector3d> out = room.fixedAim;
        for (const auto& [id, b] : room.beacons)
            if (!out.count(id)) out[id] = vec(b) - Eigen::Vector3d(0, 0, 1);
        return out;
    }

    const StudyRoom& room_;
    const StudyHardware& hw_;
    StudyMethod method_;
    UltrasonicLink link_;
    std::map<int, PanTiltHead> heads_;
    std::optional<BeaconTracker> tracker_;
};

}  // namespace

TrialOutcome runTrial(const StudyRoom& room, const StudyHardware& hw, const StudyMethod& method,
                      const TPoint2D& at, mrpt::random::CRandomGenerator& rng) {
    TrialRunner runner(room, hw, method);
    return runner.trial(at, rng);
}

double CoverageResult::minReception() const {
    double m = points.empty() ? 0.0 : 1.0;
    for (const auto& p : points) m = std::min(m, p.reception());
    return m;
}

double CoverageResult::meanError() const {
    double sum = 0;
    int n = 0;
    for (const auto& p : points) sum += p.meanError * p.fixes, n += p.fixes;
    return n ? sum / n : 0.0;
}

double CoverageResult::maxError() const {
    double m = 0;
    for (const auto& p : points) m = std::max(m, p.maxError);
    return m;
}

size_t CoverageResult::pointsCovered(const CoverageCriteria& c) const {
    return size_t(std::count_if(points.begin(), points.end(), [&](const PointStats& p) {
        return p.trials > 0 && p.reception() >= c.reception - 1e-12 && p.maxError <= c.errorBound;
    }));
}

CoverageResult evaluateCoverage(const StudyRoom& room, const StudyHardware& hw,
                                const StudyMethod& method, const std::vector<TPoint2D>& points,
                                int trials, uint64_t seed, const CoverageCriteria& criteria,
                                bool stopAtFailure) {
    CoverageResult out;
    out.points.resize(points.size());
    std::atomic<bool> failed{false};
    // a point fails once its misses exceed what the reception rate allows, or one error
    // is over the bound: a search for the verdict stops there
    const int missesAllowed = int(std::floor((1.0 - criteria.reception) * trials + 1e-9));
    common::parallelFor(points.size(), [&](size_t i) {
        if (stopAtFailure && failed) return;
        // a runner per point: nothing a fix leaves behind reaches another point's
        TrialRunner runner(room, hw, method);
        PointStats& p = out.points[i];
        p.at = points[i];
        mrpt::random::CRandomGenerator rng(streamSeed(seed, i));
        double sum = 0;
        for (int k = 0; k < trials; ++k) {
            const auto t = runner.trial(points[i], rng);
            ++p.trials;
            if (t.fixed) {
                ++p.fixes;
                sum += t.error;
                p.maxError = std::max(p.maxError, t.error);
            }
            if (stopAtFailure &&
                (p.trials - p.fixes > missesAllowed || p.maxError > criteria.errorBound)) {
                failed = true;
                break;
            }
        }
        p.meanError = p.fixes ? sum / p.fixes : 0.0;
    });
    if (stopAtFailure && failed) out.complete = false;
    return out;
}

std::vector<TPoint2D> testGrid(double sizeX, double sizeY, double spacing, double wallMargin) {
    if (!(spacing > 0)) throw Error("beacon study: the test grid's spacing must be positive");
    const auto axis = [&](double size) {
        std::vector<double> v;
        const double span = size - 2 * wallMargin;
        if (span < 0) {
            v.push_back(size / 2);
            return v;
        }
        const int n = int(std::floor(span / spacing + 1e-9)) + 1;
        const double start = size / 2 - (n - 1) * spacing / 2;
        for (int i = 0; i < n; ++i) v.push_back(start + i * spacing);
        return v;
    };
    std::vector<TPoint2D> out;
    for (const double y : axis(sizeY))
        for (const double x : axis(sizeX)) out.push_back({x, y});
    return out;
}

BeaconMap spreadBeacons(double sizeX, double sizeY, double ceiling, int n) {
    if (n < 1) throw Error("beacon study: a layout needs at least one beacon");
    // the floor sampled on a grid fine enough that a cell's centroid moves by rounding only
    constexpr int kSamples = 64;
    std::vector<Eigen::Vector2d> samples;
    for (int j = 0; j < kSamples; ++j)
        for (int i = 0; i < kSamples; ++i)
            samples.emplace_back((i + 0.5) * sizeX / kSamples, (j + 0.5) * sizeY / kSamples);
    const auto halton = [](int i, int base) {
        double f = 1, r = 0;
        for (; i > 0; i /= base) f /= base, r += f * (i % base);
        return r;
    };
    std::vector<Eigen::Vector2d> c;
    for (int k = 0; k < n; ++k) c.emplace_back(halton(k + 1, 2) * sizeX, halton(k + 1, 3) * sizeY);
    std::vector<size_t> cell(samples.size());
    for (int iteration = 0; iteration < 300; ++iteration) {  // Lloyd's iteration
        for (size_t s = 0; s < samples.size(); ++s) {
            double best = std::numeric_limits<double>::infinity();
            for (size_t k = 0; k < c.size(); ++k)
                if (const double d = (samples[s] - c[k]).squaredNorm(); d < best)
                    best = d, cell[s] = k;
        }
        std::vector<Eigen::Vector2d> sum(c.size(), Eigen::Vector2d::Zero());
        std::vector<int> count(c.size(), 0);
        for (size_t s = 0; s < samples.size(); ++s) sum[cell[s]] += samples[s], ++count[cell[s]];
        double moved = 0;
        for (size_t k = 0; k < c.size(); ++k)
            if (count[k]) {
                const Eigen::Vector2d m = sum[k] / count[k];
                moved = std::max(moved, (m - c[k]).norm());
                c[k] = m;
            }
        if (moved < 1e-6) break;
    }
    BeaconMap out;
    for (int k = 0; k < n; ++k) out[k + 1] = TPoint3D(c[size_t(k)].x(), c[size_t(k)].y(), ceiling);
    return out;
}

std::map<int, Eigen::Vector3d> straightDown(const BeaconMap& beacons) {
    std::map<int, Eigen::Vector3d> out;
    for (const auto& [id, b] : beacons) out[id] = {b.x, b.y, 0};
    return out;
}

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

}  // namespace

StudyRoom spreadRoom(double sizeX, double sizeY, double ceiling, int n, bool active) {
    StudyRoom r;
    r.sizeX = sizeX;
    r.sizeY = sizeY;
    r.beacons = spreadBeacons(sizeX, sizeY, ceiling, n);
    r.active = active;
    r.fixedAim = straightDown(r.beacons);
    return r;
}

AgentsResult serveAgents(const StudyRoom& room, const StudyHardware& hw, const StudyMethod& method,
                         int agents, Channel channel, double seconds, int layouts, uint64_t seed,
                         double errorBound) {
    AgentsResult out;
    out.agents = agents;
    out.channel = channel;
    out.seconds = seconds;
    out.layouts = layouts;
    TrialRunner runner(room, hw, method);
    const double quiet =
        runner.link().detectionThresholdDb() - 3 * hw.ultrasonic.fadingSigmaDb;  // not heard
    const size_t perFix = size_t(std::max(1, hw.beaconsPerFix));
    constexpr size_t kFewestRanges = 3;  // BeaconTracker's fixes take no fewer
    double sumError = 0, sumRate = 0, minRate = std::numeric_limits<double>::infinity();
    size_t epochs = 0, served = 0;
    for (int layout = 0; layout < layouts; ++layout) {
        mrpt::random::CRandomGenerator rng(streamSeed(seed, uint64_t(layout)));
        // agents at random places, at least 1 m apart (a robot's footprint and some room)
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
        std::vector<size_t> fixes(size_t(agents), 0);
        std::vector<double> lastServed(size_t(agents), -1);
        // the GDOP of each agent's own loudest set: agents stand still, so once per layout
        std::vector<double> ownGdop;
        for (const auto& p : at)
            ownGdop.push_back(planarGdop(room.beacons, runner.loudest(p, perFix), p));
        for (double t = 0; t < seconds;) {
            // longest waiting first, ties by index
            std::vector<size_t> order(static_cast<size_t>(agents));
            std::iota(order.begin(), order.end(), 0);
            std::stable_sort(order.begin(), order.end(),
                             [&](size_t a, size_t b) { return lastServed[a] < lastServed[b]; });
            std::vector<size_t> who;
            std::vector<std::vector<int>> beaconsOf;
            std::vector<int> taken;
            for (const size_t a : order) {
                if (!who.empty() && channel == Channel::Shared) break;
                auto mine = runner.loudest(at[a], perFix, taken);
                // the leftovers of other agents may be in a line: not taken if the fix would
                // be much weaker than from the agent's own loudest set
                if (!taken.empty() && planarGdop(room.beacons, mine, at[a]) > 1.5 * ownGdop[a])
                    continue;
                mine.erase(std::remove_if(mine.begin(), mine.end(),
                                          [&](int id) {
                                              return runner.predictedMargin(
                                                         id, runner.aimOf(id, at[a]), at[a]) <
                                                     runner.link().detectionThresholdDb();
                                          }),
                           mine.end());
                if (mine.size() < kFewestRanges) continue;
                // no burst of one served agent predicted audible at another's receiver
                bool clear = true;
                for (size_t k = 0; k < who.size() && clear && channel == Channel::Simultaneous;
                     ++k) {
                    const size_t b = who[k];
                    for (const int j : beaconsOf[k])
                        clear = clear &&
                                runner.predictedMargin(j, runner.aimOf(j, at[b]), at[a]) < quiet;
                    for (const int i : mine)
                        clear = clear &&
                                runner.predictedMargin(i, runner.aimOf(i, at[a]), at[b]) < quiet;
                }
                if (!clear) continue;
                who.push_back(a);
                beaconsOf.push_back(mine);
                taken.insert(taken.end(), mine.begin(), mine.end());
            }
            if (who.empty()) break;  // nobody can be served: nothing changes later
            ++epochs;
            served += who.size();
            size_t slots = 0;
            for (const auto& b : beaconsOf)
                slots = std::max(slots, b.size() * size_t(method.shotsPerBeacon));
            std::vector<mrpt::obs::CObservationBeaconRanges> obs(who.size());
            for (size_t s = 0; s < slots; ++s) {
                // every served agent's beacon of this slot fires at once
                std::vector<std::pair<size_t, int>> firing;  // (served index, beacon)
                for (size_t k = 0; k < who.size(); ++k)
                    if (s < beaconsOf[k].size() * size_t(method.shotsPerBeacon))
                        firing.emplace_back(k, beaconsOf[k][s % beaconsOf[k].size()]);
                for (const auto& [k, id] : firing) {
                    const TPoint3D& rx = at[who[k]];
                    auto reading = runner.shoot(id, runner.aimOf(id, rx), rx, rng);
                    ++out.shots;
                    bool fromOther = false;
                    for (const auto& [k2, id2] : firing) {
                        if (k2 == k) continue;
                        const auto other =
                            runner.shoot(id2, runner.aimOf(id2, at[who[k2]]), rx, rng);
                        // the decoder triggers on the first burst it hears
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
            t += double(slots) * hw.shotInterval;
            for (size_t k = 0; k < who.size(); ++k) {
                lastServed[who[k]] = t;
                if (const auto f = runner.fix(obs[k])) {
                    const double e =
                        std::hypot(f->position.x() - at[who[k]].x, f->position.y() - at[who[k]].y);
                    ++fixes[who[k]];
                    ++out.fixes;
                    sumError += e;
                    out.maxError = std::max(out.maxError, e);
                    out.overBound += e > errorBound;
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
