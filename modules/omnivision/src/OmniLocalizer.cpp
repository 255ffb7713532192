#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/IniSection.h>
#include <mrloc/common/Metrics.h>
#include <mrloc/common/Rawlog.h>
#include <mrloc/common/Trajectory.h>
#include <mrloc/omnivision/MarkerDetector.h>
#include <mrloc/omnivision/OmniFiles.h>
#include <mrloc/omnivision/OmniLocalizer.h>
#include <mrpt/core/format.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CObservationImage.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CObservationRange.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

namespace mrloc::omnivision {

namespace {
constexpr double kSameInstant = 1e-3;  ///< s: snapshots are looked up by time

template <class T>
std::shared_ptr<T> expect(const mrpt::obs::CObservation::Ptr& obs, const char* className) {
    auto p = std::dynamic_pointer_cast<T>(obs);
    if (!p)
        throw Error("omnivision: observation '" + obs->sensorLabel + "' is a " +
                    obs->GetRuntimeClass()->className + ", expected " + className);
    return p;
}
}  // namespace

std::vector<std::optional<Vec2>> OmniResult::final() const {
    return refined ? refined->position.back() : paper.position;
}

std::vector<std::optional<double>> OmniResult::finalHeading() const {
    return refined ? refined->heading.back() : paper.heading;
}

void OmniLocalizer::configure(const mrpt::config::CConfigFileBase& ini) {
    options_.loadFromConfigFile(ini, "omnivision");
    origin_ = common::configOrigin(ini);
    views_.clear();
    firstTime_.reset();
    odometer_.clear();
    odometryPaths_.clear();
    odometryPoses_.clear();
    lidar_.clear();
    result_.reset();
}

void OmniLocalizer::saveConfig(mrpt::config::CConfigFileBase& target) const {
    options_.saveToConfigFile(target, "omnivision");
}

void OmniLocalizer::process(const mrpt::obs::CObservation::Ptr& obs) {
    const std::string robot = common::robotOfLabel(obs->sensorLabel);
    const std::string sensor = common::sensorOfLabel(obs->sensorLabel);
    const double t = mrpt::Clock::toDouble(obs->timestamp);
    if (!firstTime_ || t < *firstTime_) firstTime_ = t;
    if (sensor == "omni") {
        const auto img = expect<mrpt::obs::CObservationImage>(obs, "CObservationImage");
        DetectorOptions detector;  // the band's size splits overlapping markers
        detector.markerRadius = options_.markerRadius;
        detector.markerHeight = options_.markerHeight;
        views_[t][robot] =
            makeView(detectMarkers(img->image, options_.panorama, detector), obs->sensorLabel);
    } else if (sensor == "omni_bearings") {
        const auto b = expect<mrpt::obs::CObservationBearingRange>(obs, "CObservationBearingRange");
        views_[t][robot] = viewFromObservation(*b, obs->sensorLabel);
    } else if (sensor == "odom") {
        const auto o = expect<mrpt::obs::CObservationOdometry>(obs, "CObservationOdometry");
        auto& path = odometryPaths_[robot];
        path.add(t, o->odometry);
        odometryPoses_[robot].push_back({t, mrpt::poses::CPose3D(o->odometry)});
        auto& readings = odometer_[robot];
        const double heading =
            readings.empty()
                ? o->odometry.phi()
                : readings.back().heading +
                      mrpt::math::wrapToPi(o->odometry.phi() - readings.back().heading);
        readings.push_back({t, path.length(), heading});
    } else if (sensor.rfind("lidar.", 0) == 0) {
        const auto r = expect<mrpt::obs::CObservationRange>(obs, "CObservationRange");
        if (r->sensedData.size() != 1 || !std::isfinite(r->sensedData.front().sensedDistance))
            throw Error("omnivision: '" + obs->sensorLabel + "' must hold one finite distance");
        lidar_.push_back(
            {t, robot, sensor.substr(6), double(r->sensedData.front().sensedDistance)});
    }
    result_.reset();
}

namespace {
/** A quantity the odometer accumulates, linearly interpolated at t (clamped to the log). */
template <class Path, class Get>
double odometerAt(const Path& path, double t, Get get) {
    if (t <= path.front().t) return get(path.front());
    if (t >= path.back().t) return get(path.back());
    const auto hi = std::lower_bound(path.begin(), path.end(), t,
                                     [](const auto& r, double time) { return r.t < time; });
    const auto lo = hi - 1;
    const double a = (t - lo->t) / (hi->t - lo->t);
    return get(*lo) + a * (get(*hi) - get(*lo));
}
}  // namespace

double OmniLocalizer::travelledBetween(const std::string& robot, double t0, double t1) const {
    const auto it = odometer_.find(robot);
    if (it == odometer_.end() || it->second.empty()) return 0;
    const auto length = [](const OdometerReading& r) { return r.length; };
    return odometerAt(it->second, t1, length) -
           odometerAt(it->second, t0, length);  // eq. (8)'s l_C
}

double OmniLocalizer::turnedBetween(const std::string& robot, double t0, double t1) const {
    const auto it = odometer_.find(robot);
    if (it == odometer_.end() || it->second.empty()) return 0;
    const auto heading = [](const OdometerReading& r) { return r.heading; };
    return odometerAt(it->second, t1, heading) - odometerAt(it->second, t0, heading);
}

Snapshot OmniLocalizer::snapshotAt(double t, const std::vector<std::string>& robots) const {
    auto it = views_.lower_bound(t - kSameInstant);
    if (it == views_.end() || it->first > t + kSameInstant)
        throw Error(mrpt::format("omnivision: no camera snapshot at t = %.3f in the rawlog", t));
    Snapshot s;
    s.time = it->first;
    for (const auto& r : robots) {
        const auto v = it->second.find(r);
        s.views.push_back(v == it->second.end() ? View{} : v->second);
    }
    return s;
}

const OmniResult& OmniLocalizer::result() const {
    if (result_) return *result_;
    if (views_.empty())
        throw Error(
            "omnivision: the rawlog has no <robot>.omni or <robot>.omni_bearings "
            "observation");
    OmniResult r;
    std::set<std::string> names;
    for (const auto& [t, byRobot] : views_)
        for (const auto& [name, v] : byRobot) names.insert(name);
    r.robots.assign(names.begin(), names.end());
    const auto index = [&](const std::string& name, const char* key) {
        const auto it = std::find(r.robots.begin(), r.robots.end(), name);
        if (it == r.robots.end())
            throw Error(origin_ + ": [omnivision] " + key + ": robot '" + name +
                        "' has no camera in the rawlog");
        return int(it - r.robots.begin());
    };
    const double start = *firstTime_;  // snapshot times count from the rawlog's start
    SearchOptions so;
    so.sumTolerance = options_.sumToleranceRad();
    so.bearingTolerance = options_.bearingToleranceRad();
    RefinementProblem p;
    p.bearingSigma = options_.bearingNoise();
    if (options_.render) {
        // The middle of a marker's columns errs by 1/sqrt(24) of a column (each edge
        // anywhere in its column), and a column spans cos^2(angle off the view's axis) / f.
        const Panorama pano = options_.panorama;
        p.bearingSigmaAt = [pano](double bearing) {
            return pano.columnAngleAt(bearing) / std::sqrt(24.0);
        };
        p.stillViewsRepeat = true;
    }
    if (options_.method == "proposed") {
        bool solved = false;
        for (size_t round = 0; round < options_.pairs.size() && !solved; ++round) {
            const auto& [na, nb] = options_.pairs[round];
            const double tb = start + options_.tb + double(round) * options_.roundPeriod;
            const double te = start + options_.te + double(round) * options_.roundPeriod;
            const int a = index(na, "pairs"), b = index(nb, "pairs");
            const Snapshot sb = snapshotAt(tb, r.robots), se = snapshotAt(te, r.robots);
            const Identification ie = identify(se, so);
            std::vector<double> travelled, turned;
            for (const auto& name : r.robots) {
                travelled.push_back(travelledBetween(name, tb, te));
                turned.push_back(turnedBetween(name, tb, te));
            }
            Identification ib;
            try {
                if (options_.localizedSearch()) {
                    const auto local = localizedRestartSearch(
                        sb, se, ie, a, b, travelled, turned, so,
                        options_.searchAtTb == OmniOptions::SearchAtTb::LocalizedTurn);
                    r.localizedSearches.push_back({na + " " + nb, local.witnessesTried,
                                                   local.triples, local.triangles,
                                                   local.unconfirmed});
                    // no witness: the fall-back paper 000 names, t_b searched as t_e
                    ib = local.witness >= 0 ? local.before : identify(sb, so);
                } else {
                    ib = identify(sb, so);
                }
                const auto prop = proposedMethod(sb, ib, se, ie, a, b, travelled);
                r.a = a, r.b = b, r.moving = prop.moving, r.travelled = prop.travelled;
                r.time = se.time, r.timeBefore = sb.time;
                r.snapshots = {sb, se};
                r.ids = {ib, ie};
                r.paper = prop.after;
                p.snapshots = {sb, se};
                p.labels = {ib.labels, ie.labels};
                p.initial = {prop.before.position, prop.after.position};
                p.stationary = {a, b};
                for (size_t k = 0; k < r.robots.size(); ++k)
                    if (travelled[k] > 0 && prop.before.position[k] && prop.after.position[k])
                        p.distances.push_back({0, int(k), 1, int(k), travelled[k],
                                               options_.odometerSigma * travelled[k] + 1e-3});
                solved = true;
            } catch (const Error& e) {
                r.restarts.push_back(na + " " + nb + ": " + e.what() +
                                     mrpt::format(" [%zu and %zu triangles]", ib.triangles.size(),
                                                  ie.triangles.size()));  // the paper's restart
            }
        }
        if (!solved) {
            std::string why;
            for (const auto& s : r.restarts) why += "\n  " + s;
            throw Error("omnivision: no stopped pair gave the baseline L:" + why);
        }
    } else {
        // Named references, not a structured binding: C++17 lambdas cannot capture those.
        const std::string& na = options_.measuredPair.first;
        const std::string& nb = options_.measuredPair.second;
        const int a = index(na, "measured_pair"), b = index(nb, "measured_pair");
        const Snapshot s = snapshotAt(start + options_.snapshot, r.robots);
        const auto reading = std::find_if(lidar_.begin(), lidar_.end(), [&](const auto& l) {
            return l.from == na && l.to == nb && std::abs(l.time - s.time) < kSameInstant;
        });
        if (reading == lidar_.end())
            throw Error("omnivision: conventional method: no distance " + na + ".lidar." + nb +
                        " measured at the snapshot");
        const Identification id = identify(s, so);
        r.a = a, r.b = b, r.time = s.time;
        r.snapshots = {s};
        r.ids = {id};
        r.paper = conventionalMethod(s, id, a, b, reading->distance);
        p.snapshots = {s};
        p.labels = {id.labels};
        p.initial = {r.paper.position};
        p.distances.push_back({0, a, 0, b, reading->distance, std::max(options_.lidarSigma, 1e-4)});
    }
    if (options_.refine) {
        p.a = r.a, p.b = r.b;
        r.refined = refineLayout(p);
    }
    result_ = std::move(r);
    return *result_;
}

std::map<std::string, common::Trajectory> OmniLocalizer::estimates() const {
    const auto& r = result();
    std::map<std::string, common::Trajectory> out;
    const auto final = r.final();
    const auto heading = r.finalHeading();
    for (size_t k = 0; k < r.robots.size(); ++k) {
        auto& traj = out[r.robots[k]];  // a robot the layout did not place: none
        if (!final[k] || !heading[k]) continue;
        // paper 000 solves one instant; from then on each robot's own odometry carries it
        const auto odometry = odometryPoses_.find(r.robots[k]);
        const common::Trajectory none;
        traj = common::carriedByOdometry(
            mrpt::poses::CPose3D(final[k]->x(), final[k]->y(), 0, *heading[k], 0, 0), r.time,
            odometry == odometryPoses_.end() ? none : odometry->second);
    }
    return out;
}

std::map<std::string, common::CovarianceTrack> OmniLocalizer::covariances() const {
    const auto& r = result();
    std::map<std::string, common::CovarianceTrack> out;
    if (!r.refined) return out;
    const auto final = r.final();
    const auto heading = r.finalHeading();
    for (size_t k = 0; k < r.robots.size(); ++k) {
        if (!final[k] || !heading[k]) continue;  // one line per estimate
        common::StampedCovariance c{r.time, {}};
        const Eigen::Matrix3d& P = r.refined->covariance.back()[k];
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) c.cov(i, j) = P(i, j);
        out[r.robots[k]].push_back(c);
    }
    return out;
}

