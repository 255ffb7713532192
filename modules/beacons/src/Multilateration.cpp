#include <mrloc/beacons/Multilateration.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>

namespace mrloc::beacons {

using Eigen::Matrix3d;
using Eigen::Vector3d;

const char* toString(FixStatus s) {
    switch (s) {
        case FixStatus::Ok:
            return "ok";
        case FixStatus::InvalidInput:
            return "invalid input (NaN, infinite or negative value)";
        case FixStatus::TooFewRanges:
            return "fewer than 3 ranges";
        case FixStatus::CoincidentBeacons:
            return "the beacons coincide";
        case FixStatus::CollinearBeacons:
            return "the beacons are collinear";
        case FixStatus::IllConditioned:
            return "ill-conditioned geometry (GDOP too large)";
        case FixStatus::AmbiguousMirror:
            return "mirror ambiguity that the rule cannot resolve";
        case FixStatus::NotConverged:
            return "Gauss-Newton did not converge";
    }
    return "?";
}

namespace {

// Eigenvalue ratios below these mark a degenerate spread of beacons.
constexpr double kCollinearRatio = 1e-8;
constexpr double kPlanarRatio = 1e-4;  // out-of-plane spread under 1 % of the in-plane one
constexpr double kCoincident = 1e-12;  // m^2
// The leave-one-out fits robustMultilaterate tries at most: every range of the paper's
// 4 to 8 beacons, the most suspect 12 of a longer observation.
constexpr size_t kLeaveOneOutFits = 12;

/** The problem in coordinates centred on the beacons' centroid (better conditioned).
 *  Nothing is copied: a fix allocates no memory. */
struct Centred {
    const std::vector<RangeMeasurement>& m;
    Vector3d centroid;
    bool planar2d;
    double zKnown;  // 2-D: the receiver's z relative to the centroid

