#include <mrloc/logimport/Unicycle.h>

#include <cmath>

namespace mrloc::logimport {

mrpt::poses::CPose2D moveArc(const mrpt::poses::CPose2D& from, double v, double vy, double w,
                             double dt) {
    const double a = w * dt;
    // the increment in the start's frame: a constant body twist (v, vy, w) over dt; the
    // series below keeps it exact as a -> 0 (straight motion)
    double s, c;  // sin(a)/a and (1 - cos(a))/a
    if (std::abs(a) < 1e-6) {
        s = 1 - a * a / 6;
        c = a / 2;
    } else {
        s = std::sin(a) / a;
        c = (1 - std::cos(a)) / a;
    }
    const double dx = (v * s - vy * c) * dt;
    const double dy = (v * c + vy * s) * dt;
    return from + mrpt::poses::CPose2D(dx, dy, a);
}

}  // namespace mrloc::logimport
