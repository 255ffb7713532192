#include <mrloc/common/Error.h>
#include <mrloc/common/ParallelFor.h>
#include <mrloc/common/Rawlog.h>
#include <mrloc/polymap/ScanLocalizer.h>
#include <mrpt/core/format.h>
#include <mrpt/math/wrap2pi.h>

#include <algorithm>
#include <boost/math/distributions/binomial.hpp>
#include <cmath>
#include <unordered_map>

namespace mrloc::polymap {

namespace {

constexpr size_t kMaxBeams = 100000;
constexpr size_t kProfileBins = 720;  // the first scan's ranges cast every 0.5 degree
constexpr double kDeg = M_PI / 180;

TPoint2D sensorAt(const TPose2D& robot, const TPose2D& sensor) {
    const double c = std::cos(robot.phi), s = std::sin(robot.phi);
    return {robot.x + c * sensor.x - s * sensor.y, robot.y + s * sensor.x + c * sensor.y};
}

TPose2D robotOfSensorAt(const TPoint2D& sensorPos, double phi, const TPose2D& sensor) {
    const double c = std::cos(phi), s = std::sin(phi);
    return {sensorPos.x - (c * sensor.x - s * sensor.y),
            sensorPos.y - (s * sensor.x + c * sensor.y), phi};
}

bool near(const TPose2D& a, const TPose2D& b, double distance, double angle) {
    return std::hypot(a.x - b.x, a.y - b.y) <= distance &&
           std::abs(mrpt::math::wrapToPi(a.phi - b.phi)) <= angle;
}

/** Keeps the first of every group of poses within (distance, angle); `poses` best first. */
std::vector<PoseHypothesis> distinct(std::vector<PoseHypothesis> poses, double distance,
                                     double angle, size_t limit) {
    std::vector<PoseHypothesis> kept;
    std::unordered_map<int64_t, std::vector<size_t>> cells;  // kept poses by distance-sized cell
    const auto key = [](int64_t cx, int64_t cy) {            // unsigned: no shift of a negative
        return int64_t((uint64_t(cx) << 32) ^ uint64_t(uint32_t(cy)));
    };
    const auto cellOf = [distance](double v) { return int64_t(std::floor(v / distance)); };
    for (auto& p : poses) {
        bool dup = false;
        const int64_t cx = cellOf(p.pose.x), cy = cellOf(p.pose.y);
        for (int64_t dx = -1; dx <= 1 && !dup; ++dx)
            for (int64_t dy = -1; dy <= 1 && !dup; ++dy) {
                const auto it = cells.find(key(cx + dx, cy + dy));
                if (it == cells.end()) continue;
                for (const size_t k : it->second)
                    if (near(kept[k].pose, p.pose, distance, angle)) {
                        dup = true;
                        break;
                    }
            }
        if (dup) continue;
        cells[key(cx, cy)].push_back(kept.size());
        kept.push_back(std::move(p));
        if (kept.size() >= limit) break;
    }
    return kept;
}

size_t strideFor(const ScanBeamSet& beams, size_t wanted) {
    return std::max<size_t>(1, beams.returns / wanted);
}

}  // namespace

ScanBeamSet beamSetOf(const mrpt::obs::CObservation2DRangeScan& scan) {
    const size_t n = scan.getScanSize();
    const std::string what = "scan '" + scan.sensorLabel + "'";
    if (n < 8 || n > kMaxBeams)
        throw Error(what + mrpt::format(": %zu beams (mrloc takes 8 to %zu)", n, kMaxBeams));
    if (!(scan.aperture > 0) || scan.aperture > 2 * M_PI + 1e-6)
        throw Error(what + mrpt::format(": aperture %g rad is not in (0, 2 pi]", scan.aperture));
    if (!(scan.maxRange > 0) || !std::isfinite(scan.maxRange))
        throw Error(what + mrpt::format(": max range %g m", scan.maxRange));
    ScanBeamSet b;
    b.sensor = {scan.sensorPose.x(), scan.sensorPose.y(), scan.sensorPose.yaw()};
    b.maxRange = scan.maxRange;
    b.sigma = std::isfinite(scan.stdError) ? std::max(0.f, scan.stdError) : 0.0;
    b.time = mrpt::Clock::toDouble(scan.timestamp);
    b.angle.resize(n);
    b.range.resize(n);
    // MRPT's convention (CObservation2DRangeScan::getScanAngle), in double precision
    const double step = scan.aperture / double(n - 1);
    const bool leftward = common::storedFlag(scan.rightToLeft);
    for (size_t i = 0; i < n; ++i) {
        const double a = leftward ? -0.5 * scan.aperture + step * double(i)
                                  : 0.5 * scan.aperture - step * double(i);
        b.angle[i] = a + b.sensor.phi;
        const double r = scan.getScanRange(i);
        if (!std::isfinite(r)) throw Error(what + mrpt::format(": beam %zu range is %g", i, r));
        const bool returned = scan.getScanRangeValidity(i) && r > 0 && r < 0.999 * scan.maxRange;
        b.range[i] = returned ? r : NAN;
        b.returns += returned;
    }
    return b;
}

bool throughBeamsAreRandom(size_t through, size_t returns) {
    if (through == 0 || returns == 0) return true;
    const boost::math::binomial_distribution<double> random(double(returns), BeamModel::random);
    // P(X >= through) = 1 - P(X <= through - 1)
    return boost::math::cdf(boost::math::complement(random, double(through - 1))) >=
           BeamModel::throughTail;
}

namespace {

template <bool kLikelihood>
BeamAgreement scored(const WallMap& map, const ScanBeamSet& beams, const TPose2D& robot,
                     double tolerance, size_t stride) {
    BeamAgreement a;
    const TPoint2D origin = sensorAt(robot, beams.sensor);
    const double tol2 = tolerance * tolerance;
    const double sigma = 0.5 * tolerance, hitPeak = BeamModel::hit / (sigma * std::sqrt(2 * M_PI));
    for (size_t i = 0; i < beams.range.size(); i += stride) {
        const double r = beams.range[i];
        if (std::isnan(r)) continue;
        ++a.returns;
        // cast to the scan's reach: a shorter beam is clutter only if the map has a wall
        // farther along
        const double predicted =
            map.caster.cast(origin, robot.phi + beams.angle[i], beams.maxRange);
        const double e = r - predicted;
        if (std::abs(e) <= tolerance)
            ++a.agree;
        else if (e < 0)
            a.clutter += predicted < beams.maxRange;
        else
            ++a.through;
        a.cost += std::min(e * e, tol2);
        if constexpr (kLikelihood) {
            const double p = hitPeak * std::exp(-0.5 * e * e / (sigma * sigma)) +
                             (e < 0 ? BeamModel::shortReading / std::max(predicted, 0.01) : 0) +
                             BeamModel::random / beams.maxRange;
            a.logRatio += std::log(p * beams.maxRange);
        }
    }
    return a;
}

}  // namespace

BeamAgreement scoreScan(const WallMap& map, const ScanBeamSet& beams, const TPose2D& robot,
                        double tolerance, size_t stride) {
    return scored<true>(map, beams, robot, tolerance, stride);
}

BeamAgreement costOfScan(const WallMap& map, const ScanBeamSet& beams, const TPose2D& robot,
                         double tolerance, size_t stride) {
    return scored<false>(map, beams, robot, tolerance, stride);
}

PoseHypothesis refinePose(const WallMap& map, const ScanBeamSet& beams, const TPose2D& start,
                          double tolerance, double step, double angleStep, size_t stride) {
    TPose2D pose = start;
    double best = costOfScan(map, beams, pose, tolerance, stride).cost;
    for (double s = step, a = angleStep; s >= 0.01 || a >= 0.1 * kDeg; s *= 0.5, a *= 0.5) {
        for (int round = 0; round < 8; ++round) {
            bool moved = false;
            const TPose2D moves[6] = {{s, 0, 0},  {-s, 0, 0}, {0, s, 0},
                                      {0, -s, 0}, {0, 0, a},  {0, 0, -a}};
            for (const auto& m : moves) {
                const TPose2D p{pose.x + m.x, pose.y + m.y, mrpt::math::wrapToPi(pose.phi + m.phi)};
                const double c = costOfScan(map, beams, p, tolerance, stride).cost;
                if (c < best) best = c, pose = p, moved = true;
            }
            if (!moved) break;
        }
    }
    PoseHypothesis h;
    h.pose = pose;
    h.score = scoreScan(map, beams, pose, tolerance, 1);
    return h;
}

std::vector<PoseHypothesis> globalHypotheses(const WallMap& map, const ScanBeamSet& beams,
                                             const ScanLocalizerOptions& o, SearchStats* stats) {
    SearchStats st;
    if (beams.returns < 8)
        throw Error(mrpt::format("scan at t = %.3f: %zu beams returned, too few to localize",
                                 beams.time, beams.returns));
    const size_t stride = strideFor(beams, 90);
    std::vector<size_t> used;
    for (size_t i = 0; i < beams.range.size(); i += stride)
        if (!std::isnan(beams.range[i])) used.push_back(i);
    const double binWidth = 2 * M_PI / kProfileBins;
    const double hs = o.headingStep * kDeg;
    // a large building: the grid's step grows until at most maxPositions are searched (the
    // search's cost is the positions' range profiles; the beams' tolerance widens with it)
    double ps = o.positionStep;
    {
        const double freeArea =
            double(map.freeCells.count()) * map.freeCells.resolution * map.freeCells.resolution;
        double area = freeArea;
        if (o.region)
            area = std::min(area, (o.region->second.x - o.region->first.x) *
                                      (o.region->second.y - o.region->first.y));
        if (area / (ps * ps) > double(o.maxPositions))
            ps = std::sqrt(area / double(o.maxPositions));
    }
    st.positionStep = ps;
    std::vector<double> headings;
    if (o.heading) {
        for (int k = -4; k <= 4; ++k) headings.push_back(*o.heading + 0.5 * k * hs);
    } else {
        const int n = std::max(1, int(std::lround(360 / o.headingStep)));
        for (int k = 0; k < n; ++k) headings.push_back(2 * M_PI * k / n);
    }
    st.headings = headings.size();
    // per beam: its profile bin offset and its tolerance on this grid (a pose is off by up to
    // half a position step and half a heading step, and the profile by half a bin)
    std::vector<double> tol(used.size());
    for (size_t u = 0; u < used.size(); ++u)
        tol[u] = o.tolerance + beams.range[used[u]] * (0.5 * hs + 0.5 * binWidth) + 0.71 * ps;
    const double offset = std::hypot(beams.sensor.x, beams.sensor.y);
    TPoint2D lo = map.min, hi = map.max;
    if (o.region) {
        lo = {std::max(lo.x, o.region->first.x - offset),
              std::max(lo.y, o.region->first.y - offset)};
        hi = {std::min(hi.x, o.region->second.x + offset),
              std::min(hi.y, o.region->second.y + offset)};
    }
    const double rangeCap =
        std::min(beams.maxRange, std::hypot(map.max.x - map.min.x, map.max.y - map.min.y));
    const size_t needed = size_t(std::ceil(o.minAgreement * 0.8 * double(used.size())));
    // on the coarse grid, the beams through walls the beam model lets a pose have, and 3
    // more (a grid pose is up to half a step off the refined one)
    size_t allowed = 0;
    while (allowed < used.size() && throughBeamsAreRandom(allowed + 1, used.size())) ++allowed;
    if (o.maxThrough < 1)
        allowed = std::min(allowed, size_t(o.maxThrough * 2 * double(used.size())));
    const size_t throughCap = 3 + allowed;
    // one row of positions: its candidates, in order (rows run on every core; concatenated
    // in row order, the result does not depend on the number of threads)
    struct Row {
        std::vector<PoseHypothesis> candidates;
        size_t positions = 0, poses = 0;
    };
    const auto searchRow = [&](double y, Row& row) {
        std::vector<double> profile(kProfileBins);
        for (double x = lo.x + 0.5 * ps; x < hi.x; x += ps) {
            const TPoint2D at{x, y};
            if (!map.freeCells.at(at)) continue;
            ++row.positions;
            for (size_t k = 0; k < kProfileBins; ++k)
                profile[k] = map.caster.cast(at, binWidth * double(k), rangeCap);
            for (const double h : headings) {
                const TPose2D robot = robotOfSensorAt(at, h, beams.sensor);
                if (o.region && (robot.x < o.region->first.x || robot.x > o.region->second.x ||
                                 robot.y < o.region->first.y || robot.y > o.region->second.y))
                    continue;
                if (!map.freeCells.at({robot.x, robot.y})) continue;
                ++row.poses;
                size_t agree = 0, through = 0;
                for (size_t u = 0; u < used.size(); ++u) {
                    const double phi = (h + beams.angle[used[u]]) / binWidth;
                    long bin = std::lround(phi) % long(kProfileBins);
                    if (bin < 0) bin += long(kProfileBins);
                    const double e = beams.range[used[u]] - profile[size_t(bin)];
                    if (std::abs(e) <= tol[u])
                        ++agree;
                    else if (e > 0)
                        ++through;
                }
                if (agree < needed || through > throughCap) continue;
                PoseHypothesis c;
                c.pose = robot;
                c.score.returns = used.size();
                c.score.agree = agree;
                c.score.through = through;
                c.score.cost = -(double(agree) - 3.0 * double(through));  // lower is better
                row.candidates.push_back(std::move(c));
            }
        }
    };
    std::vector<double> ys;
    for (double y = lo.y + 0.5 * ps; y < hi.y; y += ps) ys.push_back(y);
    std::vector<Row> rows(ys.size());
    common::parallelFor(ys.size(), [&](size_t i) { searchRow(ys[i], rows[i]); });
    std::vector<PoseHypothesis> candidates;
    for (auto& row : rows) {
        st.positions += row.positions;
        st.poses += row.poses;
        for (auto& c : row.candidates) candidates.push_back(std::move(c));
    }
    std::sort(candidates.begin(), candidates.end(),
              [](const PoseHypothesis& a, const PoseHypothesis& b) {
                  return a.score.cost < b.score.cost;
              });
    candidates =
        distinct(std::move(candidates), o.mergeDistance, o.mergeAngle * kDeg, 3 * o.maxHypotheses);
    std::vector<PoseHypothesis> refined(candidates.size());
    const size_t refineStride = strideFor(beams, 120);
    common::parallelFor(candidates.size(), [&](size_t i) {
        refined[i] = refinePose(map, beams, candidates[i].pose, o.tolerance, 0.5 * ps, 0.5 * hs,
                                refineStride);
        refined[i].path.push_back({beams.time, refined[i].pose});
    });
    st.refined = refined.size();
    // best first by the beam model's likelihood (BeamModel)
    std::sort(refined.begin(), refined.end(), [](const PoseHypothesis& a, const PoseHypothesis& b) {
        return a.score.logRatio != b.score.logRatio ? a.score.logRatio > b.score.logRatio
                                                    : a.score.cost < b.score.cost;
    });
    const size_t all = refined.size();
    refined = distinct(std::move(refined), 0.5 * o.mergeDistance, 0.5 * o.mergeAngle * kDeg, all);
    // a pose fits if the map explains its scan better than noise, with enough beams agreeing
    // and not too many short in front of mapped walls; kept within the margin of the best
    const auto fits = [&o](const PoseHypothesis& h) {
        return h.score.logRatio > 0 && h.score.agreement() >= o.minAgreement &&
               throughBeamsAreRandom(h.score.through, h.score.returns) &&
               h.score.throughFraction() <= o.maxThrough &&
               h.score.clutterFraction() <= o.maxClutter;
    };
    double best = 0;
    for (const auto& h : refined)
        if (fits(h)) best = std::max(best, h.score.agreement());
    std::vector<PoseHypothesis> kept;
    for (auto& h : refined)
        if (fits(h) && h.score.agreement() >= best - o.keepMargin &&
            kept.size() < o.maxHypotheses) {
            h.rank = kept.size() + 1;
            h.evidence = h.score.agreement();
            kept.push_back(std::move(h));
        } else {
            st.runnerUp = std::max(st.runnerUp, h.score.agreement());
        }
    if (stats) *stats = st;
    return kept;
}

PassiveElimination::PassiveElimination(const WallMap& map, const ScanLocalizerOptions& options,
                                       std::vector<PoseHypothesis> hypotheses, double time)
    : map_(&map), options_(options), live_(std::move(hypotheses)), startTime_(time) {
    initial_ = live_.size();
    if (live_.size() == 1) uniqueTime = 0, uniqueDistance = 0;
}

void PassiveElimination::update(const TPose2D& motion, double travelled, const ScanBeamSet& beams) {
    ++scans;
    if (live_.empty() || beams.returns < 8) return;
    // seed 002 step 9 on a recorded log: each hypothesis moved as the robot moved, refined
    // against the new scan (odometry drifts), then compared with the others
    const size_t stride = strideFor(beams, 90);
    for (auto& h : live_) {
        const double c = std::cos(h.pose.phi), s = std::sin(h.pose.phi);
        const TPose2D moved{h.pose.x + c * motion.x - s * motion.y,
                            h.pose.y + s * motion.x + c * motion.y,
                            mrpt::math::wrapToPi(h.pose.phi + motion.phi)};
        auto r = refinePose(*map_, beams, moved, options_.tolerance, 0.08, 1.5 * kDeg, stride);
        h.pose = r.pose;
        h.score = r.score;
        h.evidence += r.score.agreement();
        h.path.push_back({beams.time, h.pose});
    }
    if (live_.size() == 1) return;  // tracking: the one hypothesis is never dropped
    double best = 0;
    for (const auto& h : live_) best = std::max(best, h.score.agreement());
    std::vector<PoseHypothesis> next;
    for (auto& h : live_) {
        const bool trails = h.score.agreement() < best - options_.keepMargin;
        h.trailing = trails ? h.trailing + 1 : 0;
        const bool dropped = h.trailing >= 2 || h.score.logRatio <= 0 ||
                             !throughBeamsAreRandom(h.score.through, h.score.returns) ||
                             h.score.throughFraction() > options_.maxThrough;
        if (!dropped) next.push_back(std::move(h));
    }
    if (next.empty()) {  // the map explains no one's scan: keep the best, say nothing is known
        auto it = std::max_element(live_.begin(), live_.end(), [](const auto& a, const auto& b) {
            return a.score.agreement() < b.score.agreement();
        });
        next.push_back(std::move(*it));
    }
    // hypotheses that converged onto one pose are one: the one with more evidence stays
    std::sort(next.begin(), next.end(), [](const PoseHypothesis& a, const PoseHypothesis& b) {
        return a.evidence != b.evidence ? a.evidence > b.evidence : a.rank < b.rank;
    });
    const size_t count = next.size();
    live_ = distinct(std::move(next), 0.25, 5 * kDeg, count);
    if (live_.size() == 1 && !uniqueTime) {
        uniqueTime = beams.time - startTime_;
        uniqueDistance = travelled;
    }
}

}  // namespace mrloc::polymap
