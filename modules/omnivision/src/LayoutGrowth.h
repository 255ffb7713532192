#pragma once
// Seed and grow (TriangleSearch.h), the pieces its files share:
//  - ImageTable: each camera's images and the signed angles between every ordered pair of
//    them, sorted, so that "which pairs subtend about delta" is a binary search;
//  - seeds (SeedSearch.cpp): triangles from the swarm's hull first, then pairs of hull
//    robots (for a camera range), then any three angle pairs summing to 180 degrees;
//  - LayoutGrower: places a seed triangle and grows the layout where rays of placed robots
//    meet (LayoutGrowth.cpp), then polishes positions and relabels images (LayoutPolish.cpp);
//  - identify() (SeedAndGrow.cpp) tries seeds until a layout labels nearly every image.
#include <mrloc/common/Error.h>
#include <mrloc/omnivision/TriangleSearch.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>
#include <set>
#include <utility>
#include <vector>

namespace mrloc::omnivision::seedgrow {

/** Wraps to (-pi, pi] for angles a few turns away at most: the hot loops call it often
 *  and mrpt::math::wrapToPi's fmod dominated their profile. */
inline double wrapToPi(double a) {
    while (a > M_PI) a -= 2 * M_PI;
    while (a <= -M_PI) a += 2 * M_PI;
    return a;
}
using Vec2 = Eigen::Vector2d;

inline double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }
inline Vec2 unit(double angle) { return {std::cos(angle), std::sin(angle)}; }
inline double direction(const Vec2& from, const Vec2& to) {
    return std::atan2(to.y() - from.y(), to.x() - from.x());
}

/** The least-squares meeting point of lines, each through a point at a direction. */
class LineMeeting {
 public:
    /** weight: 1 / the variance of the point's distance from the line (m^-2): then
     *  information() is the meeting point's information matrix. */
    void add(const Vec2& through, double angle, double weight = 1) {
        const Vec2 normal(-std::sin(angle), std::cos(angle));
        A_ += weight * normal * normal.transpose();
        b_ += weight * normal * normal.dot(through);
    }
    const Eigen::Matrix2d& information() const { return A_; }
    /** None when the lines are (nearly) parallel. */
    std::optional<Vec2> solve() const {
        if (std::abs(A_.determinant()) <= 1e-12) return std::nullopt;
        return A_.ldlt().solve(b_);
    }

 private:
    Eigen::Matrix2d A_ = Eigen::Matrix2d::Zero();
    Eigen::Vector2d b_ = Eigen::Vector2d::Zero();
};

/** A triangle whose identities are fixed, counter-clockwise r[0] -> r[1] -> r[2]. At
 *  r[v], image[v][0] shows the next robot and image[v][1] the previous one, so that the
 *  signed angle from the first to the second is the interior angle. */
struct Seed {
    std::array<int, 3> r{};
    std::array<std::array<int, 2>, 3> image{};
    /** Two robots only (tryPairSeeds): r[0]'s image[0][0] shows r[1], r[1]'s image[1][1]
     *  shows r[0]; r[2] and the other images are unused. */
    bool pair = false;
};

/** A robot placed (up to scale) in the growing layout. */
struct Layout {
    std::vector<char> placed;
    std::vector<Vec2> p;
    std::vector<double> heading;
    Labels labels;
    std::vector<int> order;  ///< placement order
    double scale = 1;        ///< the seed triangle's mean side
};

/** A robot that might stand where the rays of placed robots meet. */
struct Candidate {
    int robot = -1;
    Vec2 at;
    double heading = 0;
    std::vector<std::pair<int, int>> raysIn;  ///< placed robot, its image of `robot`
    std::vector<std::pair<int, int>> seen;    ///< placed robot, `robot`'s image of it
    double residual = 0;                      ///< sum of squared bearing errors
    size_t rayChecks = 0;  ///< placed robots beyond the two anchors asked for a ray into it
    size_t evidence() const { return raysIn.size() + seen.size(); }
    /** Checks that could have failed and those that did not: rays asked of placed robots
     *  beyond the two anchors, and the candidate's own images of the placed robots beyond
     *  the two its heading was fitted to. */
    size_t checks() const { return rayChecks + (raysIn.size() - 2); }
    size_t hits() const { return (raysIn.size() - 2) + (seen.size() - 2); }
};

