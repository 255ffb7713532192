#include <mrloc/common/ExactPredicates.h>
#include <mrloc/polymap/ViewComparison.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace mrloc::polymap {

bool wellConditioned(const VisibilityPolygon& V, double clearance) {
    const size_t n = V.size();
    for (size_t i = 0; i < n; ++i) {
        if (V.isRadial(i)) continue;  // a window: not a wall
        const TPoint2D &a = V.vertices[i], &b = V.vertices[(i + 1) % n];
        const TVector2D ab = b - a;
        const double length = ab.norm();
        if (length == 0 || std::abs(common::cross(a, b)) / length >= clearance) continue;
        const double foot = -common::dot(a, ab) / (length * length);  // viewpoint's foot
        if (foot < 0 || foot > 1) return false;
    }
    return true;
}

double radialMismatch(const RadialProfile& V, double angle, double range, double step,
                      double tolerance) {
    const auto off = [&](double d) { return std::abs(range - V.radius(angle + d)); };
    const double e = off(0);
    return e > tolerance ? std::min({e, off(-0.5 * step), off(0.5 * step)}) : e;
}

double beamMismatch(const ScanBeams& beams, const VisibilityPolygon& V, double quantile) {
    const RadialProfile profile(V);
    std::vector<double> error(beams.range.size());
    for (size_t b = 0; b < error.size(); ++b)
        error[b] = beams.noReturn[b]
                       ? std::max(0.0, beams.range[b] - profile.radius(beams.angle[b]))
                       : radialMismatch(profile, beams.angle[b], beams.range[b], beams.step, 0);
    if (error.empty()) return 0;
    const size_t k = std::min(error.size() - 1, size_t(quantile * double(error.size())));
    std::nth_element(error.begin(), error.begin() + long(k), error.end());
    return error[k];
}

bool beamsTellApart(const VisibilityPolygon& a, const VisibilityPolygon& b, int beams,
                    double margin, double maxRange) {
    const double step = 2 * M_PI / beams;
    const RadialProfile pa(a), pb(b);
    int differ = 0;
    for (int k = 0; k < beams; ++k) {
        const double t = k * step, ra = pa.radius(t);
        const bool beyond = ra >= maxRange && pb.radius(t) >= maxRange;
        differ += !beyond && radialMismatch(pb, t, ra, step, margin) > margin;
        if (differ * 50 > beams) return true;
    }
    return false;
}

}  // namespace mrloc::polymap
