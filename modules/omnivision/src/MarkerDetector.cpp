#include <mrloc/common/Error.h>
#include <mrloc/omnivision/MarkerDetector.h>
#include <mrpt/core/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace mrloc::omnivision {

namespace {

/** Union-find over component labels, to join blobs cut by the strip's wrap-around. */
int root(std::vector<int>& parent, int x) {
    while (parent[size_t(x)] != x) x = parent[size_t(x)] = parent[size_t(parent[size_t(x)])];
    return x;
}

/** One column of a blob: the rows its red run spans, and whether it touches the strip's
 *  top or bottom (then its height is only a lower bound). */
struct BlobColumn {
    int x = 0, height = 0;
    bool clipped = false;
};

/** Columns of a blob taken as one marker. */
struct Piece {
    double bearing = 0;  ///< rad, robot frame
    double span = 0;     ///< rad of azimuth its columns cover
    int height = 0;      ///< px, its columns' median (a lone column may gain a row pair)
    bool clipped = false;
};

// A marker's bearing is the middle of the azimuths its columns span. Each column counts
// once, by the angle it spans: a pinhole view's columns are even in the image, not in
// azimuth (one at 45 degrees off the view's axis spans half the angle of one on it), and
// a column's red rows grow with 1 / depth along the view's axis, which differs across a
// marker off the axis. A mean over pixels leans away from the axis by up to 0.16 deg for
// the markers 3 m away in omnivision_5robots.ini; over columns by angle it does not.
Piece pieceOf(const std::vector<BlobColumn>& columns, size_t begin, size_t end, const Panorama& p) {
    Piece out;
    double sx = 0, sy = 0;
    std::vector<int> heights;
    for (size_t i = begin; i < end; ++i) {
        const int x = columns[i].x;
        const double a = p.bearingOfColumn(x);
        const double span = std::abs(
            std::remainder(p.bearingOfColumn(x - 0.5) - p.bearingOfColumn(x + 0.5), 2 * M_PI));
        sx += span * std::cos(a), sy += span * std::sin(a);
        out.span += span;
        heights.push_back(columns[i].height);
        out.clipped = out.clipped || columns[i].clipped;
    }
    out.bearing = std::atan2(sy, sx);
    std::nth_element(heights.begin(), heights.begin() + long(heights.size() / 2), heights.end());
    out.height = heights[heights.size() / 2];
    return out;
}

/** Whether a piece is as wide as a whole band at the depth its height gives: a band's
 *  front at depth z along the view's axis spans f * height / z rows, and a band at
 *  distance d spans 2 asin(radius / d) of azimuth. */
bool isWholeBand(const Piece& piece, const Panorama& p, const DetectorOptions& o) {
    const double offAxis = p.offAxis(piece.bearing);
    const auto widthAt = [&](double rows) {
        const double depth = p.focal() * o.markerHeight / std::max(rows, 0.5);
        const double distance = depth / std::cos(offAxis) + o.markerRadius;
        return 2 * std::asin(std::min(1.0, o.markerRadius / distance));
    };
    const double column = p.columnAngleAt(piece.bearing);
    const bool notTooWide =
        piece.clipped || piece.span <= widthAt(piece.height + o.heightSlack) + 1.5 * column;
    return notTooWide && piece.span >= widthAt(piece.height - o.heightSlack) - 1.5 * column;
}

/** A neighbouring piece within one step of the last, and at least this share of the
 *  tallest's height, is the same band: off a view's axis a band's height changes across
 *  it, a quantum at a time. Measured on 100 rendered robots in 36 x 36 m (0.15 m bands,
 *  512 px views; bearings within half a pixel of a visible robot, and not): 0.8 gives
 *  4,029 and 357; 0.7 4,016 and 365; 0.9 3,826 and 390; no share 3,560 and 520. */
constexpr double kSameBandShare = 0.8;

/** The markers of one blob: cut where its height steps; a piece that no neighbour stands in
 *  front of (taller: nearer) is a band, widened over its neighbours of the same band, kept if
 *  it is as wide as a whole band. A band partly hidden by a nearer one is dropped. */
void splitBlob(const std::vector<BlobColumn>& columns, const Panorama& p, const DetectorOptions& o,
               std::vector<double>& bearings) {
    std::vector<std::pair<size_t, size_t>> runs;  // [begin, end) between height steps
    for (size_t i = 1, begin = 0; i <= columns.size(); ++i)
        if (i == columns.size() ||
            std::abs(columns[i].height - columns[i - 1].height) >= o.heightStep) {
            runs.emplace_back(begin, i);
            begin = i;
        }
    std::vector<int> height(runs.size(), 0);
    for (size_t k = 0; k < runs.size(); ++k)
        for (size_t i = runs[k].first; i < runs[k].second; ++i)
            height[k] = std::max(height[k], columns[i].height);
    // Tallest first: a band's own pieces (its height changes across it a quantum at a time)
    // are taken by its tallest, so that it is found once.
    std::vector<size_t> order(runs.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t i, size_t j) { return height[i] > height[j]; });
    std::vector<bool> taken(runs.size(), false);
    const auto sameBand = [&](size_t next, size_t from, size_t top) {
        return !taken[next] && std::abs(height[next] - height[from]) <= o.heightStep &&
               height[next] >= kSameBandShare * height[top];
    };
    for (size_t k : order) {
        const bool behind = (k > 0 && height[k - 1] > height[k]) ||
                            (k + 1 < runs.size() && height[k + 1] > height[k]);
        if (taken[k] || behind) continue;
        size_t first = k, last = k;
        while (first > 0 && sameBand(first - 1, first, k)) --first;
        while (last + 1 < runs.size() && sameBand(last + 1, last, k)) ++last;
        std::fill(taken.begin() + long(first), taken.begin() + long(last) + 1, true);
        const Piece band = pieceOf(columns, runs[first].first, runs[last].second, p);
        if (isWholeBand(band, p, o)) bearings.push_back(band.bearing);
    }
}

}  // namespace

