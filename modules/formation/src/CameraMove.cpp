#include <mrloc/common/Error.h>
#include <mrloc/formation/CameraMove.h>
#include <mrpt/math/wrap2pi.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <set>

namespace mrloc::formation {

namespace {
/** When Algorithm 1 misses a beacon, steps along the heading (m) that look from nearby
 *  viewpoints in turn and come back to where it started (a tag seen edge-on, or cut at a
 *  robot's corner), then two steps away from the beacons (the rear camera looks back: from
 *  farther the base beacons stand nearer its axis), from where Algorithm 1's depth
 *  condition brings the robot back. */
constexpr std::array<double, 7> kRecovery{0.03, -0.06, 0.09, -0.12, 0.06, 0.3, 0.3};
/** When the rear camera misses the anchor after facing away from it, turns (rad) that look
 *  to either side in widening steps: headings of +-20, +-40 and +-60 degrees about the
 *  first, with the camera's +-53 degrees that is +-113 degrees searched. */
constexpr std::array<double, 6> kAnchorScan{0.35, -0.70, 1.05, -1.40, 1.75, -2.10};
/** Algorithm 1 frames after which its pixel tolerance doubles: a robot that dithers about
 *  the vertex (the maneuvers' errors larger than the tolerance asks) stops near it rather
 *  than loses the move. */
constexpr int kRelaxEvery = 20;
/** The lattice fit drops the tag with the largest residual while any is over this (px): a
 *  tag cut at another robot's edge, or a robot far off its believed vertex. */
constexpr double kFitOutlier = 4;
/** A lattice fit farther than this (m) from where Algorithm 1 put the robot among its three
 *  beacons is not trusted (Algorithm 1 places it within millimetres of them). */
constexpr double kFitMaxCorrection = 0.05;

/** The rear camera's picture column (px) of a world point at the camera's height, the robot
 *  at `pose`: unlike project(), also for a point outside the picture (the fit's numeric
 *  Jacobian steps across the picture's edge). */
double rearColumn(const mrpt::poses::CPose2D& pose, const MarkerOptions& m, const TPoint2D& p,
                  const mrpt::img::TCamera& k) {
    const auto local = rearCameraPose(pose, m.bodySize, m.tagHeight)
                           .inverseComposePoint({p.x, p.y, m.tagHeight});  // +Z ahead, +X right
    return k.cx() + k.fx() * local.x / local.z;
}
}  // namespace

std::optional<LatticeFit> fitToLattice(const std::vector<MarkerSighting>& tags,
                                       const std::vector<mrpt::poses::CPose2D>& believed,
                                       size_t self, const mrpt::poses::CPose2D& start,
                                       const mrpt::img::TCamera& k, const MarkerOptions& markers,
                                       size_t minRobots) {
    struct Bearing {
        TPoint2D point;  ///< the tag's centre, believed
        double u = 0;    ///< px, seen
        size_t robot = 0;
    };
    std::vector<Bearing> seen;
    for (const auto& t : tags) {
        const size_t r = size_t(t.id / 4);
        if (t.id < 0 || r == self || r >= believed.size()) continue;
        const auto c = markerCentre(believed[r], Side(t.id % 4), markers);
        seen.push_back({{c.x, c.y}, t.u, r});
    }
    const auto robots = [&] {
        std::set<size_t> r;
        for (const auto& b : seen) r.insert(b.robot);
        return r.size();
    };
    for (;;) {
        if (robots() < std::max<size_t>(minRobots, 3)) return std::nullopt;
        // Gauss-Newton on (x, y, phi), numeric Jacobian of each column
        Eigen::Vector3d x(start.x(), start.y(), start.phi());
        const auto residuals = [&](const Eigen::Vector3d& q) {
            Eigen::VectorXd r(Eigen::Index(seen.size()));
            const mrpt::poses::CPose2D pose(q[0], q[1], q[2]);
            for (size_t i = 0; i < seen.size(); ++i)
                r[Eigen::Index(i)] = seen[i].u - rearColumn(pose, markers, seen[i].point, k);
            return r;
        };
        bool converged = false;
        for (int it = 0; it < 20 && !converged; ++it) {
            const Eigen::VectorXd r = residuals(x);
            Eigen::MatrixXd J(r.size(), 3);
            for (int j = 0; j < 3; ++j) {
                Eigen::Vector3d dx = Eigen::Vector3d::Zero();
                dx[j] = 1e-5;
                J.col(j) = -(residuals(x + dx) - residuals(x - dx)) / 2e-5;  // the columns'
            }
            const Eigen::Vector3d step = (J.transpose() * J).ldlt().solve(J.transpose() * r);
            if (!step.allFinite()) return std::nullopt;
            x += step;
            converged = step.head<2>().norm() < 1e-6 && std::abs(step[2]) < 1e-6;
        }
        if (!converged || !x.allFinite()) return std::nullopt;
        const Eigen::VectorXd r = residuals(x);
        Eigen::Index worst = 0;
        if (r.cwiseAbs().maxCoeff(&worst) > kFitOutlier) {
            seen.erase(seen.begin() + worst);
            continue;
        }
        return LatticeFit{mrpt::poses::CPose2D(x[0], x[1], mrpt::math::wrapToPi(x[2])), robots(),
                          std::sqrt(r.squaredNorm() / double(r.size()))};
    }
}

CameraMove::CameraMove(const Move& move, const std::vector<TPoint2D>& believed,
                       const std::vector<double>& headings, const CameraMoveOptions& o)
    : move_(move), o_(o), anchor_(believed.at(move.anchor)) {
    at_ = believed.at(move.robot);
    heading_ = headings.at(move.robot);
    if (headings.size() != believed.size())
        throw Error("formation: a move needs every robot's believed heading");
    for (size_t i = 0; i < believed.size(); ++i)
        believed_.emplace_back(believed[i].x, believed[i].y, headings[i]);
    // Algorithm 2's midpoints: which two beacons each lies between
    const std::array<size_t, 3> b{move.base[0], move.base[1], move.anchor};
    for (size_t p = 0; p + 1 < move.path.size(); ++p) {
        double best = INFINITY;
        std::array<size_t, 2> pair{};
        for (size_t i = 0; i < 3; ++i)
            for (size_t j = i + 1; j < 3; ++j) {
                const double d = ((believed[b[i]] + believed[b[j]]) * 0.5 - move.path[p]).norm();
                if (d < best) best = d, pair = {b[i], b[j]};
            }
        gates_.push_back(pair);
        gatePoints_.push_back(move.path[p]);
    }
    if (gates_.empty()) throw Error("formation: a move's path has no gate between beacons");
    BeaconTriangle triangle;
    for (size_t i = 0; i < 3; ++i) {
        triangle.pose[i] = mrpt::poses::CPose2D(believed[b[i]].x, believed[b[i]].y, headings[b[i]]);
        triangle.robot[i] = b[i];
    }
    algorithmOne_.emplace(triangle, o.intrinsics, o.markers, o.algorithmOne);
}

std::vector<Maneuver> CameraMove::order(std::vector<Maneuver> maneuvers) {
    for (const auto& m : maneuvers) {
        if (m.kind == Maneuver::Kind::Turn)
            heading_ = mrpt::math::wrapToPi(heading_ + m.amount);
        else
            at_ = at_ + TPoint2D{std::cos(heading_), std::sin(heading_)} * m.amount;
    }
    return maneuvers;
}

std::vector<Maneuver> CameraMove::towards(const TPoint2D& p) {
    return order(
        {Maneuver::turn(mrpt::math::wrapToPi(std::atan2(p.y - at_.y, p.x - at_.x) - heading_))});
}

std::vector<Maneuver> CameraMove::start() { return towards(gatePoints_[0]); }

std::optional<CameraMove::Camera> CameraMove::camera() const {
    switch (phase_) {
        case Phase::Gate:
            return Camera::Front;
        case Phase::FaceAway:
        case Phase::AlgorithmOne:
        case Phase::LatticeFit:
            return Camera::Rear;
        default:
            return std::nullopt;
    }
}

std::optional<MarkerSighting> CameraMove::largestTag(
    size_t robot, const std::vector<MarkerSighting>& tags) const {
    std::optional<MarkerSighting> best;
    for (const auto& t : tags)
        if (size_t(t.id / 4) == robot && (!best || t.size > best->size)) best = t;
    return best;
}

std::vector<Maneuver> CameraMove::gatePassed() {
    at_ = gatePoints_[gate_];  // the camera put it there
    if (++gate_ < gates_.size()) return towards(gatePoints_[gate_]);
    // building the triangle: the rear camera onto the anchor, the believed way first
    phase_ = Phase::FaceAway;
    const TPoint2D away = at_ * 2 - anchor_;
    return towards(away);
}

std::vector<Maneuver> CameraMove::finishBlind() {
    phase_ = Phase::Lost;
    std::vector<Maneuver> m;
    if ((move_.target - at_).norm() > 0.01) {
        m = towards(move_.target);
        auto drive = order({Maneuver::drive((move_.target - at_).norm())});
        m.insert(m.end(), drive.begin(), drive.end());
    }
    auto face = towards(at_ * 2 - anchor_);  // away from the anchor, as Algorithm 1 leaves it
    m.insert(m.end(), face.begin(), face.end());
    return m;
}

std::vector<Maneuver> CameraMove::fitStep(const std::vector<MarkerSighting>& tags) {
    phase_ = Phase::Done;
    if (!o_.latticeFit || latticeFits_ >= o_.latticeFits) return {};
    // arrivalHeading: facing away from the anchor
    const double heading = std::atan2(move_.target.y - anchor_.y, move_.target.x - anchor_.x);
    const auto fit = fitToLattice(tags, believed_, move_.robot,
                                  mrpt::poses::CPose2D(move_.target.x, move_.target.y, heading),
                                  o_.intrinsics, o_.markers, o_.latticeFitRobots);
    if (!fit) return {};  // Algorithm 1's vertex stands
    const TPoint2D at{fit->pose.x(), fit->pose.y()}, to = move_.target - at;
    if (to.norm() < o_.latticeFitTolerance || to.norm() > kFitMaxCorrection) return {};
    // to the vertex the lattice fit puts it off from, and facing away from the anchor again
    ++latticeFits_;
    phase_ = Phase::LatticeFit;
    at_ = at, heading_ = fit->pose.phi();
    // forwards or backwards, whichever turns less
    double along = std::atan2(to.y, to.x), distance = to.norm();
    if (std::abs(mrpt::math::wrapToPi(along - heading_)) > M_PI / 2)
        along = mrpt::math::wrapToPi(along + M_PI), distance = -distance;
    return order({Maneuver::turn(mrpt::math::wrapToPi(along - heading_)), Maneuver::drive(distance),
                  Maneuver::turn(mrpt::math::wrapToPi(heading - along))});
}

std::vector<Maneuver> CameraMove::decide(const std::vector<MarkerSighting>& tags) {
    if (!camera()) return {};
    if (++frames_ > o_.maxFrames) return finishBlind();
    const double f = o_.intrinsics.fx(), cx = o_.intrinsics.cx();
    switch (phase_) {
        case Phase::Gate: {
            const auto a = largestTag(gates_[gate_][0], tags),
                       b = largestTag(gates_[gate_][1], tags);
            const double believed = (gatePoints_[gate_] - at_).norm();
            if (!a || !b) {  // not both in view: the believed geometry
                ++blindGates_;
                auto m = order({Maneuver::drive(believed)});
                auto next = gatePassed();
                m.insert(m.end(), next.begin(), next.end());
                return m;
            }
            const double centre = 0.5 * (a->u + b->u) - cx;
            std::vector<Maneuver> m;
            if (std::abs(centre) > o_.gateTolerance) {  // a point right of centre: turn right
                m = order({Maneuver::turn(-std::atan2(centre, f))});
                if (!o_.algorithmOne.together) return m;  // and look again
            }
            // beacons s apart at depth D show f s / D apart; the tags face the robot, half a
            // body nearer than the robots' centres
            const double D = f * o_.side / std::abs(a->u - b->u) + o_.markers.bodySize / 2;
            if (D > o_.gateStop + 0.15) {
                auto drive = order({Maneuver::drive(D - o_.gateStop)});
                m.insert(m.end(), drive.begin(), drive.end());
                return m;
            }
            auto through = order({Maneuver::drive(D)});
            m.insert(m.end(), through.begin(), through.end());
            auto next = gatePassed();
            m.insert(m.end(), next.begin(), next.end());
            return m;
        }
        case Phase::FaceAway: {
            const auto anchor = largestTag(move_.anchor, tags);
            if (!anchor && scans_ < int(kAnchorScan.size())) {
                // look to either side for it
                return order({Maneuver::turn(kAnchorScan[size_t(scans_++)])});
            }
            if (!anchor) return finishBlind();
            const double e = anchor->u - cx;
            std::vector<Maneuver> m;
            if (std::abs(e) > o_.algorithmOne.pixelTolerance) {
                m = order({Maneuver::turn(-std::atan2(e, f))});
                if (!o_.algorithmOne.together) return m;  // and look again
            }
            phase_ = Phase::AlgorithmOne;  // out to the vertex, then Algorithm 1
            auto out = order({Maneuver::drive((move_.target - at_).norm())});
            m.insert(m.end(), out.begin(), out.end());
            return m;
        }
        case Phase::AlgorithmOne: {
            if (++algorithmOneFrames_ % kRelaxEvery == 0) algorithmOne_->relaxTolerance(2);
            const auto m = algorithmOne_->decide(tags);
            if (!m && recoveries_ < int(kRecovery.size())) {
                // look again from a step away
                return order({Maneuver::drive(kRecovery[size_t(recoveries_++)])});
            }
            if (!m) return finishBlind();
            recoveries_ = 0;
            if (m->empty()) return fitStep(tags);
            return order(*m);
        }
        case Phase::LatticeFit:
            return fitStep(tags);
        default:
            return {};
    }
}

}  // namespace mrloc::formation
