#include <mrloc/common/Error.h>
#include <mrloc/common/Rawlog.h>
#include <mrloc/polymap/ScanPolygon.h>
#include <mrpt/core/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace mrloc::polymap {

using common::cross;
using common::dot;

namespace {

struct Line {
    TPoint2D point;  ///< on the line
    TVector2D dir;   ///< unit
};

/** Total least squares over points[a..b] (indices modulo n). */
Line fitLine(const std::vector<TPoint2D>& pts, size_t a, size_t b) {
    const size_t n = pts.size();
    const size_t count = (b + n - a) % n + 1;
    if (count < 3) {
        const TVector2D d = pts[b % n] - pts[a % n];
        return {pts[a % n], d * (1 / std::max(d.norm(), 1e-12))};
    }
    TPoint2D c{0, 0};
    for (size_t k = 0; k < count; ++k) c += pts[(a + k) % n];
    c = c * (1.0 / count);
    Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
    for (size_t k = 0; k < count; ++k) {
        const TVector2D d = pts[(a + k) % n] - c;
        cov += Eigen::Vector2d(d.x, d.y) * Eigen::Vector2d(d.x, d.y).transpose();
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
    const Eigen::Vector2d v = eig.eigenvectors().col(1);  // largest eigenvalue
    TVector2D dir{v.x(), v.y()};
    if (dot(dir, pts[(a + count - 1) % n] - pts[a % n]) < 0) dir = -dir;
    return {c, dir};
}

/** Where the ray from the origin along `ray` meets the line; `fallback` when they are
 *  nearly parallel (a wall seen almost edge-on). */
TPoint2D onRay(const Line& l, const TVector2D& ray, const TPoint2D& fallback) {
    const double denom = cross(ray, l.dir);
    if (std::abs(denom) < std::sin(5 * M_PI / 180)) return ray * fallback.norm();
    return ray * (cross(l.point, l.dir) / denom);
}

TPoint2D intersect(const Line& a, const Line& b, const TPoint2D& fallback) {
    const double denom = cross(a.dir, b.dir);
    if (std::abs(denom) < std::sin(2 * M_PI / 180)) return fallback;
    const double t = cross(b.point - a.point, b.dir) / denom;
    return a.point + a.dir * t;
}

/** Iterative end-point fit of points[a..b]: indices where the run bends. */
void splitRun(const std::vector<TPoint2D>& pts, size_t a, size_t b, double tol,
              std::vector<size_t>& cuts) {
    const size_t n = pts.size();
    const TPoint2D &p = pts[a % n], &q = pts[b % n];
    const TVector2D d = q - p;
    const double len = d.norm();
    double worst = 0;
    size_t at = a;
    for (size_t k = a + 1; k < b; ++k) {
        const double dist =
            len > 0 ? std::abs(cross(d, pts[k % n] - p)) / len : (pts[k % n] - p).norm();
        if (dist > worst) worst = dist, at = k;
    }
    if (worst <= tol) return;
    splitRun(pts, a, at, tol, cuts);
    cuts.push_back(at);
    splitRun(pts, at, b, tol, cuts);
}

}  // namespace

ScanBeams beamsOf(const mrpt::obs::CObservation2DRangeScan& scan, double heading,
                  bool noReturnAllowed) {
    const size_t n = scan.getScanSize();
    const std::string what = "scan '" + scan.sensorLabel + "'";
    if (n < 8) throw Error(what + ": too few beams (" + std::to_string(n) + ")");
    ScanBeams beams;
    beams.step = scan.aperture / double(n - 1);
    if (std::abs(beams.step * n - 2 * M_PI) > 0.5 * beams.step)
        throw Error(what + mrpt::format(": not a full turn (%zu beams over %.2f deg)", n,
                                        scan.aperture * 180 / M_PI));
    const double sign = common::storedFlag(scan.rightToLeft) ? 1 : -1;
    beams.angle.resize(n);
    beams.range.resize(n);
    beams.noReturn.assign(n, false);
    if (noReturnAllowed && !(std::isfinite(scan.maxRange) && scan.maxRange > 0))
        throw Error(what + mrpt::format(": max range is %g", double(scan.maxRange)));
    for (size_t i = 0; i < n; ++i) {
        beams.angle[i] = heading + sign * scan.getScanAngle(i);
        if (!scan.getScanRangeValidity(i)) {
            if (!noReturnAllowed)
                throw Error(what + mrpt::format(": beam %zu has no return; the visibility "
                                                "polygon must be closed (raise the scanner's "
                                                "max range)",
                                                i));
            beams.noReturn[i] = true;
            beams.range[i] = scan.maxRange;
            continue;
        }
        const double r = scan.getScanRange(i);
        if (!std::isfinite(r) || r < 0)
            throw Error(what + mrpt::format(": beam %zu range is %g", i, r));
        beams.range[i] = r;
    }
    return beams;
}

VisibilityPolygon visibilityFromScan(const mrpt::obs::CObservation2DRangeScan& scan, double heading,
                                     const ScanPolygonOptions& o) {
    const ScanBeams beams = beamsOf(scan, heading);
    const std::vector<double>& angle = beams.angle;
    const size_t n = angle.size();
    const double step = beams.step;
    std::vector<TPoint2D> pts(n);
    for (size_t i = 0; i < n; ++i)
        pts[i] = {beams.range[i] * std::cos(angle[i]), beams.range[i] * std::sin(angle[i])};
    // Jumps: the gap to the next beam is larger than a wall at incidence breakAngle gives.
    const double threshold = std::sin(step) / std::sin(o.breakAngle - step);
    std::vector<bool> jumpAfter(n);
    size_t jumps = 0;
    for (size_t i = 0; i < n; ++i) {
        const size_t j = (i + 1) % n;
        const double r = std::min(pts[i].norm(), pts[j].norm());
        // Two noisy ranges differ by sqrt(2) sigma: 8 sigma keeps false jumps below 1e-8.
        jumpAfter[i] = (pts[j] - pts[i]).norm() > r * threshold + 8 * o.rangeSigma;
        jumps += jumpAfter[i];
    }
    const double splitTol = std::max(6 * o.rangeSigma, 0.01);  // max of 1e3 normals < 4.5 sigma
    VisibilityPolygon V;
    V.angularTolerance = 0.5 * step;
    const auto rayAt = [&](double a) { return TVector2D{std::cos(a), std::sin(a)}; };
    // Runs of beams between jumps; with none, the whole turn from the farthest beam (which
    // is a corner) back to itself.
    size_t first = 0;
    if (jumps == 0)
        first = size_t(std::max_element(pts.begin(), pts.end(),
                                        [](auto& a, auto& b) { return a.norm() < b.norm(); }) -
                       pts.begin());
    else
        while (!jumpAfter[(first + n - 1) % n]) ++first;  // a run starts after a jump
    size_t a = first;
    for (size_t covered = 0; covered < n;) {
        size_t b = a;  // last beam of the run, as an unwrapped index
        if (jumps == 0)
            b = a + n;  // closes on its first beam
        else
            while (!jumpAfter[b % n]) ++b;
        std::vector<size_t> cuts{a};
        splitRun(pts, a, b, splitTol, cuts);
        cuts.push_back(b);
        // A wall needs two beams off its corners; shorter pieces are a corner's rounding.
        for (size_t k = 0; k + 1 < cuts.size() && cuts.size() > 2;) {
            if (cuts[k + 1] - cuts[k] >= 3) {
                ++k;
                continue;
            }
            cuts.erase(cuts.begin() + long(k + 2 < cuts.size() ? k + 1 : k));
            if (k > 0) --k;
        }
        // Leave the beams at a corner out of both fits: they straddle two walls.
        const auto fitPiece = [&](size_t k, size_t kEnd) {
            const size_t lo = cuts[k] + (k > 0 ? 1 : 0);
            const size_t hi = cuts[kEnd] - (kEnd + 1 < cuts.size() ? 1 : 0);
            return fitLine(pts, lo, std::max(lo, hi));
        };
        std::vector<Line> walls;
        for (size_t k = 0; k + 1 < cuts.size(); ++k) walls.push_back(fitPiece(k, k + 1));
        // Merge: neighbours on one line (a split by noise) become one wall.
        for (size_t k = 0; k + 1 < walls.size();) {
            if (std::abs(cross(walls[k].dir, walls[k + 1].dir)) > std::sin(o.mergeAngle) ||
                dot(walls[k].dir, walls[k + 1].dir) < 0) {
                ++k;
                continue;
            }
            cuts.erase(cuts.begin() + long(k + 1));
            walls.erase(walls.begin() + long(k + 1));
            walls[k] = fitPiece(k, k + 1);
        }
        if (jumps == 0) {
            // Closed: every cut, including the first beam, is a corner between two walls.
            for (size_t k = 0; k + 1 < cuts.size(); ++k)
                V.vertices.push_back(intersect(walls[(k + walls.size() - 1) % walls.size()],
                                               walls[k], pts[cuts[k] % n]));
            break;
        }
        const double startRay = angle[a % n] - 0.5 * step, endRay = angle[b % n] + 0.5 * step;
        V.vertices.push_back(onRay(walls.front(), rayAt(startRay), pts[a % n]));
        for (size_t k = 1; k + 1 < cuts.size(); ++k)
            V.vertices.push_back(intersect(walls[k - 1], walls[k], pts[cuts[k] % n]));
        V.vertices.push_back(onRay(walls.back(), rayAt(endRay), pts[b % n]));
        covered += b - a + 1;
        a = b + 1;
    }
    return V;
}

}  // namespace mrloc::polymap