common::Trajectories OmniLocalizer::truthInEstimateFrame(const common::Trajectories& gt) const {
    const auto& r = result();
    const auto ga = gt.find(r.robots[size_t(r.a)]), gb = gt.find(r.robots[size_t(r.b)]);
    if (ga == gt.end() || gb == gt.end()) return {};  // no truth for A or B: no errors
    const auto pa = common::interpolate(ga->second, r.time);
    const auto pb = common::interpolate(gb->second, r.time);
    if (!pa || !pb) return {};
    // The paper's frame: A at the origin, B on the +x axis.
    const mrpt::poses::CPose3D frame(pa->x(), pa->y(), 0,
                                     std::atan2(pb->y() - pa->y(), pb->x() - pa->x()), 0, 0);
    const mrpt::poses::CPose3D toFrame = -frame;
    common::Trajectories truth;
    for (const auto& [robot, traj] : gt) {
        auto& out = truth[robot];
        for (const auto& s : traj) out.push_back({s.t, toFrame + s.pose});
    }
    return truth;
}

std::vector<std::optional<mrpt::poses::CPose2D>> OmniLocalizer::truthAtLayout(
    const common::Trajectories& truth) const {
    const auto& r = result();
    std::vector<std::optional<mrpt::poses::CPose2D>> out(r.robots.size());
    for (size_t k = 0; k < r.robots.size(); ++k)
        if (const auto it = truth.find(r.robots[k]); it != truth.end())
            if (const auto p = common::interpolate(it->second, r.time))
                out[k] = mrpt::poses::CPose2D(p->x(), p->y(), p->yaw());
    return out;
}

