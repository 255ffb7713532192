#include <mrloc/common/Error.h>
#include <mrloc/omnivision/MarkerDetector.h>
#include <mrpt/core/format.h>

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
    const int last = bgr.cols - 1;
    for (int y = 0; y < bgr.rows; ++y)  // column 0 continues column W-1
        for (int dy = -1; dy <= 1; ++dy) {
            if (y + dy < 0 || y + dy >= bgr.rows) continue;
            const int a = labels.at<int>(y, 0), b = labels.at<int>(y + dy, last);
            if (a > 0 && b > 0) parent[size_t(root(parent, a))] = root(parent, b);
        }
    // A marker's bearing is the middle of the azimuths its columns span. Each column counts
    // once, by the angle it spans: a pinhole view's columns are even in the image, not in
    // azimuth (one at 45 degrees off the view's axis spans half the angle of one on it), and
    // a column's red rows grow with 1 / depth along the view's axis, which differs across a
    // marker off the axis. A mean over pixels leans away from the axis by up to 0.16 deg for
    // the markers 3 m away in omnivision_5robots.ini; over columns by angle it does not.
    std::vector<int> count(size_t(n), 0), counted(size_t(n), -1);  // column last counted in
    std::vector<double> sx(size_t(n), 0), sy(size_t(n), 0);
    for (int x = 0; x < bgr.cols; ++x) {
        const double a = p.bearingOfColumn(x);
        const double span = std::abs(
            std::remainder(p.bearingOfColumn(x - 0.5) - p.bearingOfColumn(x + 0.5), 2 * M_PI));
        for (int y = 0; y < bgr.rows; ++y)
            if (const int l = labels.at<int>(y, x); l > 0) {
                const size_t r = size_t(root(parent, l));
                ++count[r];
                if (counted[r] == x) continue;  // the column counts once per marker
                counted[r] = x;
                sx[r] += span * std::cos(a), sy[r] += span * std::sin(a);
            }
    }
    std::vector<double> bearings;
    for (int l = 1; l < n; ++l)
        if (root(parent, l) == l && count[size_t(l)] >= o.minPixels)
            bearings.push_back(std::atan2(sy[size_t(l)], sx[size_t(l)]));
    return bearings;
}

}  // namespace mrloc::omnivision
