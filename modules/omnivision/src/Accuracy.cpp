#include <mrloc/common/Error.h>
#include <mrloc/common/Metrics.h>
#include <mrloc/common/Progress.h>
#include <mrloc/omnivision/Accuracy.h>
#include <mrloc/omnivision/Refinement.h>
#include <mrloc/omnivision/RelativeLocation.h>
#include <mrpt/random/RandomGenerators.h>

#include <algorithm>
#include <cmath>

namespace mrloc::omnivision {

namespace {

Snapshot noisyViews(const std::vector<mrpt::poses::CPose2D>& poses,
                    const std::vector<std::vector<int>>& seen, double sigma,
                    mrpt::random::CRandomGenerator& rng) {
    Snapshot s;
    for (size_t o = 0; o < poses.size(); ++o) {
        std::vector<double> b;
        for (int r : seen[o])
            b.push_back(std::atan2(poses[size_t(r)].y() - poses[o].y(),
                                   poses[size_t(r)].x() - poses[o].x()) -
                        poses[o].phi() + rng.drawGaussian1D(0, sigma));
        s.views.push_back(makeView(b, "accuracy sweep"));
    }
    return s;
}

}  // namespace

std::vector<AccuracyPoint> accuracySweep(const AccuracyLayout& truth, int trials,
                                         unsigned long seed, const common::Log& log) {
    mrpt::random::CRandomGenerator rng(static_cast<uint32_t>(seed));
    std::vector<AccuracyPoint> levels;
    for (double a : {0.05, 0.1, 0.5}) levels.push_back({"angle", a, 0.01});
    for (double d : {0.0, 0.01, 0.02, 0.05}) levels.push_back({"distance", 0.1, d});
    const size_t n = truth.after.size();
    const auto trueDistance = [&](size_t i, size_t j) {
        return std::hypot(truth.after[i].x() - truth.after[j].x(),
                          truth.after[i].y() - truth.after[j].y());
    };
    common::Progress progress("omnivision accuracy sweep", levels.size() * size_t(trials), log);
    size_t done = 0;
    for (auto& level : levels) {
        const double sigma = level.angleSigmaDeg * M_PI / 180;
        SearchOptions o;
        o.sumTolerance = 6 * sigma;
        o.bearingTolerance = 4 * sigma;
        double paperSum = 0, refinedSum = 0;
        for (int t = 0; t < trials; ++t) {
            progress.update(done++);
            try {
                const auto se = noisyViews(truth.after, truth.seenAfter, sigma, rng);
                const auto ie = identify(se, o);
                RefinementProblem p;
                Solution paper;
                p.bearingSigma = sigma;
                p.a = truth.a, p.b = truth.b;
                if (truth.proposed) {
                    const auto sb = noisyViews(truth.before, truth.seenBefore, sigma, rng);
                    const auto ib = identify(sb, o);
                    std::vector<double> travelled(n);
                    for (size_t r = 0; r < n; ++r)
                        travelled[r] = std::hypot(truth.after[r].x() - truth.before[r].x(),
                                                  truth.after[r].y() - truth.before[r].y()) *
                                       (1 + rng.drawGaussian1D(0, level.distanceSigma));
                    const auto prop = proposedMethod(sb, ib, se, ie, truth.a, truth.b, travelled);
                    paper = prop.after;
                    p.snapshots = {sb, se};
                    p.labels = {ib.labels, ie.labels};
                    p.initial = {prop.before.position, prop.after.position};
                    p.stationary = {truth.a, truth.b};
                    for (size_t r = 0; r < n; ++r)
                        if (travelled[r] > 0 && prop.before.position[r] && prop.after.position[r])
                            p.distances.push_back(
                                {0, int(r), 1, int(r), travelled[r],
                                 std::max(1e-4, level.distanceSigma) * travelled[r]});
                } else {
                    const double d = trueDistance(size_t(truth.a), size_t(truth.b)) *
                                     (1 + rng.drawGaussian1D(0, level.distanceSigma));
                    paper = conventionalMethod(se, ie, truth.a, truth.b, d);
                    p.snapshots = {se};
                    p.labels = {ie.labels};
                    p.initial = {paper.position};
                    p.distances.push_back(
                        {0, truth.a, 0, truth.b, d, std::max(1e-4, level.distanceSigma) * d});
                }
                const auto fit = refineLayout(p);
                const auto& refined = fit.position.back();
                std::vector<double> ep, er;
                for (const auto& [e, d] : paper.distance) {
                    const double truth = trueDistance(size_t(e.first), size_t(e.second));
                    ep.push_back(std::abs(d - truth) / truth);
                    const auto &pi = refined[size_t(e.first)], &pj = refined[size_t(e.second)];
                    if (pi && pj) er.push_back(std::abs((*pi - *pj).norm() - truth) / truth);
                }
                paperSum += common::percentile(ep, 50);
                refinedSum += common::percentile(er, 50);
                ++level.trials;
            } catch (const Error&) {
                ++level.failures;  // identification or geometry failed at this noise
            }
        }
        if (level.trials > 0) {
            level.paper = paperSum / level.trials;
            level.refined = refinedSum / level.trials;
        }
    }
    return levels;
}

}  // namespace mrloc::omnivision