    Vector3d b(size_t i) const { return m[i].beacon - centroid; }
    /** Squared range; in 2-D minus the known vertical offset. */
    double r2(size_t i) const {
        const double dz = planar2d ? zKnown - b(i).z() : 0.0;
        return m[i].range * m[i].range - dz * dz;
    }
};

/** Closed-form start from the differences of eq. (5) against their mean, which removes the
 *  quadratic term: -2 b_i . x = r_i^2 - mean(r^2) - |b_i|^2 + mean(|b|^2). Solved over the
 *  eigenvectors of the scatter S = sum b_i b_i^T whose eigenvalues are not negligible. */
template <int D>
Eigen::Matrix<double, D, 1> linearStart(
    const Centred& c, const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, D, D>>& es,
    int usedDims) {
    double meanR2 = 0, meanB2 = 0;
    const size_t n = c.m.size();
    for (size_t i = 0; i < n; ++i) {
        meanR2 += c.r2(i);
        meanB2 += c.b(i).template head<D>().squaredNorm();
    }
    meanR2 /= double(n);
    meanB2 /= double(n);
    Eigen::Matrix<double, D, 1> v = Eigen::Matrix<double, D, 1>::Zero();
    for (size_t i = 0; i < n; ++i) {
        const Eigen::Matrix<double, D, 1> bi = c.b(i).template head<D>();
        v += -0.5 * bi * (c.r2(i) - meanR2 - bi.squaredNorm() + meanB2);
    }
    Eigen::Matrix<double, D, 1> x = Eigen::Matrix<double, D, 1>::Zero();
    for (int k = D - usedDims; k < D; ++k) {
        const auto e = es.eigenvectors().col(k);
        x += e * (e.dot(v) / es.eigenvalues()(k));
    }
    return x;
}

/** Mean squared distance off the solved subspace: r_i^2 - |x - b_i|^2, averaged. */
double outOfSubspace2(const Centred& c, const Vector3d& x, int dims) {
    double w2 = 0;
    for (size_t i = 0; i < c.m.size(); ++i) {
        const Vector3d d = x - c.b(i);
        w2 += c.r2(i) - (dims == 2 ? d.head<2>().squaredNorm() : d.squaredNorm());
    }
    return std::max(0.0, w2 / double(c.m.size()));
}

/** (H^T H)^-1 of the top-left dims x dims block (zero elsewhere); false if singular. */
bool invertBlock(const Matrix3d& A, int dims, Matrix3d& inv) {
    inv.setZero();
    if (dims == 2) {
        const Eigen::Matrix2d a = A.topLeftCorner<2, 2>();
        const double det = a.determinant();
        if (!(std::abs(det) > 1e-24)) return false;
        inv.topLeftCorner<2, 2>() = a.inverse();
        return true;
    }
    bool invertible = false;
    double det = 0;
    A.computeInverseAndDetWithCheck(inv, det, invertible, 1e-24);
    return invertible;
}

/** Smallest eigenvalue of the dims x dims block of a symmetric matrix. */
double minEigen(const Matrix3d& A, int dims) {
    if (dims == 2) {
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es;
        es.computeDirect(A.topLeftCorner<2, 2>(), Eigen::EigenvaluesOnly);
        return es.eigenvalues()(0);
    }
    Eigen::SelfAdjointEigenSolver<Matrix3d> es;
    es.computeDirect(A, Eigen::EigenvaluesOnly);
    return es.eigenvalues()(0);
}

/** Gauss-Newton, seed 001 eq. (8)-(10): x(k+1) = x(k) - F'(x(k))^* F(x(k)). With J of full
 *  column rank the pseudo-inverse is (J^T J)^-1 J^T, applied through the normal equations. */
/** (rangeSigma / sigma_i)^2 for a range with its own sd, else 1. */
double weightOf(const RangeMeasurement& m, const MultilaterationOptions& o) {
    return m.sigma > 0 ? (o.rangeSigma * o.rangeSigma) / (m.sigma * m.sigma) : 1.0;
}

/** The weighted fix's normal matrices at the solution (multilaterate's loop, each range
 *  weighted by weightOf): H^T W H, J^T W J and J^T W cov(f) W J. */
template <class CentredT>
[[gnu::noinline]] void weightedGeometry(const std::vector<RangeMeasurement>& m, const CentredT& c,
                                        const Vector3d& x, int dims,
                                        const MultilaterationOptions& o, Matrix3d& HtWH,
                                        Matrix3d& JtJ, Matrix3d& JtWJ) {
    HtWH.setZero();
    JtJ.setZero();
    JtWJ.setZero();
    for (size_t i = 0; i < m.size(); ++i) {
        const Vector3d d = x - c.b(i);
        const double n = d.norm();
        Vector3d u = n > 1e-12 ? Vector3d(d / n) : Vector3d::Zero();
        Vector3d g = 2.0 * d;
        if (dims == 2) u.z() = g.z() = 0;
        const double w = weightOf(m[i], o);
        const double si2 = m[i].sigma > 0 ? m[i].sigma * m[i].sigma : o.rangeSigma * o.rangeSigma;
        HtWH += w * u * u.transpose();
        JtJ += w * g * g.transpose();
        JtWJ += g * g.transpose() * (w * w * 4.0 * m[i].range * m[i].range * si2);
    }
}

/** Gauss-Newton on either residual; Weighted: each row by weightOf (ranges with their own
 *  sd). */
template <bool Weighted>
int gaussNewtonLoop(const std::vector<RangeMeasurement>& m, const Vector3d& centroid, Vector3d& x,
                    int dims, const MultilaterationOptions& o, double& lastStep) {
    lastStep = 0;
    for (int it = 1; it <= o.maxIterations; ++it) {
        Matrix3d JtJ = Matrix3d::Zero();
        Vector3d Jtf = Vector3d::Zero();
        for (const auto& mi : m) {
            const Vector3d d = x - (mi.beacon - centroid);
            Vector3d g;
            double f;
            if (o.residual == Residual::SquaredRange) {
                f = d.squaredNorm() - mi.range * mi.range;  // eq. (6)
                g = 2.0 * d;                                // row of eq. (9)
            } else {
                const double n = d.norm();
                if (n < 1e-12) continue;  // at a beacon: the range residual has no gradient
                f = n - mi.range;
                g = d / n;
            }
            if (dims == 2) g.z() = 0;
            if constexpr (Weighted) {
                const double w = weightOf(mi, o);
                JtJ.noalias() += w * g * g.transpose();
                Jtf.noalias() += w * g * f;
            } else {
                JtJ.noalias() += g * g.transpose();
                Jtf.noalias() += g * f;
            }
        }
        Matrix3d inv;
        if (!invertBlock(JtJ, dims, inv)) return -it;  // J lost rank: degenerate geometry
        const Vector3d step = inv * Jtf;
        if (!step.allFinite()) return -it;
        x -= step;  // eq. (10)
        lastStep = step.norm();
        if (lastStep <= o.tolerance * (1.0 + x.norm())) return it;
    }
    return o.maxIterations;
}

/** The weighted loop apart, and never inlined, so that the usual unweighted fix keeps its
 *  code, bit for bit and as fast (inlined, it cost the unweighted fixes 5-9 % in
 *  bench_multilateration). */
[[gnu::noinline]] int weightedGaussNewton(const std::vector<RangeMeasurement>& m,
                                          const Vector3d& centroid, Vector3d& x, int dims,
                                          const MultilaterationOptions& o, double& lastStep) {
    return gaussNewtonLoop<true>(m, centroid, x, dims, o, lastStep);
}

bool finite(const RangeMeasurement& m) {
    return m.beacon.allFinite() && std::isfinite(m.range) && m.range >= 0;
}

/** The linear start (centred coordinates) and whether the beacons leave a mirror image. */
struct Start {
    Vector3d x = Vector3d::Zero();
    Vector3d normal = Vector3d::Zero();  // of the mirror plane (3-D) or line (2-D)
    bool mirrored = false;
    FixStatus refused = FixStatus::Ok;  ///< not Ok: the beacons' layout gives no fix
};

/** The linear start from the beacons' scatter S: 2-D with the height known, else 3-D;
 *  refuses coincident beacons, and collinear ones in 3-D. */
Start linearStartOf(const Centred& c, bool planar2d) {
    Start s;
    const size_t count = c.m.size();
    if (planar2d) {
        Eigen::Matrix2d S = Eigen::Matrix2d::Zero();
        for (size_t i = 0; i < count; ++i) {
            const Eigen::Vector2d b = c.b(i).head<2>();
            S += b * b.transpose();
        }
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es;
        es.computeDirect(S);
        if (es.eigenvalues()(1) < kCoincident) {
            s.refused = FixStatus::CoincidentBeacons;
            return s;
        }
        s.mirrored = es.eigenvalues()(0) < kPlanarRatio * es.eigenvalues()(1);
        s.x.head<2>() = linearStart<2>(c, es, s.mirrored ? 1 : 2);
        if (s.mirrored) s.normal.head<2>() = es.eigenvectors().col(0);
        return s;
    }
    Matrix3d S = Matrix3d::Zero();
    for (size_t i = 0; i < count; ++i) {
        const Vector3d b = c.b(i);
        S += b * b.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Matrix3d> es;
    es.computeDirect(S);
    const Vector3d& ev = es.eigenvalues();
    if (ev(2) < kCoincident) {
        s.refused = FixStatus::CoincidentBeacons;
        return s;
    }
    if (ev(1) < kCollinearRatio * ev(2)) {
        s.refused = FixStatus::CollinearBeacons;  // any rotation about the line fits
        return s;
    }
    s.mirrored = ev(0) < kPlanarRatio * ev(2);
    s.x = linearStart<3>(c, es, s.mirrored ? 2 : 3);
    if (s.mirrored) s.normal = es.eigenvectors().col(0);
    return s;
}

/** All beacons in one plane (3-D) or on one line (2-D): x and its mirror image fit the
 *  ranges equally well. Places the start on the side the rule asks for; false when the rule
 *  needs a hint and none is given. */
bool chooseMirrorSide(const Centred& c, int dims, const MultilaterationOptions& o, Start& s) {
    const double w = std::sqrt(outOfSubspace2(c, s.x, dims));
    const Vector3d a = s.x + w * s.normal, b = s.x - w * s.normal;
    const Vector3d hint = o.hint ? Vector3d(*o.hint - c.centroid) : Vector3d::Zero();
    const bool useHint =
        o.mirror == MirrorRule::NearestToHint || c.planar2d || std::abs(s.normal.z()) < 0.1;
    if (useHint && !o.hint) return false;
    if (useHint)
        s.x = (a - hint).squaredNorm() <= (b - hint).squaredNorm() ? a : b;
    else
        s.x = (o.mirror == MirrorRule::Below) == (a.z() < b.z()) ? a : b;
    return true;
}

/** The geometry at the solution x: H has the unit line-of-sight vectors as rows; J is the
 *  squared-range residual's Jacobian, with its covariance. */
struct Geometry {
    Matrix3d HtH = Matrix3d::Zero(), HtWH = Matrix3d::Zero();  // geometry; weighted
    Matrix3d JtJ = Matrix3d::Zero(), JtWJ = Matrix3d::Zero();  // squared-range covariance
    double sumRes2 = 0;
};

Geometry geometryAt(const std::vector<RangeMeasurement>& m, const Centred& c, const Vector3d& x,
                    int dims, const MultilaterationOptions& o, bool weighted) {
    Geometry g;
    const double s2 = o.rangeSigma * o.rangeSigma;
    for (size_t i = 0; i < m.size(); ++i) {
        const Vector3d d = x - c.b(i);
        const double n = d.norm();
        g.sumRes2 += (n - m[i].range) * (n - m[i].range);
        Vector3d u = n > 1e-12 ? Vector3d(d / n) : Vector3d::Zero();
        Vector3d grad = 2.0 * d;
        if (dims == 2) u.z() = grad.z() = 0;
        g.HtH += u * u.transpose();
        g.JtJ += grad * grad.transpose();
        // f_i = |x - x_i|^2 - r_i^2 moves by 2 r_i dr_i for a range error dr_i.
        g.JtWJ += grad * grad.transpose() * (4.0 * m[i].range * m[i].range * s2);
    }
    if (weighted) weightedGeometry(m, c, x, dims, o, g.HtWH, g.JtJ, g.JtWJ);
    return g;
}

/** The fix's GDOP and covariance from the geometry; false when they cannot be had (the
 *  geometry is singular: ill-conditioned). */
bool covarianceOf(const Geometry& g, int dims, const MultilaterationOptions& o, bool weighted,
                  Fix& fix) {
    Matrix3d G;
    if (!(minEigen(g.HtH, dims) > 1e-12) || !invertBlock(g.HtH, dims, G)) {
        fix.gdop = std::numeric_limits<double>::infinity();
        return false;
    }
    fix.gdop = std::sqrt(G.trace());
    const double s2 = o.rangeSigma * o.rangeSigma;
    if (o.residual == Residual::Range) {
        Matrix3d Gw = G;  // (sum u u^T / sigma_i^2)^-1 = s2 (H^T W H)^-1
        if (weighted && !invertBlock(g.HtWH, dims, Gw)) return false;
        fix.covariance = s2 * Gw;
        return true;
    }
    // First-order propagation through the pseudo-inverse of eq. (10): J^+ cov(f) J^+^T.
    Matrix3d Ai;
    if (!invertBlock(g.JtJ, dims, Ai)) return false;
    fix.covariance = Ai * g.JtWJ * Ai;
    return true;
}

}  // namespace

Fix multilaterate(const std::vector<RangeMeasurement>& m, const MultilaterationOptions& o) {
    Fix fix;
    for (const auto& mi : m)
        if (!finite(mi)) return fix;  // InvalidInput
    if (o.knownHeight && !std::isfinite(*o.knownHeight)) return fix;
    if (m.size() < 3) {
        fix.status = FixStatus::TooFewRanges;
        return fix;
    }
    const bool planar2d = o.knownHeight.has_value();
    const int dims = planar2d ? 2 : 3;

    Vector3d centroid = Vector3d::Zero();
    for (const auto& mi : m) centroid += mi.beacon;
    centroid /= double(m.size());
    const Centred c{m, centroid, planar2d, planar2d ? *o.knownHeight - centroid.z() : 0.0};

    Start start = linearStartOf(c, planar2d);
    if (start.refused != FixStatus::Ok) {
        fix.status = start.refused;
        return fix;
    }
    if (start.mirrored && !chooseMirrorSide(c, dims, o, start)) {
        fix.status = planar2d ? FixStatus::CollinearBeacons : FixStatus::AmbiguousMirror;
        return fix;
    }
    Vector3d x = start.x;
    if (planar2d) x.z() = c.zKnown;

    double lastStep = 0;
    const bool weighted =
        std::any_of(m.begin(), m.end(), [](const auto& r) { return r.sigma > 0; });
    fix.iterations = weighted ? weightedGaussNewton(m, c.centroid, x, dims, o, lastStep)
                              : gaussNewtonLoop<false>(m, c.centroid, x, dims, o, lastStep);
    if (fix.iterations < 0 || !x.allFinite()) {
        fix.iterations = std::abs(fix.iterations);
        fix.status = FixStatus::IllConditioned;
        return fix;
    }

    const Geometry g = geometryAt(m, c, x, dims, o, weighted);
    fix.position = x + c.centroid;
    fix.rmsResidual = std::sqrt(g.sumRes2 / double(m.size()));
    if (start.mirrored) {
        const Vector3d mirror = x - 2.0 * x.dot(start.normal) * start.normal;
        fix.mirrorAmbiguous = (mirror - x).norm() > 1e-9;
        fix.mirrorPosition = mirror + c.centroid;
    }
    if (!covarianceOf(g, dims, o, weighted, fix) || fix.gdop > o.maxGdop)
        fix.status = FixStatus::IllConditioned;
    else if (lastStep > 1e-6 * (1.0 + x.norm()))
        fix.status = FixStatus::NotConverged;
    else
        fix.status = FixStatus::Ok;
    return fix;
}

Fix robustMultilaterate(const std::vector<RangeMeasurement>& m, const MultilaterationOptions& o,
                        double outlierThreshold, int* rejectedIndex) {
    if (rejectedIndex) *rejectedIndex = -1;
    Fix all = multilaterate(m, o);
    const size_t minLeft = o.knownHeight ? 3 : 4;  // one spare range to tell who is wrong
    if ((all.ok() && all.rmsResidual <= outlierThreshold) || m.size() < minLeft + 1) return all;
    // Which ranges to try leaving out: every one while that is a few fits; beyond, the
    // kLeaveOneOutFits whose removal the linearised fit says shrinks the squared residuals
    // most, r_i^2 / (1 - h_ii) at the all-ranges solution (h_ii the hat matrix's diagonal,
    // u_i^T (H^T H)^-1 u_i), so that a log with thousands of ranges in one observation costs
    // O(n log n), not n fits of n ranges (issue 26).
    std::vector<size_t> skips(m.size());
    for (size_t i = 0; i < m.size(); ++i) skips[i] = i;
    if (m.size() > kLeaveOneOutFits) {
        if (all.position.allFinite() && all.status != FixStatus::InvalidInput &&
            all.status != FixStatus::TooFewRanges && all.status != FixStatus::CoincidentBeacons &&
            all.status != FixStatus::CollinearBeacons && all.status != FixStatus::AmbiguousMirror) {
            const int dims = o.knownHeight ? 2 : 3;
            Vector3d x = all.position;
            if (o.knownHeight) x.z() = *o.knownHeight;
            std::vector<Vector3d> u(m.size());
            Matrix3d HtH = Matrix3d::Zero();
            for (size_t i = 0; i < m.size(); ++i) {
                const Vector3d d = x - m[i].beacon;
                u[i] = d.norm() > 1e-12 ? Vector3d(d / d.norm()) : Vector3d::Zero();
                if (dims == 2) u[i].z() = 0;
                HtH += u[i] * u[i].transpose();
            }
            Matrix3d G;
            if (!invertBlock(HtH, dims, G)) return all;
            std::vector<double> drop(m.size());
            for (size_t i = 0; i < m.size(); ++i) {
                const double r = (x - m[i].beacon).norm() - m[i].range;
                const double h = std::min(u[i].dot(G * u[i]), 1.0 - 1e-9);
                drop[i] = r * r / (1.0 - h);
            }
            std::partial_sort(
                skips.begin(), skips.begin() + kLeaveOneOutFits, skips.end(),
                [&](size_t a, size_t b) { return drop[a] != drop[b] ? drop[a] > drop[b] : a < b; });
            skips.resize(kLeaveOneOutFits);
            std::sort(skips.begin(), skips.end());
        } else {
            return all;  // no solution to rank the ranges by
        }
    }
    Fix best;
    int bestIndex = -1;
    std::vector<RangeMeasurement> subset;
    for (const size_t skip : skips) {
        subset.clear();
        for (size_t i = 0; i < m.size(); ++i)
            if (i != skip) subset.push_back(m[i]);
        Fix f = multilaterate(subset, o);
        if (f.ok() && (bestIndex < 0 || f.rmsResidual < best.rmsResidual)) {
            best = f;
            bestIndex = int(skip);
        }
    }
    if (bestIndex < 0 || best.rmsResidual > outlierThreshold) return all;
    if (rejectedIndex) *rejectedIndex = bestIndex;
    return best;
}

double cramerRaoBound(const std::vector<Vector3d>& beacons, const Vector3d& truth, double sigma,
                      bool knownHeight) {
    const int dims = knownHeight ? 2 : 3;
    Eigen::MatrixXd HtH = Eigen::MatrixXd::Zero(dims, dims);
    for (const auto& b : beacons) {
        const Vector3d u = (truth - b).normalized();
        HtH += u.head(dims) * u.head(dims).transpose();
    }
    return sigma * std::sqrt(HtH.inverse().trace());
}

}  // namespace mrloc::beacons