common::ObservationUse OmniLocalizer::observationUse() const {
    common::ObservationUse use;
    use.kind =
        "omni-directional views (CObservationImage <robot>.omni, CObservationBearingRange "
        "<robot>.omni_bearings)";
    for (const auto& [t, views] : views_) use.seen += views.size();
    use.used = use.seen;
    return use;
}

nlohmann::json OmniLocalizer::methodMetrics() const {
    const auto& r = result();
    nlohmann::json j;
    j["method"] = options_.method;
    j["camera"] = options_.render ? "render" : "bearings";
    j["robots"] = r.robots.size();
    j["pair"] = r.robots[size_t(r.a)] + " " + r.robots[size_t(r.b)];
    j["restarts"] = r.restarts;
    j["search_at_tb"] = OmniOptions::wordOf(options_.searchAtTb);
    for (const auto& l : r.localizedSearches) {
        nlohmann::json lj = {{"pair", l.pair},
                             {"witnesses_tried", l.witnessesTried},
                             {"image_triples", l.triples},
                             {"triangles_summing_to_180", l.triangles}};
        if (!l.fallback.empty()) lj["full_search_instead"] = l.fallback;
        j["localized_searches"].push_back(lj);
    }
    j["baseline_L_m"] = r.paper.baseline;
    if (r.moving >= 0) {
        j["moving_robot_C"] = r.robots[size_t(r.moving)];
        j["travelled_l_C_m"] = r.travelled;
    }
    j["sum_tolerance_deg"] = options_.sumToleranceRad() * 180 / M_PI;
    j["bearing_tolerance_deg"] = options_.bearingToleranceRad() * 180 / M_PI;
    const char* names[] = {"t_b", "t_e"};
    for (size_t s = 0; s < r.ids.size(); ++s) {
        nlohmann::json sj;
        sj["triangles"] = r.ids[s].triangles.size();
        sj["seeds_tried"] = r.ids[s].candidates;
        sj["pair_visits"] = r.ids[s].pairVisits;
        const bool localized = options_.localizedSearch() && r.ids.size() == 2 && s == 0 &&
                               !r.localizedSearches.empty() &&
                               r.localizedSearches.back().fallback.empty();
        sj["search"] = localized ? "localized" : "full";
        std::vector<std::string> unresolved;
        std::map<std::string, size_t> why;  // reason's key -> robots
        for (int k : r.ids[s].unresolved) {
            unresolved.push_back(r.robots[size_t(k)]);
            ++why[textOf(whyUnresolved(r.snapshots[s], r.ids[s], k)).key];
        }
        sj["unresolved"] = unresolved;
        sj["unresolved_why"] = why;
        j["snapshots"][r.ids.size() == 2 ? names[s] : "snapshot"] = sj;
    }
    if (r.refined) {
        j["refined_rms_bearing_residual_deg"] = r.refined->rmsBearingResidual * 180 / M_PI;
        j["refined_bearings"] = r.refined->bearings;
        j["refined_iterations"] = r.refined->iterations;
    }
    return j;
}

