#include <mrloc/common/Error.h>
#include <mrloc/omnivision/Snapshot.h>
#include <mrpt/math/wrap2pi.h>

#include <algorithm>
#include <cmath>

namespace mrloc::omnivision {

View makeView(std::vector<double> bearings, const std::string& what) {
    for (auto& b : bearings) {
        if (!std::isfinite(b)) throw Error(what + ": a bearing is not a finite number");
        b = mrpt::math::wrapToPi(b);
        if (b >= M_PI) b -= 2 * M_PI;
    }
    std::sort(bearings.begin(), bearings.end());
    return {std::move(bearings)};
}

View viewFromObservation(const mrpt::obs::CObservationBearingRange& obs, const std::string& what) {
    std::vector<double> b;
    for (const auto& m : obs.sensedData) b.push_back(m.yaw);
    return makeView(std::move(b), what);
}

double signedAngle(const View& v, int p, int q) {
    return mrpt::math::wrapToPi(v.bearings[q] - v.bearings[p]);
}

double interiorAngle(const View& v, int p, int q) { return std::abs(signedAngle(v, p, q)); }

std::vector<ImageAngle> anglesOf(const View& v) {
    std::vector<ImageAngle> out;
    const int n = int(v.size());
    out.reserve(size_t(n * (n - 1) / 2));
    for (int p = 0; p < n; ++p)
        for (int q = p + 1; q < n; ++q) out.push_back({p, q, interiorAngle(v, p, q)});
    return out;
}

}  // namespace mrloc::omnivision