/** Each camera's images and the signed angles between them. */
class ImageTable {
 public:
    explicit ImageTable(const Snapshot& s, size_t maxVisits = size_t(-1));
    /** Angle pairs forPairsNear has handed out and images findImage has looked at so far:
     *  the search's work, bounded by maxVisits. */
    size_t visits() const { return visits_; }

    const Snapshot& snapshot() const { return snapshot_; }
    int robots() const { return int(snapshot_.robots()); }
    const View& view(int r) const { return snapshot_.views[size_t(r)]; }
    double bearing(int r, int image) const { return view(r).bearings[size_t(image)]; }

    struct PairAngle {
        double angle;  ///< signed, from image `from` to image `to`
        int from, to;
    };
    /** Per robot, every ordered pair of its images, sorted by angle. */
    const std::vector<std::vector<PairAngle>>& pairTables() const { return pairs_; }

    /** Calls f(e, g) for every ordered pair of robot r's images whose signed angle is
     *  within tol of delta. */
    template <class F>
    void forPairsNear(int r, double delta, double tol, F&& f) const {
        const auto& ps = pairs_[size_t(r)];
        const auto scan = [&](double lo, double hi) {
            auto it = std::lower_bound(ps.begin(), ps.end(), lo,
                                       [](const PairAngle& p, double v) { return p.angle < v; });
            for (; it != ps.end() && it->angle <= hi; ++it) {
                if (++visits_ > maxVisits_) throw tooMuchWork();
                f(it->from, it->to);
            }
        };
        scan(delta - tol, delta + tol);
        if (delta - tol < -M_PI) scan(delta - tol + 2 * M_PI, M_PI);
        if (delta + tol > M_PI) scan(-M_PI, delta + tol - 2 * M_PI);
    }

    /** The unlabeled image of robot r nearest the bearing b (robot frame), within tol; labels
     *  may be empty (any image). */
    int findImage(const Labels& labels, int r, double b, double tol) const;

 private:
    Error tooMuchWork() const;

    // findImage's index, per robot: the bearings unrolled over three turns (b - 2 pi, b,
    // b + 2 pi), so that a window about any bearing is one contiguous run with no angle
    // wrapped in the scan, and the first unrolled image at or after each of kCells equal
    // slices of (-2 pi, 2 pi], so that the run's start is a lookup and a step or two.
    // (A binary search here was 47 % of N = 100; wrapping each image's angle, later, 53 %.)
    static constexpr size_t kCells = 2048;
    static constexpr double kCellWidth = 4 * M_PI / double(kCells);
    static double cellStart(size_t i) { return -2 * M_PI + double(i) * kCellWidth; }
    static size_t cellOf(double a) {
        return std::min(kCells - 1, size_t(std::max(0.0, (a + 2 * M_PI) / kCellWidth)));
    }

    const Snapshot& snapshot_;
    std::vector<std::vector<PairAngle>> pairs_;
    std::vector<std::vector<double>> unrolled_;
    std::vector<std::vector<uint32_t>> cells_;
    mutable size_t visits_ = 0;  // the work meter: a search's cost, bounded by maxVisits_
    size_t maxVisits_;
};

/** Tries a seed; true stops the search. */
using SeedAttempt = std::function<bool(const Seed&)>;
/** Seeds from the hull, best conditioned first; true if an attempt stopped the search. */
bool tryHullSeeds(const ImageTable& table, const SearchOptions& o, const SeedAttempt& attempt);
/** Pairs of robots on the hull's boundary, each the other's extreme image: i's first image
 *  (counter-clockwise after its gap) shows j and j's last shows i. Where cameras see only
 *  their neighbours the hull's ears are wider than their range and no hull triangle is
 *  true; a pair is grown from the robots both see (the first group). */