std::vector<double> detectMarkers(const mrpt::img::CImage& strip, const omnivision::Panorama& p,
                                  const DetectorOptions& o) {
    if (!strip.isColor() || int(strip.getWidth()) != p.width() ||
        int(strip.getHeight()) != p.height)
        throw Error(mrpt::format("omnivision: expected a %dx%d colour panorama, got %zux%zu %s",
                                 p.width(), p.height, strip.getWidth(), strip.getHeight(),
                                 strip.isColor() ? "colour" : "grey"));
    cv::Mat bgr;
    strip.asCvMat(bgr, mrpt::img::SHALLOW_COPY);  // CImage keeps OpenCV's BGR order
    cv::Mat mask(bgr.rows, bgr.cols, CV_8U);
    for (int y = 0; y < bgr.rows; ++y)
        for (int x = 0; x < bgr.cols; ++x) {
            const auto& px = bgr.at<cv::Vec3b>(y, x);
            const double b = px[0], g = px[1], r = px[2];
            mask.at<uint8_t>(y, x) = r >= o.minRed && r >= o.redRatio * g && r >= o.redRatio * b;
        }
    cv::Mat labels;
    const int n = cv::connectedComponents(mask, labels, 8, CV_32S);
    std::vector<int> parent(static_cast<size_t>(n));
    std::iota(parent.begin(), parent.end(), 0);
    const int width = bgr.cols, last = width - 1;
    for (int y = 0; y < bgr.rows; ++y)  // column 0 continues column W-1
        for (int dy = -1; dy <= 1; ++dy) {
            if (y + dy < 0 || y + dy >= bgr.rows) continue;
            const int a = labels.at<int>(y, 0), b = labels.at<int>(y + dy, last);
            if (a > 0 && b > 0) parent[size_t(root(parent, a))] = root(parent, b);
        }
    // Each blob's columns in the order they run: from a column without red, so that a blob
    // across the wrap-around comes in one piece (a strip red in every column starts at 0).
    int start = 0;
    for (int x = 0; x < width; ++x)
        if (cv::countNonZero(mask.col(x)) == 0) {
            start = x;
            break;
        }
    std::vector<std::vector<BlobColumn>> blobs(static_cast<size_t>(n));
    std::vector<int> pixels(static_cast<size_t>(n), 0), top(static_cast<size_t>(n)),
        bottom(static_cast<size_t>(n)), inColumn(static_cast<size_t>(n), -1);
    std::vector<size_t> seen;
    for (int i = 0; i < width; ++i) {
        const int x = (start + i) % width;
        seen.clear();
        for (int y = 0; y < bgr.rows; ++y)
            if (const int l = labels.at<int>(y, x); l > 0) {
                const size_t r = size_t(root(parent, l));
                ++pixels[r];
                if (inColumn[r] != i) inColumn[r] = i, top[r] = y, seen.push_back(r);
                bottom[r] = y;
            }
        for (size_t r : seen)
            blobs[r].push_back(
                {x, bottom[r] - top[r] + 1, top[r] == 0 || bottom[r] == bgr.rows - 1});
    }
    const bool split = o.markerRadius > 0 && o.markerHeight > 0;
    std::vector<double> bearings;
    for (size_t l = 1; l < blobs.size(); ++l) {
        if (blobs[l].empty() || pixels[l] < o.minPixels) continue;
        if (split)
            splitBlob(blobs[l], p, o, bearings);
        else
            bearings.push_back(pieceOf(blobs[l], 0, blobs[l].size(), p).bearing);
    }
    return bearings;
}

}  // namespace mrloc::omnivision
