// The sensed visibility polygon from a simulated 360-degree scan, and hypothesis generation
// from it under range noise: H must not change.
#include <gtest/gtest.h>
#include <mrloc/common/Error.h>
#include <mrloc/polymap/Hypotheses.h>
#include <mrloc/polymap/MapGenerators.h>
#include <mrloc/polymap/ScanPolygon.h>
#include <mrloc/sim/Scanner.h>

using namespace mrloc;
using common::TPoint2D;

namespace {

polymap::VisibilityPolygon sense(const common::Polygon& P, const TPoint2D& at, double heading,
                                 const sim::ScannerOptions& s,
                                 mrpt::random::CRandomGenerator& rng) {
    const auto scan = sim::scanFloorPlan(P, {at.x, at.y, heading}, s, rng);
    polymap::ScanPolygonOptions o;
    o.rangeSigma = s.rangeSigma;
    return polymap::visibilityFromScan(*scan, heading, o);
}

/** H from a noisy scan at each site equals the sites, each within `tolerance`. */
void expectSameHypotheses(const polymap::GeneratedMap& map, double sigma, double tolerance,
                          unsigned seed) {
    mrpt::random::CRandomGenerator rng(seed);
    sim::ScannerOptions s;
    s.rangeSigma = sigma;
    const polymap::HypothesisGenerator gen(map.polygon, {tolerance, 3 * M_PI / 180});
    for (const auto& site : map.sites) {
        const double heading = rng.drawUniform(-M_PI, M_PI);
        const auto H = gen.generate(sense(map.polygon, site, heading, s, rng));
        ASSERT_EQ(H.size(), map.sites.size())
            << map.description << " sigma " << sigma << " at " << site.asString();
        for (const auto& other : map.sites) {
            double nearest = 1e9;
            for (const auto& h : H) nearest = std::min(nearest, (h.point - other).norm());
            EXPECT_LT(nearest, tolerance) << map.description << ": " << other.asString();
        }
    }
}

}  // namespace

TEST(ScanPolygon, NoiseFreeScanMatchesTheExactPolygon) {
    // Only the beam spacing separates them: windows within half a beam step (times range).
    const auto map = polymap::stepsMap({});
    mrpt::random::CRandomGenerator rng(1);
    sim::ScannerOptions s;
    s.rangeSigma = 0;
    for (const auto& site : map.sites) {
        const auto exact = polymap::visibilityPolygon(map.polygon, site);
        const auto sensed = sense(map.polygon, site, 0.3, s, rng);
        double rMax = 0;
        for (const auto& v : exact.vertices) rMax = std::max(rMax, v.norm());
        EXPECT_LT(polymap::boundaryDistance(exact, sensed, 0.005), rMax * M_PI / 1440 + 1e-3)
            << site.asString();
        EXPECT_EQ(sensed.size(), exact.size()) << site.asString();
    }
}

TEST(ScanPolygon, NoiseUpToTheToleranceKeepsH) {
    // Stated tolerance: with 1440 beams, range noise up to 1 cm and tolerance 0.1 m, H is
    // unchanged, on the steps maps, on rooms along a corridor and on a plain polygon.
    polymap::StepsMapOptions three;
    three.steps = 3;
    for (unsigned seed = 1; seed <= 3; ++seed)
        for (const double sigma : {0.002, 0.005, 0.01}) {
            expectSameHypotheses(polymap::stepsMap({}), sigma, 0.1, seed);
            expectSameHypotheses(polymap::stepsMap(three), sigma, 0.1, seed);
            mrpt::random::CRandomGenerator mapRng(seed);
            expectSameHypotheses(polymap::roomsMap({}, mapRng), sigma, 0.1, seed);
        }
}

TEST(ScanPolygon, BadScansAreClearErrors) {
    const auto P = common::Polygon::fromVertices({{0, 0}, {40, 0}, {40, 3}, {0, 3}}, "box");
    mrpt::random::CRandomGenerator rng(1);
    sim::ScannerOptions s;
    s.maxRange = 10;  // the far ends are out of range: V is not closed
    const auto scan = sim::scanFloorPlan(P, {5, 1, 0}, s, rng);
    scan->sensorLabel = "r1.scan";
    try {
        polymap::visibilityFromScan(*scan, 0, {});
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("r1.scan"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("max range"), std::string::npos) << e.what();
    }
    auto half = sim::scanFloorPlan(P, {5, 1, 0}, {}, rng);
    half->aperture = float(M_PI);
    EXPECT_THROW(polymap::visibilityFromScan(*half, 0, {}), Error);
}

TEST(ScanPolygon, AStepTooShortToSeeDoesNotHideTheTruth) {
    // Three rooms of map seed 3 (room_steps 4, as config/polymap_rooms.ini's keys give): a
    // 1/8 m step of the room's ceiling, seen edge-on, is lost from the scan's V, whose two
    // walls then meet at a corner no vertex of P has. That corner anchored the search and
    // H was empty (0 hypotheses from the robot's own map); it now neither anchors nor must
    // match, and every site finds the three rooms.
    polymap::RoomsMapOptions o;
    o.rooms = 3;
    mrpt::random::CRandomGenerator mapRng(3);
    const auto map = polymap::roomsMap(o, mapRng);
    // the run's scanner (1440 beams, 5 mm noise) and the tolerance it derived (0.064 m)
    expectSameHypotheses(map, sim::ScannerOptions{}.rangeSigma, 0.064, 1);
}
