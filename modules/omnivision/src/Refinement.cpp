#include <mrloc/common/Error.h>
#include <mrloc/omnivision/Refinement.h>
#include <mrpt/math/wrap2pi.h>

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace mrloc::omnivision {

namespace {

/** Indices of one pose's unknowns in the state vector (-1: fixed by the gauge). */
struct PoseVars {
    int x = -1, y = -1, h = -1;
};

struct Row {
    double residual = 0, weight = 0;
    std::vector<std::pair<int, double>> jac;  ///< (variable, derivative)
};

struct LabelledBearing {
    int observer, target;  ///< poses
    double z, weight;
};

/** The least-squares problem of a refinement: one pose per (instant, robot), shared across
 *  instants by stationary robots; the gauge fixes A's position and B's y at the first
 *  instant; its rows are the labelled bearings and the known distances. */
class LayoutProblem {
 public:
    explicit LayoutProblem(const RefinementProblem& p) : p_(p) {
        S_ = p.snapshots.size();
        n_ = p.snapshots[0].robots();
        placePoses();
        collectBearings();
        initialHeadings();
    }

    /** Gauss-Newton on the normal equations, at most 50 steps; throws when the layout is
     *  not determined. Returns the iterations. */
    int solve() {
        const size_t dim = x_.size();
        Eigen::MatrixXd H(dim, dim);
        int iterations = 0;
        for (int it = 0; it < 50; ++it) {
            Eigen::VectorXd g = Eigen::VectorXd::Zero(Eigen::Index(dim));
            normalEquations(H, &g);
            Eigen::LDLT<Eigen::MatrixXd> ldlt(H);
            // A rank-deficient system has a pivot at rounding level (1e-16 of the largest);
            // legitimately weak modes (the scale, fixed by one distance) stay far above it.
            if (ldlt.info() != Eigen::Success ||
                !(ldlt.vectorD().minCoeff() > 1e-14 * ldlt.vectorD().maxCoeff()))
                throw Error(
                    "omnivision refinement: the layout is not determined (a robot seen by "
                    "fewer than two cameras, or no distance to fix the scale)");
            const Eigen::VectorXd step = ldlt.solve(-g);
            for (size_t k = 0; k < dim; ++k) x_[k] += step[Eigen::Index(k)];
            iterations = it + 1;
            if (step.cwiseAbs().maxCoeff() < 1e-10) break;
        }
        return iterations;
    }

    /** The solution: poses, headings, their covariance (H^-1 at the solution) and the
     *  bearings' RMS residual. */
    void writeSolution(RefinedLayout& out) const {
        const size_t dim = x_.size();
        Eigen::MatrixXd H(dim, dim);
        normalEquations(H, nullptr);
        const Eigen::MatrixXd cov =
            H.ldlt().solve(Eigen::MatrixXd::Identity(Eigen::Index(dim), Eigen::Index(dim)));
        double sumSq = 0;
        for (const auto& m : bearings_) sumSq += std::pow(bearingResidual(m), 2);
        out.bearings = bearings_.size();
        out.rmsBearingResidual =
            bearings_.empty() ? 0 : std::sqrt(sumSq / double(bearings_.size()));
        out.position.assign(S_, std::vector<std::optional<Vec2>>(n_));
        out.heading.assign(S_, std::vector<std::optional<double>>(n_));
        out.covariance.assign(S_, std::vector<Eigen::Matrix3d>(n_, Eigen::Matrix3d::Zero()));
        for (size_t s = 0; s < S_; ++s)
            for (size_t r = 0; r < n_; ++r) {
                const int pose = poseOf_[s][r];
                if (pose < 0) continue;
                out.position[s][r] = position(pose);
                const auto& v = vars_[size_t(pose)];
                out.heading[s][r] = mrpt::math::wrapToPi(x_[size_t(v.h)]);
                const int idx[3] = {v.x, v.y, v.h};
                for (int a = 0; a < 3; ++a)
                    for (int b = 0; b < 3; ++b)
                        if (idx[a] >= 0 && idx[b] >= 0)
                            out.covariance[s][r](a, b) = cov(idx[a], idx[b]);
            }
    }

 private:
    bool isStationary(int r) const {
        return std::find(p_.stationary.begin(), p_.stationary.end(), r) != p_.stationary.end();
    }

    /** The state vector: each pose's unknowns, with the gauge's left out. */
    void placePoses() {
        poseOf_.assign(S_, std::vector<int>(n_, -1));
        for (size_t s = 0; s < S_; ++s)
            for (size_t r = 0; r < n_; ++r) {
                if (!p_.initial[s][r]) continue;
                if (s > 0 && isStationary(int(r)) && poseOf_[0][r] >= 0) {
                    poseOf_[s][r] = poseOf_[0][r];
                    continue;
                }
                poseOf_[s][r] = int(vars_.size());
                PoseVars v;
                const Vec2 at = *p_.initial[s][r];
                const bool isA = int(r) == p_.a && (s == 0 || isStationary(p_.a));
                const bool isB = int(r) == p_.b && (s == 0 || isStationary(p_.b));
                if (!isA) v.x = int(x_.size()), x_.push_back(at.x());
                if (!isA && !isB) v.y = int(x_.size()), x_.push_back(at.y());
                v.h = int(x_.size()), x_.push_back(0);
                vars_.push_back(v);
            }
        fixedAt_.resize(vars_.size());
        for (size_t s = 0; s < S_; ++s)
            for (size_t r = 0; r < n_; ++r)
                if (poseOf_[s][r] >= 0) fixedAt_[size_t(poseOf_[s][r])] = *p_.initial[s][r];
    }

    Vec2 position(int pose) const {
        const auto& v = vars_[size_t(pose)];
        Vec2 q = fixedAt_[size_t(pose)];
        if (v.x >= 0) q.x() = x_[size_t(v.x)];
        if (v.y >= 0) q.y() = x_[size_t(v.y)];
        return q;
    }

    /** Every labelled image between two placed poses, weighted by its bearing's sd. */
    void collectBearings() {
        for (size_t s = 0; s < S_; ++s)
            for (size_t o = 0; o < n_; ++o) {
                if (poseOf_[s][o] < 0) continue;
                const auto& lab = p_.labels[s][o];
                for (size_t img = 0; img < lab.size(); ++img) {
                    if (lab[img] < 0 || poseOf_[s][size_t(lab[img])] < 0) continue;
                    const int observer = poseOf_[s][o], target = poseOf_[s][size_t(lab[img])];
                    const bool seen =
                        std::any_of(bearings_.begin(), bearings_.end(), [&](const auto& b) {
                            return b.observer == observer && b.target == target;
                        });
                    if (p_.stillViewsRepeat && seen) continue;  // both still: the same image
                    const double z = p_.snapshots[s].views[o].bearings[img];
                    const double sigma = p_.bearingSigmaAt ? p_.bearingSigmaAt(z) : p_.bearingSigma;
                    bearings_.push_back({observer, target, z, 1.0 / (sigma * sigma)});
                }
            }
    }

    /** Initial headings: the circular mean of what each camera's labelled images imply. */
    void initialHeadings() {
        std::vector<double> sx(vars_.size(), 0), sy(vars_.size(), 0);
        for (const auto& m : bearings_) {
            const Vec2 d = position(m.target) - position(m.observer);
            const double h = std::atan2(d.y(), d.x()) - m.z;
            sx[size_t(m.observer)] += std::cos(h), sy[size_t(m.observer)] += std::sin(h);
        }
        for (size_t v = 0; v < vars_.size(); ++v) x_[size_t(vars_[v].h)] = std::atan2(sy[v], sx[v]);
    }

    double bearingResidual(const LabelledBearing& m) const {
        const Vec2 d = position(m.target) - position(m.observer);
        return mrpt::math::wrapToPi(std::atan2(d.y(), d.x()) -
                                    x_[size_t(vars_[size_t(m.observer)].h)] - m.z);
    }

    /** The residual rows at the current state: bearings, then distances. */
    std::vector<Row> rows() const {
        std::vector<Row> out;
        for (const auto& m : bearings_) {
            const Vec2 d = position(m.target) - position(m.observer);
            const double rho2 = d.squaredNorm();
            Row row;
            row.residual = bearingResidual(m);
            row.weight = m.weight;
            const double dx = -d.y() / rho2, dy = d.x() / rho2;  // d atan2 / d target
            const auto& vo = vars_[size_t(m.observer)];
            const auto& vt = vars_[size_t(m.target)];
            if (vt.x >= 0) row.jac.push_back({vt.x, dx});
            if (vt.y >= 0) row.jac.push_back({vt.y, dy});
            if (vo.x >= 0) row.jac.push_back({vo.x, -dx});
            if (vo.y >= 0) row.jac.push_back({vo.y, -dy});
            row.jac.push_back({vo.h, -1});
            out.push_back(std::move(row));
        }
        for (const auto& m : p_.distances) {
            const int pi = poseOf_[m.si][size_t(m.i)], pj = poseOf_[m.sj][size_t(m.j)];
            if (pi < 0 || pj < 0) continue;
            const Vec2 d = position(pj) - position(pi);
            const double len = std::max(d.norm(), 1e-12);
            Row row;
            row.residual = len - m.distance;
            row.weight = 1.0 / (m.sigma * m.sigma);
            const Vec2 u = d / len;
            const auto& vi = vars_[size_t(pi)];
            const auto& vj = vars_[size_t(pj)];
            if (vj.x >= 0) row.jac.push_back({vj.x, u.x()});
            if (vj.y >= 0) row.jac.push_back({vj.y, u.y()});
            if (vi.x >= 0) row.jac.push_back({vi.x, -u.x()});
            if (vi.y >= 0) row.jac.push_back({vi.y, -u.y()});
            out.push_back(std::move(row));
        }
        return out;
    }

    /** H = J^T W J and, when asked, g = J^T W r at the current state. */
    void normalEquations(Eigen::MatrixXd& H, Eigen::VectorXd* g) const {
        H.setZero();
        for (const auto& row : rows())
            for (const auto& [a, ja] : row.jac) {
                if (g) (*g)[a] += row.weight * ja * row.residual;
                for (const auto& [b, jb] : row.jac) H(a, b) += row.weight * ja * jb;
            }
    }

    const RefinementProblem& p_;
    size_t S_ = 0, n_ = 0;
    std::vector<std::vector<int>> poseOf_;  ///< [instant][robot]: its pose, -1 if unplaced
    std::vector<PoseVars> vars_;
    std::vector<Vec2> fixedAt_;  ///< each pose's initial position (its fixed coordinates)
    std::vector<double> x_;      ///< the state
    std::vector<LabelledBearing> bearings_;
};

}  // namespace

RefinedLayout refineLayout(const RefinementProblem& p) {
    const size_t S = p.snapshots.size();
    if (S == 0 || p.initial.size() != S || p.labels.size() != S)
        throw Error("omnivision refinement: one snapshot, labels and initial layout per instant");
    if (!p.initial[0][size_t(p.a)] || !p.initial[0][size_t(p.b)])
        throw Error("omnivision refinement: A and B must be placed at the first instant");
    LayoutProblem problem(p);
    RefinedLayout out;
    out.iterations = problem.solve();
    problem.writeSolution(out);
    return out;
}

}  // namespace mrloc::omnivision
