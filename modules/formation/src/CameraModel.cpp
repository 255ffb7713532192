#include <mrloc/common/Error.h>
#include <mrloc/formation/CameraModel.h>
#include <mrpt/core/format.h>

#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

namespace mrloc::formation {

namespace {

cv::Mat cameraMatrix(const mrpt::img::TCamera& k) {
    return (cv::Mat_<double>(3, 3) << k.fx(), 0, k.cx(), 0, k.fy(), k.cy(), 0, 0, 1);
}

cv::Mat distortion(const CameraModelOptions& o, double scale) {
    return (cv::Mat_<double>(1, 4) << o.k1 * scale, o.k2 * scale, o.p1 * scale, o.p2 * scale);
}

void check(bool ok, const char* key, double value, const char* bound) {
    if (!ok) throw Error(mrpt::format("[formation] %s = %g: must be %s", key, value, bound));
}

}  // namespace

struct CameraModel::Impl {
    CameraModelOptions o;
    mrpt::img::TCamera camera;  ///< the camera's own
    mrpt::img::TCamera render;  ///< the ideal picture to render: all the lens sees
    cv::Mat K, trueD, believedD;
    cv::Mat mapX, mapY;  ///< each camera pixel's ray in the ideal (rendered) picture
};

CameraModel::CameraModel(const mrpt::img::TCamera& k, const CameraModelOptions& o)
    : impl_(std::make_unique<Impl>()) {
    check(std::abs(o.k1) <= 1, "lens_k1", o.k1, "within [-1, 1]");
    check(std::abs(o.k2) <= 1, "lens_k2", o.k2, "within [-1, 1]");
    check(std::abs(o.p1) <= 0.1, "lens_p1", o.p1, "within [-0.1, 0.1]");
    check(std::abs(o.p2) <= 0.1, "lens_p2", o.p2, "within [-0.1, 0.1]");
    check(std::abs(o.calibrationError) <= 1, "lens_calibration_error", o.calibrationError,
          "within [-1, 1]");
    check(o.blur >= 0 && o.blur <= 10, "camera_blur", o.blur, "in [0, 10] px");
    check(o.noise >= 0 && o.noise <= 100, "camera_noise", o.noise, "in [0, 100] grey levels");
    check(o.exposure > 0 && o.exposure <= 4, "camera_exposure", o.exposure, "in (0, 4]");
    impl_->o = o;
    impl_->K = cameraMatrix(k);
    impl_->trueD = distortion(o, 1);
    impl_->believedD = distortion(o, 1 + o.calibrationError);
    impl_->render = impl_->camera = k;
    if (o.k1 == 0 && o.k2 == 0 && o.p1 == 0 && o.p2 == 0) return;
    // A camera pixel sees the ray that its undistorted position has in the pinhole picture.
    std::vector<cv::Point2f> pixels, rays;
    pixels.reserve(size_t(k.ncols) * k.nrows);
    for (uint32_t v = 0; v < k.nrows; ++v)
        for (uint32_t u = 0; u < k.ncols; ++u) pixels.emplace_back(float(u), float(v));
    cv::undistortPoints(pixels, rays, impl_->K, impl_->trueD, cv::noArray(), impl_->K);
    // A barrel lens sees beyond the pinhole picture of the same focal length: the ideal
    // picture is rendered as large as the rays reach (same focal length, the principal point
    // moved by the margin), so that no camera pixel samples outside it.
    float minX = 0, minY = 0, maxX = float(k.ncols - 1), maxY = float(k.nrows - 1);
    for (const auto& r : rays) {
        if (!std::isfinite(r.x) || !std::isfinite(r.y))
            throw Error(
                "[formation] lens_k1, lens_k2, lens_p1, lens_p2: the lens model folds "
                "over inside the picture (a pixel has no ray)");
        minX = std::min(minX, r.x), maxX = std::max(maxX, r.x);
        minY = std::min(minY, r.y), maxY = std::max(maxY, r.y);
    }
    const double left = std::ceil(-minX) + 2, top = std::ceil(-minY) + 2;
    // whole multiples of 4 px: the renderer reads rows without padding (sim::PinholeCamera)
    const double width = 4 * std::ceil((std::ceil(maxX) + 3 + left) / 4);
    const double height = 4 * std::ceil((std::ceil(maxY) + 3 + top) / 4);
    if (width > 4 * double(k.ncols) || height > 4 * double(k.nrows))
        throw Error(mrpt::format(
            "[formation] lens_k1 = %g, lens_k2 = %g: the lens sees more than 4 times the "
            "pinhole picture's width or height; give a weaker distortion",
            o.k1, o.k2));
    impl_->render.ncols = uint32_t(width), impl_->render.nrows = uint32_t(height);
    impl_->render.setIntrinsicParamsFromValues(k.fx(), k.fy(), k.cx() + left, k.cy() + top);
    impl_->mapX.create(int(k.nrows), int(k.ncols), CV_32FC1);
    impl_->mapY.create(int(k.nrows), int(k.ncols), CV_32FC1);
    for (uint32_t v = 0, i = 0; v < k.nrows; ++v)
        for (uint32_t u = 0; u < k.ncols; ++u, ++i) {
            impl_->mapX.at<float>(int(v), int(u)) = rays[i].x + float(left);
            impl_->mapY.at<float>(int(v), int(u)) = rays[i].y + float(top);
        }
}

const mrpt::img::TCamera& CameraModel::renderIntrinsics() const { return impl_->render; }
const mrpt::img::TCamera& CameraModel::intrinsics() const { return impl_->camera; }

CameraModel::~CameraModel() = default;
CameraModel::CameraModel(CameraModel&&) noexcept = default;
CameraModel& CameraModel::operator=(CameraModel&&) noexcept = default;

const CameraModelOptions& CameraModel::options() const { return impl_->o; }

mrpt::img::CImage CameraModel::degrade(const mrpt::img::CImage& rendered,
                                       mrpt::random::CRandomGenerator& rng) const {
    const auto& o = impl_->o;
    const cv::Mat image = rendered.asCvMat<cv::Mat>(mrpt::img::SHALLOW_COPY);
    cv::Mat gray;
    if (image.channels() == 3)
        cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
    else
        gray = image.clone();
    if (gray.cols != int(impl_->render.ncols) || gray.rows != int(impl_->render.nrows))
        throw Error("formation: a picture for the camera model is not of renderIntrinsics()' size");
    if (!impl_->mapX.empty()) {  // the lens: straight lines bend
        cv::Mat bent;
        cv::remap(gray, bent, impl_->mapX, impl_->mapY, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
        gray = bent;
    }
    if (o.blur > 0) cv::GaussianBlur(gray, gray, cv::Size(0, 0), o.blur);
    cv::Mat levels;
    gray.convertTo(levels, CV_32F, o.exposure);
    if (o.noise > 0) {
        // OpenCV's generator seeded from the run's: the same seed, the same picture, at a
        // fraction of the cost of one draw of the run's generator per pixel
        cv::RNG noise(rng.drawUniform64bit());
        cv::Mat n(levels.size(), CV_32F);
        noise.fill(n, cv::RNG::NORMAL, 0.0, o.noise);
        levels += n;
    }
    cv::Mat out;
    levels.convertTo(out, CV_8U);  // saturates: an over-exposed tag loses its white margin
    return mrpt::img::CImage(out, mrpt::img::DEEP_COPY);
}

std::vector<MarkerSighting> CameraModel::see(const mrpt::img::CImage& rendered,
                                             mrpt::random::CRandomGenerator& rng) const {
    if (impl_->o.ideal()) return detectMarkers(rendered, 1);
    auto tags = detectMarkers(degrade(rendered, rng), 1);
    if (impl_->mapX.empty()) return tags;
    // the robot's own undistortion of each tag's corners (its calibration, OpenCV's)
    for (auto& t : tags) {
        std::vector<cv::Point2f> c, ideal;
        for (const auto& p : t.corners) c.emplace_back(float(p.x), float(p.y));
        cv::undistortPoints(c, ideal, impl_->K, impl_->believedD, cv::noArray(), impl_->K);
        std::array<mrpt::math::TPoint2D, 4> q;
        for (size_t i = 0; i < 4; ++i) q[i] = {ideal[i].x, ideal[i].y};
        t = sightingFromCorners(t.id, q);
    }
    return tags;
}

}  // namespace mrloc::formation
