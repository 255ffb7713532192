// Hypothesis generation on exact visibility polygons: the seed's steps maps, rooms along a
// corridor, two rooms joined asymmetrically, and polygons without self-similarity.
#include <gtest/gtest.h>
#include <mrloc/polymap/Hypotheses.h>
#include <mrloc/polymap/MapGenerators.h>

using namespace mrloc;
using common::TPoint2D;
using polymap::HypothesisGenerator;

namespace {

/** Every site finds exactly the sites, each once. */
void expectSitesFindEachOther(const polymap::GeneratedMap& map, double tolerance = 1e-6) {
    const HypothesisGenerator gen(map.polygon, {tolerance, 1e-6});
    for (const auto& site : map.sites) {
        const auto H = gen.generate(polymap::visibilityPolygon(map.polygon, site));
        ASSERT_EQ(H.size(), map.sites.size()) << map.description << " from " << site.asString();
        for (const auto& s : map.sites) {
            size_t found = 0;
            for (const auto& h : H) found += (h.point - s).norm() < 1e-9;
            EXPECT_EQ(found, 1u) << map.description << ": site " << s.asString();
        }
        for (const auto& h : H) EXPECT_LT((h.translation - (h.point - H[0].point)).norm(), 1e-12);
    }
}

}  // namespace

TEST(Hypotheses, StepsMapsOfThePaper) {
    // seed 002 sec. 3: n = 76 with 3 steps and k = 6; n = 148 with 6 steps and k = 12.
    for (const auto& [steps, n, k] : {std::tuple{3, 76u, 6u}, std::tuple{6, 148u, 12u}}) {
        polymap::StepsMapOptions o;
        o.steps = steps;
        const auto map = polymap::stepsMap(o);
        EXPECT_EQ(map.polygon.size(), n);
        EXPECT_EQ(map.sites.size(), k);
        expectSitesFindEachOther(map);
    }
}

TEST(Hypotheses, StepsMapFamily) {
    for (int steps : {1, 2, 4, 9})
        for (int branches : {1, 3}) {
            polymap::StepsMapOptions o;
            o.steps = steps;
            o.branchesPerStep = branches;
            o.stepWidth = 6 * branches + 4;
            const auto map = polymap::stepsMap(o);
            EXPECT_EQ(map.polygon.size(), (size_t)(steps * (4 + 10 * branches) + 4));
            expectSitesFindEachOther(map);
        }
}

TEST(Hypotheses, RoomsAlongACorridor) {
    for (unsigned seed = 1; seed <= 6; ++seed) {
        mrpt::random::CRandomGenerator rng(seed);
        polymap::RoomsMapOptions o;
        o.rooms = 2 + (int)seed % 4;
        o.roomSteps = 2 + (int)seed % 5;
        expectSitesFindEachOther(polymap::roomsMap(o, rng));
    }
}

TEST(Hypotheses, TwoIdenticalRoomsJoinedAsymmetricallyGiveTwo) {
    mrpt::random::CRandomGenerator rng(11);
    polymap::RoomsMapOptions o;
    o.rooms = 2;
    o.rightMargin = 7;
    const auto map = polymap::roomsMap(o, rng);
    expectSitesFindEachOther(map);
    // In the corridor, off-centre, the two ends differ: a single hypothesis.
    const HypothesisGenerator gen(map.polygon, {1e-6, 1e-6});
    const TPoint2D corridor{2.3, 1.1};
    const auto H = gen.generate(polymap::visibilityPolygon(map.polygon, corridor));
    ASSERT_EQ(H.size(), 1u);
    EXPECT_LT((H[0].point - corridor).norm(), 1e-9);
}

TEST(Hypotheses, NoSelfSimilarityGivesOne) {
    mrpt::random::CRandomGenerator rng(5);
    for (int poly = 0; poly < 20; ++poly) {
        const auto P = polymap::randomStarPolygon(12 + poly, 0.3, 1.0, rng);
        const HypothesisGenerator gen(P, {1e-6, 1e-6});
        for (int k = 0; k < 5; ++k) {
            TPoint2D q;
            do q = {rng.drawUniform(-1.0, 1.0), rng.drawUniform(-1.0, 1.0)};
            while (P.locate(q) != common::Polygon::Where::Inside);
            const auto H = gen.generate(polymap::visibilityPolygon(P, q));
            ASSERT_EQ(H.size(), 1u) << "polygon " << poly << " at " << q.asString();
            EXPECT_LT((H[0].point - q).norm(), 1e-9);
        }
    }
}

