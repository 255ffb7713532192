#pragma once
// A uniform random point inside a polygon (rejection from its box): the polymap tests' query
// points.
#include <mrloc/common/Polygon.h>
#include <mrpt/random/RandomGenerators.h>

namespace mrloc::test {

inline common::TPoint2D randomInside(const common::Polygon& P,
                                     mrpt::random::CRandomGenerator& rng) {
    for (;;) {
        const common::TPoint2D p{rng.drawUniform(P.min().x, P.max().x),
                                 rng.drawUniform(P.min().y, P.max().y)};
        if (P.locate(p) == common::Polygon::Where::Inside) return p;
    }
}

}  // namespace mrloc::test
