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
    std::vector<double> sx(size_t(n), 0), sy(size_t(n), 0);
    std::vector<int> count(size_t(n), 0);
    std::vector<double> cosOf(size_t(bgr.cols)), sinOf(size_t(bgr.cols));
    for (int x = 0; x < bgr.cols; ++x) {
        const double a = p.bearingOfColumn(x);
        cosOf[size_t(x)] = std::cos(a), sinOf[size_t(x)] = std::sin(a);
    }
    for (int y = 0; y < bgr.rows; ++y)
        for (int x = 0; x < bgr.cols; ++x)
            if (const int l = labels.at<int>(y, x); l > 0) {
                const size_t r = size_t(root(parent, l));
                sx[r] += cosOf[size_t(x)], sy[r] += sinOf[size_t(x)], ++count[r];
            }
    std::vector<double> bearings;
    for (int l = 1; l < n; ++l)
        if (root(parent, l) == l && count[size_t(l)] >= o.minPixels)
            bearings.push_back(std::atan2(sy[size_t(l)], sx[size_t(l)]));
    return bearings;
}

}  // namespace mrloc::omnivision