bool tryPairSeeds(const ImageTable& table, const SeedAttempt& attempt);
/** Every triangle of counter-clockwise angle pairs summing to 180 degrees. */
bool tryGeneralSeeds(const ImageTable& table, const SearchOptions& o, const SeedAttempt& attempt);

/** Grows layouts from seeds over one ImageTable. */
class LayoutGrower {
 public:
    LayoutGrower(const ImageTable& table, const SearchOptions& o)
        : table_(table), o_(o), n_(table.robots()), chance_(chancePerCheck(table, o)) {}
    /** The layout grown from the seed, polished and relabeled; ok is false for a
     *  degenerate seed. */
    Layout growFrom(const Seed& seed, bool& ok) const;
    /** Grows a finished layout again, once its one-sided labels are gone (keepMutual):
     *  a robot standing in line between two placed ones had its images taken by their
     *  labels while it grew; freed, they place it, and the labels of the pairs it hides
     *  from each other go to it. Where the cameras' range is bounded (rangeBounded), from
     *  every pair of placed robots with free images: a robot left unplaced there is seen
     *  by its neighbours only, rarely by the kAnchorGroups pairs with most free images. */
    void growFreed(Layout& layout) const;
    /** The final layout's images left unlabelled near the lines to several robots, matched
     *  as groups where the match is beyond doubt (LayoutPolish.cpp). */
    void assignNearLines(Layout& layout) const;

 private:
    double tolAt(const Layout& layout, double dist) const;
    /** No robot placed, no image labelled. */
    Layout emptyLayout() const;
    bool placeSeed(const Seed& seed, Layout& layout) const;
    bool placePair(const Seed& seed, Layout& layout) const;
    double fitHeading(const Layout& layout, int r) const;
    /** What the anchor pairs of one growth round share. */
    struct Round {
        /** How far a placed robot may be from a point and still be asked (sightReach). */
        double reach = INFINITY;
        /** The reach leaves placed robots out (rangeBounded). */
        bool bounded = false;
        /** Rays into points already identified this round (from this anchor pair or
         *  another): a point most of whose rays are claimed is the same robot again and is
         *  not identified twice; candidates() adds the rays of the points it identifies.
         *  Not held against a pair seed's points (two rays each). Claiming only for later
         *  anchor pairs was measured: other labelled shares and up to 5 times the time. */
        std::set<std::pair<int, int>> claimed;
    };
    std::vector<Candidate> candidates(const Layout& layout, int s1, int s2, size_t minRays,
                                      size_t minSeen, Round& round) const;
    /** How far the cameras see, as the layout shows it: 1.1 times the longest labelled
     *  sight where under 90 % of the placed pairs are labelled (a camera range), else
     *  unbounded (a swarm that sees itself whole is checked by every robot). */
    double sightReach(const Layout& layout) const;
    /** Whether the cameras' range is bounded: some placed pair stands farther apart than
     *  the reach. Robots then see only their neighbours, and bands hide many of those
     *  (a true point misses most placed robots in range); a swarm that sees itself whole
     *  has a reach beyond its layout, however many of its labels are missing. */
    static bool rangeBounded(const Layout& layout, double reach);
    void refinePoint(const Layout& layout, Candidate& c) const;
    void identifyRobot(const Layout& layout, const Candidate& c, size_t minSeen,
                       std::vector<Candidate>& out) const;
    double residual(const Layout& layout, const Candidate& c) const;
    static void place(Layout& layout, const Candidate& c);
    /** Whether c's rays are taken by robots placed before it: by any, or where the
     *  cameras' range is bounded (rangeBounded: bands hide often), by one no farther
     *  along the image than kInFront times c's point. */
    static bool conflicts(const Layout& layout, const Candidate& c, bool bounded);
    static void sortByEvidence(std::vector<Candidate>& found);
    bool growOnce(Layout& layout, size_t anchorGroups = kAnchorGroups) const;
    /** growOnce until it places no more, polishing and relabelling after each round: a
     *  placed robot's images of other placed robots left unlabelled would cast rays that
     *  meet at robots already placed. anchorGroups: anchor pairs tried per round, at most. */
    void growAll(Layout& layout, size_t anchorGroups = kAnchorGroups) const;
    bool placeMutualGroup(Layout& layout, const std::vector<Candidate>& found) const;
    /** Whether c's agreement with the layout is beyond chance: the probability that a
     *  wrong point and robot pass as many of its checks (each by chance with the share of
     *  the circle a tolerance window over every image covers) is below 1 % over all the
     *  hypotheses a search tries (about N^4: points N^2, robots N, anchor pairs N). */
    bool significant(const Candidate& c) const;
    /** The chance that a bearing falls in a tolerance window by accident: the share of the
     *  circle that a window of +-2 tolerances (tolAt's largest) over a view's images
     *  covers, at most 1/2. */
    static double chancePerCheck(const ImageTable& table, const SearchOptions& o);
    void polish(Layout& layout, int sweeps) const;
    /** An image of camera u within the tolerance of a placed robot's predicted bearing. */
    struct Match {
        double err;  ///< the miss over the tolerance, 0..1
        int image, robot;
    };
    std::vector<Match> matchesAt(const Layout& layout, int u) const;
    void relabel(Layout& layout) const;
    /** The placed robot to take out first, if any: the most one-sided in what it sees
     *  (kMinSightShare), else the one that misses most (kMaxMissShare), else the worst
     *  fitting beyond kMaxRms. */
    int worstFit(const Layout& layout) const;
    static void unplace(Layout& layout, int r);
    static void keepMutual(Layout& layout);