TEST(Hypotheses, ViewpointsOnEdgesAndVertices) {
    // A hypothesis may sit exactly on the boundary: stand on every vertex and edge midpoint
    // of a steps map; the true point is always among H and every h in H sees the same V.
    const auto map = polymap::stepsMap({});
    const auto& P = map.polygon;
    const HypothesisGenerator gen(P, {1e-6, 1e-6});
    for (size_t i = 0; i < P.size(); i += 9)
        for (const TPoint2D q : {P[i], (P[i] + P[P.next(i)]) * 0.5}) {
            const auto V = polymap::visibilityPolygon(P, q);
            const auto H = gen.generate(V);
            bool found = false;
            for (const auto& h : H) {
                found |= (h.point - q).norm() < 1e-9;
                EXPECT_LT(
                    polymap::boundaryDistance(V, polymap::visibilityPolygon(P, h.point), 1e-3),
                    1e-6);
            }
            EXPECT_TRUE(found) << q.asString();
        }
}

// A view with corners of its own (a traced building's laser-fan fringe, a wall the trace
// bent): a rectangular notch, 0.3 x 0.2 m, pushed into one wall of the exact view at a steps
// map's site. Its two corners point the way the map's corners do, so they match map vertices
// but land on none at the truth: the strict pass (every feature on a vertex) finds nothing.
// With a verdict on the places proposed (the beams' second chance in the localizer; here
// "within 1 cm of a site"), the consensus pass proposes every site anew (each feature
// anchoring in turn, a place kept where 3 land on vertices), and nothing else passes the
// verdict. Without a verdict there is no consensus pass: H stays empty, as before.
TEST(Hypotheses, CornersTheMapLacksDoNotHideTheTruthWhenAVerdictIsGiven) {
    const auto map = polymap::stepsMap({});
    const polymap::HypothesisOptions options;  // 5 cm, 3 degrees: a scan's
    const HypothesisGenerator gen(map.polygon, options);
    const TPoint2D truth = map.sites[3];
    auto V = polymap::visibilityPolygon(map.polygon, truth);
    // the longest wall of V (not a window) gets the notch in its middle
    size_t wall = 0;
    double longest = 0;
    for (size_t i = 0; i < V.size(); ++i) {
        const double length = (V.vertices[(i + 1) % V.size()] - V.vertices[i]).norm();
        if (!V.isRadial(i) && length > longest) wall = i, longest = length;
    }
    ASSERT_GT(longest, 1.0);
    const TPoint2D a = V.vertices[wall], b = V.vertices[(wall + 1) % V.size()];
    const common::TVector2D along = (b - a) * (1 / longest), out{along.y, -along.x};  // away
    const TPoint2D mid = a + along * (0.5 * longest);
    const std::vector<TPoint2D> notch{mid - along * 0.15, mid - along * 0.15 + out * 0.2,
                                      mid + along * 0.15 + out * 0.2, mid + along * 0.15};
    V.vertices.insert(V.vertices.begin() + long(wall) + 1, notch.begin(), notch.end());

    polymap::HypothesisStats strict;
    EXPECT_TRUE(gen.generate(V, &strict).empty());
    const auto nearSite = [&](const TPoint2D& p) {
        for (const auto& s : map.sites)
            if ((p - s).norm() < 0.01) return true;
        return false;
    };
    polymap::HypothesisStats stats;
    const auto H =
        gen.generate(V, &stats, [&](const TPoint2D& p, const polymap::VisibilityPolygon&) {
            return nearSite(p) ? std::optional<double>(0.0) : std::nullopt;
        });
    ASSERT_EQ(H.size(), map.sites.size());
    for (const auto& h : H) EXPECT_TRUE(nearSite(h.point)) << h.point.asString();
    size_t truthFound = 0;
    for (const auto& h : H) truthFound += (h.point - truth).norm() < 0.01;
    EXPECT_EQ(truthFound, 1u);
    EXPECT_GT(stats.proposed, strict.proposed);
    EXPECT_LE(stats.verified, strict.verified + HypothesisGenerator::kConsensusPlaces);
}