nlohmann::json OmniLocalizer::truthMetrics(const common::Trajectories& truthInFrame) const {
    // Against the truth, in the paper's frame: pairwise distances and the layout.
    const auto& r = result();
    const auto pose = truthAtLayout(truthInFrame);
    std::vector<std::optional<Vec2>> truth(pose.size());
    for (size_t k = 0; k < pose.size(); ++k)
        if (pose[k]) truth[k] = Vec2(pose[k]->x(), pose[k]->y());
    nlohmann::json j = nlohmann::json::object();
    const auto stats = [](const std::vector<double>& v, const char* count = "pairs") {
        const auto st = common::computeStats(v);
        return nlohmann::json{{count, v.size()}, {"median", st.median}, {"max", st.max}};
    };
    // Headings (deg), the paper layout's and the refined, against the truth's.
    const auto headingErrors = [&](const std::vector<std::optional<double>>& heading) {
        std::vector<double> err;
        for (size_t k = 0; k < pose.size(); ++k)
            if (pose[k] && heading[k])
                err.push_back(std::abs(mrpt::math::wrapToPi(*heading[k] - pose[k]->phi())) * 180 /
                              M_PI);
        return stats(err, "robots");
    };
    j["heading_error_deg_paper"] = headingErrors(r.paper.heading);
    if (r.refined) j["heading_error_deg_refined"] = headingErrors(r.refined->heading.back());
    if (truth[size_t(r.a)] && truth[size_t(r.b)]) {
        j["true_L_m"] = (*truth[size_t(r.b)] - *truth[size_t(r.a)]).norm();
        std::vector<double> paperErr, refinedErr;
        const auto final = r.final();
        for (const auto& [e, d] : r.paper.distance) {
            const auto &ti = truth[size_t(e.first)], &tj = truth[size_t(e.second)];
            if (!ti || !tj) continue;
            const double dt = (*ti - *tj).norm();
            paperErr.push_back(std::abs(d - dt) / dt);
            if (r.refined && final[size_t(e.first)] && final[size_t(e.second)])
                refinedErr.push_back(
                    std::abs((*final[size_t(e.first)] - *final[size_t(e.second)]).norm() - dt) /
                    dt);
        }
        j["relative_distance_error_paper"] = stats(paperErr);
        if (r.refined) j["relative_distance_error_refined"] = stats(refinedErr);
    }
    return j;
}