    static constexpr double kMinRayAngle = 0.02;  ///< sin of ~1.1 degrees
    /** The bearing tolerance is this many bearing sigmas ([omnivision] derives it so). */
    static constexpr double kSigmasPerTolerance = 4;
    /** assignNearLines: the largest group of images matched as a whole (5! assignments),
     *  and how much worse, in squared bearing sigmas, every other assignment must be. */
    static constexpr size_t kMaxNearLine = 5;
    static constexpr double kAssignMargin = 9;
    static constexpr size_t kSmallLayout = 6;     ///< below: every placed robot must agree
    static constexpr size_t kAnchors = 4;         ///< the first robots, whose pairs all give rays
    static constexpr size_t kMissSlack = 4;       ///< misses allowed beyond twice the hits
    static constexpr size_t kAnchorGroups = 8;    ///< anchor pairs tried per round, at most
    static constexpr size_t kMinEvidence = 8;     ///< rays in plus robots seen
    static constexpr size_t kMinGroup = 4;  ///< robots placed at once beside the seed, at most
    static constexpr size_t kPerRobot = 3;  ///< candidates per robot in the group's first pass
    /** A placed robot whose labels fit the layout worse than this (RMS, bearing sigmas) is
     *  taken out again: it was placed on a chance meeting of rays near its true place. */
    static constexpr double kMaxRms = 4;
    /** A placed robot that sees fewer than this share of the placed robots that see it is
     *  taken out too (sight is mutual). */
    static constexpr double kMinSightShare = 0.5;
    /** A placed robot is taken out if more than this share of its sight checks miss (a
     *  placed robot in sight with no image where the layout predicts it, either way), and
     *  more than kMissOverMedian times the layout's median share (bands hide beyond the
     *  line to their centre). Measured at 0.05 deg, N = 75: a robot placed near its true
     *  place missed 34 % against a median of 2.7 %; occluded layouts' medians reach 61 %. */
    static constexpr double kMaxMissShare = 0.3;
    static constexpr double kMissOverMedian = 3;
    /** A point whose predicted bearing for a robot is this many bearing tolerances
     *  uncertain is not checked against that robot (it could not tell). */
    static constexpr double kMaxSpread = 10;
    /** Points farther than this times the longest labelled sight are not checked. */
    static constexpr double kReachMargin = 1.1;
    /** A robot this many times farther than a point along an image is hidden by it. */
    static constexpr double kInFront = 1.05;

    const ImageTable& table_;
    const SearchOptions& o_;
    int n_;
    double chance_;  ///< chancePerCheck
};

}  // namespace mrloc::omnivision::seedgrow
