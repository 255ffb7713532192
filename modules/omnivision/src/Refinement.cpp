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

}  // namespace

RefinedLayout refineLayout(const RefinementProblem& p) {
    const size_t S = p.snapshots.size();
    if (S == 0 || p.initial.size() != S || p.labels.size() != S)
        throw Error("omnivision refinement: one snapshot, labels and initial layout per instant");
    const size_t n = p.snapshots[0].robots();
    if (!p.initial[0][size_t(p.a)] || !p.initial[0][size_t(p.b)])
        throw Error("omnivision refinement: A and B must be placed at the first instant");
    const auto isStationary = [&](int r) {
        return std::find(p.stationary.begin(), p.stationary.end(), r) != p.stationary.end();
    };
    // One pose per (instant, robot), shared across instants by stationary robots.
    std::vector<std::vector<int>> poseOf(S, std::vector<int>(n, -1));
    std::vector<PoseVars> vars;
    std::vector<double> x;
    for (size_t s = 0; s < S; ++s)
        for (size_t r = 0; r < n; ++r) {
            if (!p.initial[s][r]) continue;
            if (s > 0 && isStationary(int(r)) && poseOf[0][r] >= 0) {
                poseOf[s][r] = poseOf[0][r];
                continue;
            }
            poseOf[s][r] = int(vars.size());
            PoseVars v;
            const Vec2 at = *p.initial[s][r];
            const bool isA = int(r) == p.a && (s == 0 || isStationary(p.a));
            const bool isB = int(r) == p.b && (s == 0 || isStationary(p.b));
            if (!isA) v.x = int(x.size()), x.push_back(at.x());
            if (!isA && !isB) v.y = int(x.size()), x.push_back(at.y());
            v.h = int(x.size()), x.push_back(0);
            vars.push_back(v);
        }
    std::vector<Vec2> fixedAt(vars.size());
    for (size_t s = 0; s < S; ++s)
        for (size_t r = 0; r < n; ++r)
            if (poseOf[s][r] >= 0) fixedAt[size_t(poseOf[s][r])] = *p.initial[s][r];
    const auto position = [&](int pose) {
        const auto& v = vars[size_t(pose)];
        Vec2 q = fixedAt[size_t(pose)];
        if (v.x >= 0) q.x() = x[size_t(v.x)];
        if (v.y >= 0) q.y() = x[size_t(v.y)];
        return q;
    };
    struct Bearing {
        int observer, target;
        double z, weight;
    };
    std::vector<Bearing> bearings;
    for (size_t s = 0; s < S; ++s)
        for (size_t o = 0; o < n; ++o) {
            if (poseOf[s][o] < 0) continue;
            const auto& lab = p.labels[s][o];
            for (size_t img = 0; img < lab.size(); ++img) {
                if (lab[img] < 0 || poseOf[s][size_t(lab[img])] < 0) continue;
                const int observer = poseOf[s][o], target = poseOf[s][size_t(lab[img])];
                const bool seen = std::any_of(bearings.begin(), bearings.end(), [&](const auto& b) {
                    return b.observer == observer && b.target == target;
                });
                if (p.stillViewsRepeat && seen) continue;  // both still: the same image again
                const double z = p.snapshots[s].views[o].bearings[img];
                const double sigma = p.bearingSigmaAt ? p.bearingSigmaAt(z) : p.bearingSigma;
                bearings.push_back({observer, target, z, 1.0 / (sigma * sigma)});
            }
        }
    // Initial headings: the circular mean of what each camera's labeled images imply.
    {
        std::vector<double> sx(vars.size(), 0), sy(vars.size(), 0);
        for (const auto& m : bearings) {
            const Vec2 d = position(m.target) - position(m.observer);
            const double h = std::atan2(d.y(), d.x()) - m.z;
            sx[size_t(m.observer)] += std::cos(h), sy[size_t(m.observer)] += std::sin(h);
        }
        for (size_t v = 0; v < vars.size(); ++v) x[size_t(vars[v].h)] = std::atan2(sy[v], sx[v]);
    }
    const auto rows = [&]() {
        std::vector<Row> out;
        for (const auto& m : bearings) {
            const Vec2 po = position(m.observer), pt = position(m.target);
            const Vec2 d = pt - po;
            const double rho2 = d.squaredNorm();
            Row row;
            row.residual = mrpt::math::wrapToPi(std::atan2(d.y(), d.x()) -
                                                x[size_t(vars[size_t(m.observer)].h)] - m.z);
            row.weight = m.weight;
            const double dx = -d.y() / rho2, dy = d.x() / rho2;  // d atan2 / d target
            const auto& vo = vars[size_t(m.observer)];
            const auto& vt = vars[size_t(m.target)];
            if (vt.x >= 0) row.jac.push_back({vt.x, dx});
            if (vt.y >= 0) row.jac.push_back({vt.y, dy});
            if (vo.x >= 0) row.jac.push_back({vo.x, -dx});
            if (vo.y >= 0) row.jac.push_back({vo.y, -dy});
            row.jac.push_back({vo.h, -1});
            out.push_back(std::move(row));
        }
        for (const auto& m : p.distances) {
            const int pi = poseOf[m.si][size_t(m.i)], pj = poseOf[m.sj][size_t(m.j)];
            if (pi < 0 || pj < 0) continue;
            const Vec2 d = position(pj) - position(pi);
            const double len = std::max(d.norm(), 1e-12);
            Row row;
            row.residual = len - m.distance;
            row.weight = 1.0 / (m.sigma * m.sigma);
            const Vec2 u = d / len;
            const auto& vi = vars[size_t(pi)];
            const auto& vj = vars[size_t(pj)];
            if (vj.x >= 0) row.jac.push_back({vj.x, u.x()});
            if (vj.y >= 0) row.jac.push_back({vj.y, u.y()});
            if (vi.x >= 0) row.jac.push_back({vi.x, -u.x()});
            if (vi.y >= 0) row.jac.push_back({vi.y, -u.y()});
            out.push_back(std::move(row));
        }
        return out;
    };
    const size_t dim = x.size();
    Eigen::MatrixXd H(dim, dim);
    RefinedLayout out;
    for (int it = 0; it < 50; ++it) {
        H.setZero();
        Eigen::VectorXd g = Eigen::VectorXd::Zero(Eigen::Index(dim));
        for (const auto& row : rows())
            for (const auto& [a, ja] : row.jac) {
                g[a] += row.weight * ja * row.residual;
                for (const auto& [b, jb] : row.jac) H(a, b) += row.weight * ja * jb;
            }
        Eigen::LDLT<Eigen::MatrixXd> ldlt(H);
        // A rank-deficient system has a pivot at rounding level (1e-16 of the largest);
        // legitimately weak modes (the scale, fixed by one distance) stay far above it.
        if (ldlt.info() != Eigen::Success ||
            !(ldlt.vectorD().minCoeff() > 1e-14 * ldlt.vectorD().maxCoeff()))
            throw Error(
                "omnivision refinement: the layout is not determined (a robot seen by "
                "fewer than two cameras, or no distance to fix the scale)");
        const Eigen::VectorXd step = ldlt.solve(-g);
        for (size_t k = 0; k < dim; ++k) x[k] += step[Eigen::Index(k)];
        out.iterations = it + 1;
        if (step.cwiseAbs().maxCoeff() < 1e-10) break;
    }
    // Covariance at the solution.
    H.setZero();
    for (const auto& row : rows())
        for (const auto& [a, ja] : row.jac)
            for (const auto& [b, jb] : row.jac) H(a, b) += row.weight * ja * jb;
    const Eigen::MatrixXd cov =
        H.ldlt().solve(Eigen::MatrixXd::Identity(Eigen::Index(dim), Eigen::Index(dim)));
    double sumSq = 0;
    for (const auto& m : bearings) {
        const Vec2 d = position(m.target) - position(m.observer);
        sumSq += std::pow(mrpt::math::wrapToPi(std::atan2(d.y(), d.x()) -
                                               x[size_t(vars[size_t(m.observer)].h)] - m.z),
                          2);
    }
    out.bearings = bearings.size();
    out.rmsBearingResidual = bearings.empty() ? 0 : std::sqrt(sumSq / double(bearings.size()));
    out.position.assign(S, std::vector<std::optional<Vec2>>(n));
    out.heading.assign(S, std::vector<std::optional<double>>(n));
    out.covariance.assign(S, std::vector<Eigen::Matrix3d>(n, Eigen::Matrix3d::Zero()));
    for (size_t s = 0; s < S; ++s)
        for (size_t r = 0; r < n; ++r) {
            const int pose = poseOf[s][r];
            if (pose < 0) continue;
            out.position[s][r] = position(pose);
            const auto& v = vars[size_t(pose)];
            out.heading[s][r] = mrpt::math::wrapToPi(x[size_t(v.h)]);
            const int idx[3] = {v.x, v.y, v.h};
            for (int a = 0; a < 3; ++a)
                for (int b = 0; b < 3; ++b)
                    if (idx[a] >= 0 && idx[b] >= 0)
                        out.covariance[s][r](a, b) = cov(idx[a], idx[b]);
        }
    return out;
}

}  // namespace mrloc::omnivision