void OmniLocalizer::writeOutputs(const std::string& outDir,
                                 const common::Trajectories& truthInFrame) const {
    const auto& r = result();
    const auto final = r.final();
    const auto truth = truthAtLayout(truthInFrame);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    LayoutFile layout;
    layout.time = r.time;
    layout.a = r.robots[size_t(r.a)];
    layout.b = r.robots[size_t(r.b)];
    for (size_t k = 0; k < r.robots.size(); ++k) {
        const auto& p = r.paper.position[k];
        LayoutPoint lp{r.robots[k],
                       p ? p->x() : nan,
                       p ? p->y() : nan,
                       nan,
                       nan,
                       nan,
                       nan,
                       nan,
                       truth[k] ? truth[k]->x() : nan,
                       truth[k] ? truth[k]->y() : nan};
        if (r.paper.heading[k]) lp.paperPhi = *r.paper.heading[k];
        if (truth[k]) lp.truePhi = truth[k]->phi();
        if (r.refined && final[k]) {
            const auto& c = r.refined->covariance.back()[k];
            lp.refinedX = final[k]->x(), lp.refinedY = final[k]->y();
            lp.cxx = c(0, 0), lp.cxy = c(0, 1), lp.cyy = c(1, 1);
            if (const auto& h = r.refined->heading.back()[k])
                lp.refinedPhi = *h, lp.cphiphi = c(2, 2);
        }
        layout.points.push_back(lp);
    }
    layout.write(outDir);
}

AccuracyLayout OmniLocalizer::accuracyLayout(const common::Trajectories& truthInFrame) const {
    const auto& r = result();
    AccuracyLayout layout;
    layout.proposed = options_.method == "proposed";
    layout.a = r.a, layout.b = r.b;
    const auto poseAt = [&](size_t k, double t) {
        const auto it = truthInFrame.find(r.robots[k]);
        const auto p = it == truthInFrame.end() ? std::nullopt : common::interpolate(it->second, t);
        if (!p) throw Error("omnivision accuracy sweep: no truth for " + r.robots[k]);
        return mrpt::poses::CPose2D(p->x(), p->y(), p->yaw());
    };
    const auto seen = [&](size_t s) {
        std::vector<std::vector<int>> out(r.robots.size());
        for (size_t o = 0; o < r.robots.size(); ++o)
            for (int who : r.ids[s].labels[o])
                if (who >= 0) out[o].push_back(who);
        return out;
    };
    for (size_t k = 0; k < r.robots.size(); ++k) {
        layout.after.push_back(poseAt(k, r.time));
        layout.before.push_back(poseAt(k, layout.proposed ? r.timeBefore : r.time));
    }
    layout.seenAfter = seen(r.ids.size() - 1);
    layout.seenBefore = seen(0);
    return layout;
}

}  // namespace mrloc::omnivision
