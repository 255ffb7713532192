// Seed and grow: the fast triangle search and identification (see TriangleSearch.h). The
// pieces are in LayoutGrowth.h; this file tries seeds until a layout labels nearly every
// image.
#include "LayoutGrowth.h"

namespace mrloc::omnivision {

using namespace seedgrow;

namespace {

size_t labelCount(const Layout& layout) {
    size_t labeled = 0;
    for (const auto& lab : layout.labels)
        for (int who : lab) labeled += who >= 0;
    return labeled;
}

/** The share of the placed robots' images that carry a label. */
double labeledShare(const Layout& layout) {
    size_t images = 0;
    for (int r : layout.order) images += layout.labels[size_t(r)].size();
    return images ? double(labelCount(layout)) / double(images) : 0;
}

/** Labels two layouts share (the same image, the same robot). */
size_t sharedLabels(const Layout& a, const Layout& b) {
    size_t shared = 0;
    for (size_t r = 0; r < a.labels.size() && r < b.labels.size(); ++r)
        for (size_t i = 0; i < a.labels[r].size() && i < b.labels[r].size(); ++i)
            shared += a.labels[r][i] >= 0 && a.labels[r][i] == b.labels[r][i];
    return shared;
}

/** A layout grown again from another seed holds at least this share of its labels. */
constexpr double kRegrownShare = 0.8;

/** A layout that no other seed grew again must place a quarter of the robots that can be
 *  placed. Measured: when the search ran through its 200 seeds, the chance layouts it kept
 *  placed 7-9 robots (N = 30 at 0.3 deg to N = 100 at 0.05 deg, 26-44 wrong labels each),
 *  the true ones 31-74 of 50-100 (occluded scenes, where one seed alone grows a part). */
constexpr size_t kAloneQuarter = 4;

/** A layout that places every robot it can and labels this share of their images is done.
 *  Images two robots share within the tolerance stay unlabelled, more with more noise: at
 *  0.05 deg and N = 75 a true layout labels 83-91 %, and with 0.9 the search then tried its
 *  200 seeds (24 s) for nothing. */
constexpr double kDoneShare = 0.75;

}  // namespace

Identification identify(const Snapshot& s, const SearchOptions& o) {
    const ImageTable table(s, o.maxPairVisits(s.robots()));
    const LayoutGrower grower(table, o);
    const int n = int(s.robots());
    size_t placeable = 0;
    for (const auto& v : s.views) placeable += v.size() >= 2;
    // Everything that can be placed is (but for 1 in 50: a robot whose images all stand
    // nearly in line with others' cannot be), and most of its images labelled.
    const auto complete = [&](const Layout& layout) {
        return layout.order.size() + placeable / 50 >= placeable &&
               labeledShare(layout) >= kDoneShare;
    };
    Layout best;
    size_t tried = 0, matched = 0, bestLabels = 0;
    bool regrown = false;  // the best layout, or one it holds, grown from two seeds
    const auto attempt = [&](const Seed& seed) {
        ++tried;
        bool ok = false;
        Layout layout = grower.growFrom(seed, ok);
        // The layout with most labels wins: chance growth from a false seed places robots
        // on a few rays each, a true layout labels nearly every image.
        const size_t labels = ok ? labelCount(layout) : 0;
        const bool grew = ok && layout.order.size() > 3 && bestLabels > 0;
        const double shared = grew ? double(sharedLabels(layout, best)) : 0;
        if (labels > bestLabels) {
            if (labels > bestLabels + bestLabels / 50) matched = 0;
            regrown = grew && shared >= kRegrownShare * double(bestLabels);  // holds the old
            best = std::move(layout);
            bestLabels = labels;
        } else {
            if (grew && shared >= kRegrownShare * double(labels)) regrown = true;  // held
            if (ok && layout.order.size() > 3 && 2 * layout.order.size() > placeable &&
                labels + labels / 50 >= bestLabels)
                ++matched;
        }
        // Done when the best layout is complete, or has been grown again from three other
        // seeds, or when the budget is spent.
        return complete(best) || matched >= 3 || tried >= o.maxSeeds;
    };
    if (!tryHullSeeds(table, o, attempt) && !tryPairSeeds(table, attempt))
        tryGeneralSeeds(table, o, attempt);
    const bool done = complete(best);
    // Measured at 0.05 deg, N = 75: the 14 and 6 wrong labels of two scenes were images of
    // one unplaced robot, each labelled as the placed robot it hides; grown once more, it
    // is placed and they are not wrong (once per search: per seed it doubled the work).
    if (best.order.size() > 3) {
        grower.growFreed(best);
        grower.assignNearLines(best);
    }
    // A seed that grew no further is no evidence: three robots' angles summing to 180
    // degrees happen by chance. Nor is a small layout that no other seed grew again and
    // that does not place every robot (kAloneQuarter).
    const bool evidence = best.order.size() > 3 &&
                          (done || regrown || best.order.size() * kAloneQuarter >= placeable);
    Labels labels = evidence || placeable <= 3 ? best.labels : Labels{};
    if (labels.empty()) {
        labels.resize(size_t(n));
        for (int r = 0; r < n; ++r) labels[size_t(r)].assign(s.views[size_t(r)].size(), -1);
    }
    auto id = consistentTriangles(s, std::move(labels), o.sumTolerance);
    id.candidates = tried;
    id.pairVisits = table.visits();
    return id;
}

}  // namespace mrloc::omnivision
