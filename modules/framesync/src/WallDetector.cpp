#include <mrloc/framesync/WallDetector.h>
#include <mrpt/math/geometry.h>
#include <mrpt/math/wrap2pi.h>

#include <algorithm>
#include <cmath>

namespace mrloc::framesync {

using mrpt::math::wrapToPi;

std::optional<std::pair<Erp, Erp>> WallDetector::erpsOf(const SonarReading& r) {
    const TPoint2D p2(r.sensor.x(), r.sensor.y());
    // the newest earlier reading a baseline away (older ones are no longer needed)
    size_t j = history_.size();
    for (size_t k = history_.size(); k-- > 0;) {
        const auto& h = history_[k];
        if ((TPoint2D(h.sensor.x(), h.sensor.y()) - p2).norm() >= options_.baseline) {
            j = k;
            break;
        }
    }
    if (j == history_.size()) return std::nullopt;
    history_.erase(history_.begin(), history_.begin() + long(j));
    const SonarReading& first = history_.front();
    const TPoint2D p1(first.sensor.x(), first.sensor.y());
    const auto roots = wallNormalDirections(p1, first.range, p2, r.range);  // eq. (4)
    if (roots.empty()) {
        ++counts_.noWall;
        return std::nullopt;
    }
    // the normal must lie in both readings' cones: a specular echo comes back only along it
    const double limit = options_.halfAperture + options_.coneMargin;
    std::vector<double> inCone;
    for (const double phi : roots)
        if (std::abs(wrapToPi(phi - r.sensor.phi())) <= limit &&
            std::abs(wrapToPi(phi - first.sensor.phi())) <= limit)
            inCone.push_back(phi);
    if (inCone.empty()) {
        ++counts_.outOfCone;
        return std::nullopt;
    }
    double phi = inCone.front();
    if (inCone.size() == 2) {
        const double apart = wrapToPi(inCone[1] - inCone[0]);
        if (std::abs(apart) > 2 * options_.coneMargin) {
            ++counts_.ambiguous;  // moving along the axis, towards or away from the wall
            return std::nullopt;
        }
        phi = wrapToPi(inCone[0] + apart / 2);
    }
    counts_.erps += 2;
    // eqs. (2)-(3): both ERPs of the pair. Each reading is the first of one pair and the
    // second of another, so the normal's noise (from r2 - r1) moves the two along the wall
    // in opposite senses and the fitted line keeps no tilt from it
    return std::make_pair(makeErp(p1, first.range, phi), makeErp(p2, r.range, phi));
}

std::optional<Wall> WallDetector::add(const SonarReading& r) {
    ++counts_.readings;
    if (!r.echo) {
        history_.clear();
        return close();
    }
    if (!history_.empty()) {
        const auto& last = history_.back().sensor;
        if (std::hypot(last.x() - r.sensor.x(), last.y() - r.sensor.y()) > options_.maxPairGap)
            history_.clear();
    }
    const auto erps = erpsOf(r);
    // A reading from the same pose as the one before it replaces it: erpsOf would pick the
    // newer of the two anyway (same distance to any later reading), and a robot standing
    // still then keeps one reading, not one per echo (the search was quadratic in the time
    // stood). Beyond kMaxHistory readings within a baseline of travel, the oldest go.
    const auto& s = r.sensor;
    if (!history_.empty() && history_.back().sensor.x() == s.x() &&
        history_.back().sensor.y() == s.y() && history_.back().sensor.phi() == s.phi())
        history_.back() = r;
    else
        history_.push_back(r);
    if (history_.size() > kMaxHistory) history_.pop_front();
    if (!erps) return std::nullopt;
    std::optional<Wall> out;
    if (!group_.empty()) {
        const double mean = std::atan2(sumSin_, sumCos_);
        const Erp& e = erps->second;
        const bool joins = std::abs(wrapToPi(e.direction - mean)) <= options_.groupAngle &&
                           (e.point - group_.back().point).norm() <= options_.groupGap;
        if (!joins) out = close();
    }
    for (const Erp* e : {&erps->first, &erps->second}) {
        group_.push_back(*e);
        sumCos_ += std::cos(e->direction), sumSin_ += std::sin(e->direction);
    }
    if ((group_.back().point - group_.front().point).norm() >= options_.wallLength) {
        auto wall = close();
        if (wall) out = wall;  // at most one of the two closes passes: the first was short
    }
    return out;
}

std::optional<Wall> WallDetector::close() {
    std::optional<Wall> wall;
    if (!group_.empty()) wall = fit();
    group_.clear();
    sumCos_ = sumSin_ = 0;
    return wall;
}

std::optional<Wall> WallDetector::fit() {
    const double span = (group_.back().point - group_.front().point).norm();
    auto& counts = counts_;
    if (group_.size() < options_.minErps || span < options_.minLength) {
        ++counts.tooShort;
        return std::nullopt;
    }
    std::vector<TPoint2D> points;
    points.reserve(group_.size());
    for (const auto& e : group_) points.push_back(e.point);
    mrpt::math::TLine2D line;
    mrpt::math::getRegressionLine(points, line);  // least squares (eigenvectors)
    // the line a x + b y + c = 0: its normal (a, b), turned towards the rays' side
    double nx = line.coefs[0], ny = line.coefs[1];
    const double norm = std::hypot(nx, ny);
    nx /= norm, ny /= norm;
    const double meanRay = std::atan2(sumSin_, sumCos_);
    if (nx * std::cos(meanRay) + ny * std::sin(meanRay) < 0) nx = -nx, ny = -ny;
    const double normal = std::atan2(ny, nx);
    // seed 004 sec. 4.1: every ERP near the line, every ray P_i R_i at a right angle to it
    double residual = 0;
    for (const auto& e : group_) residual = std::max(residual, std::abs(line.distance(e.point)));
    if (residual > options_.maxResidual) {
        ++counts.offLine;
        return std::nullopt;
    }
    for (const auto& e : group_)
        if (std::abs(wrapToPi(e.direction - normal)) > options_.maxRayAngle) {
            ++counts.notPerpendicular;
            return std::nullopt;
        }
    // the ends: the extreme ERPs projected on the line
    const TPoint2D along(-ny, nx);
    double lo = INFINITY, hi = -INFINITY;
    const TPoint2D origin = group_.front().point;
    for (const auto& e : group_) {
        const double s = (e.point - origin).x * along.x + (e.point - origin).y * along.y;
        lo = std::min(lo, s), hi = std::max(hi, s);
    }
    const double offset = -(line.coefs[0] * origin.x + line.coefs[1] * origin.y + line.coefs[2]) /
                          (norm * norm);  // origin moved onto the line
    const TPoint2D foot = origin + TPoint2D(line.coefs[0] * offset, line.coefs[1] * offset);
    Wall w;
    w.a = foot + along * lo;
    w.b = foot + along * hi;
    w.normal = normal;
    w.residual = residual;
    w.erps = group_.size();
    ++counts.walls;
    return w;
}

void WallDetector::drop() {
    history_.clear();
    group_.clear();
    sumCos_ = sumSin_ = 0;
}

void WallDetector::transform(const mrpt::poses::CPose2D& f) {
    for (auto& h : history_) h.sensor = f + h.sensor;
    for (auto& e : group_) {
        e.sensor = composePoint(f, e.sensor);
        e.point = composePoint(f, e.point);
        e.direction = wrapToPi(e.direction + f.phi());
    }
    sumCos_ = sumSin_ = 0;
    for (const auto& e : group_) sumCos_ += std::cos(e.direction), sumSin_ += std::sin(e.direction);
}

}  // namespace mrloc::framesync
