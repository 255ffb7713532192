#include <mrloc/common/Error.h>
#include <mrloc/formation/Markers.h>
#include <mrpt/opengl/CBox.h>
#include <mrpt/opengl/CTexturedPlane.h>

#include <algorithm>
#include <cmath>
#include <opencv2/aruco.hpp>

extern "C" {
#include <apriltag/apriltag.h>
#include <apriltag/tag36h11.h>
}
#include <opencv2/imgproc.hpp>

namespace mrloc::formation {

namespace {

const cv::Ptr<cv::aruco::Dictionary>& dictionary() {
    static const auto d = cv::aruco::getPredefinedDictionary(cv::aruco::DICT_APRILTAG_36h11);
    return d;
}

/** The tag as printed: its 8 x 8 cells (6 x 6 data and a black border) of 24 px on a white
 *  margin of 32 px, 256 px in all (a power of two: the renderer's texture sampling needs it,
 *  a 160 px tag came out black when small). Rows flipped: the textured plane shows the
 *  image's first row at its bottom. */
constexpr int kTagPixels = 192, kPrintedPixels = 256;
mrpt::img::CImage tagTexture(int id) {
    cv::Mat tag;
    cv::aruco::drawMarker(dictionary(), id, kTagPixels, tag, 1);
    cv::Mat printed(kPrintedPixels, kPrintedPixels, CV_8UC1, cv::Scalar(255));
    const int margin = (kPrintedPixels - kTagPixels) / 2;
    tag.copyTo(printed(cv::Rect(margin, margin, kTagPixels, kTagPixels)));
    cv::Mat rgb;
    cv::cvtColor(printed, rgb, cv::COLOR_GRAY2BGR);
    cv::flip(rgb, rgb, 0);
    return mrpt::img::CImage(rgb, mrpt::img::DEEP_COPY);
}

/** The picture in grey levels, its own copy. */
cv::Mat grayOf(const mrpt::img::CImage& picture) {
    const cv::Mat image = picture.asCvMat<cv::Mat>(mrpt::img::SHALLOW_COPY);
    cv::Mat gray;
    if (image.channels() == 3)
        cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
    else
        gray = image.clone();
    return gray;
}

}  // namespace

int markerId(size_t robot, Side side) {
    const size_t id = 4 * robot + size_t(side);
    if (id >= 587) throw Error("formation: AprilTag 36h11 has ids for 146 robots at most");
    return int(id);
}

mrpt::math::TPoint3D markerCentre(const mrpt::poses::CPose2D& robot, Side side,
                                  const MarkerOptions& o) {
    const double a = robot.phi() + double(int(side)) * M_PI / 2;
    const double r = o.bodySize / 2;
    return {robot.x() + r * std::cos(a), robot.y() + r * std::sin(a), o.tagHeight};
}

mrpt::opengl::CSetOfObjects::Ptr robotObjects(size_t robot, const MarkerOptions& o) {
    auto objects = mrpt::opengl::CSetOfObjects::Create();
    // The body stands 2 cm inside its tags: the renderer's depth buffer cannot tell a tag from
    // a face 1 mm behind it beyond about 2 m (a tag there came out black).
    const double h = o.bodySize / 2 - 0.02;
    auto body = mrpt::opengl::CBox::Create(mrpt::math::TPoint3D{-h, -h, 0},
                                           mrpt::math::TPoint3D{h, h, o.bodyHeight});
    body->setColor_u8(60, 60, 70);
    objects->insert(body);
    const double half = o.tagSize / 2 * kPrintedPixels / kTagPixels;  // with its margin
    for (const Side side : {Side::Front, Side::Left, Side::Back, Side::Right}) {
        auto plane = mrpt::opengl::CTexturedPlane::Create(-half, half, -half, half);
        plane->assignImage(tagTexture(markerId(robot, side)));
        plane->enableTextureLinearInterpolation(true);  // smooth edges: sub-pixel corners
        // printed paper: the detector needs contrast, not shading
        plane->mrpt::opengl::CRenderizableShaderTexturedTriangles::enableLight(false);
        // a tag is printed on one side: from behind, at a robot's corner, its back would cut
        // into the white margin of the next side's tag and hide it from the detector
        plane->cullFaces(mrpt::opengl::TCullFace::BACK);
        const auto c = markerCentre(mrpt::poses::CPose2D(0, 0, 0), side, o);
        const double facing = double(int(side)) * M_PI / 2;
        // The plane's +Z (its normal) outwards, its +X to the viewer's right, +Y up.
        plane->setPose(mrpt::poses::CPose3D(c.x, c.y, c.z, facing + M_PI / 2, 0, M_PI / 2));
        objects->insert(plane);
    }
    return objects;
}

void addRobot(mrpt::opengl::COpenGLScene& scene, const mrpt::poses::CPose2D& pose, size_t robot,
              const MarkerOptions& o) {
    auto objects = robotObjects(robot, o);
    objects->setPose(mrpt::poses::CPose3D(pose.x(), pose.y(), 0, pose.phi(), 0, 0));
    scene.insert(objects);
}

std::vector<MarkerSighting> detectMarkersArUco(const mrpt::img::CImage& picture) {
    const cv::Mat gray = grayOf(picture);
    std::vector<std::vector<cv::Point2f>> corners;
    std::vector<int> ids;
    const auto parameters = cv::aruco::DetectorParameters::create();
    parameters->cornerRefinementMethod = cv::aruco::CORNER_REFINE_SUBPIX;
    cv::aruco::detectMarkers(gray, dictionary(), corners, ids, parameters);
    std::vector<MarkerSighting> out;
    for (size_t i = 0; i < ids.size(); ++i) {
        // The centre: where the diagonals cross (perspective keeps straight lines straight).
        const auto& c = corners[i];
        const cv::Point2f d1 = c[2] - c[0], d2 = c[3] - c[1], w = c[1] - c[0];
        const double den = d1.x * d2.y - d1.y * d2.x;
        const double t = (w.x * d2.y - w.y * d2.x) / den;
        const double area = 0.5 * std::abs(d1.x * d2.y - d1.y * d2.x);  // a quad's, by diagonals
        const std::array<mrpt::math::TPoint2D, 4> quad{mrpt::math::TPoint2D{c[0].x, c[0].y},
                                                       {c[1].x, c[1].y},
                                                       {c[2].x, c[2].y},
                                                       {c[3].x, c[3].y}};
        out.push_back({ids[i], c[0].x + t * d1.x, c[0].y + t * d1.y, std::sqrt(area),
                       verticalEdgeHeight(quad), quad});
    }
    std::sort(out.begin(), out.end(),
              [](const MarkerSighting& a, const MarkerSighting& b) { return a.id < b.id; });
    return out;
}

std::vector<MarkerSighting> detectMarkers(const mrpt::img::CImage& picture, float decimate) {
    const cv::Mat gray = grayOf(picture);
    // One detector per thread, built once: the library's detector may not be shared across
    // threads, and building the family's decoding table costs more than a detection.
    struct AprilTag3 {
        apriltag_family_t* family = tag36h11_create();
        apriltag_detector_t* detector = apriltag_detector_create();
        AprilTag3() {
            apriltag_detector_add_family(detector, family);
            detector->quad_decimate = 2.0f;
            detector->nthreads = 1;
        }
        ~AprilTag3() {
            apriltag_detector_destroy(detector);
            tag36h11_destroy(family);
        }
    };
    thread_local AprilTag3 tags;
    apriltag_detector_t* detector = tags.detector;
    detector->quad_decimate = decimate;
    image_u8_t im{gray.cols, gray.rows, int(gray.step), gray.data};
    zarray_t* detections = apriltag_detector_detect(detector, &im);
    std::vector<MarkerSighting> out;
    for (int i = 0; i < zarray_size(detections); ++i) {
        apriltag_detection_t* d = nullptr;
        zarray_get(detections, i, &d);
        const double e1x = d->p[2][0] - d->p[0][0], e1y = d->p[2][1] - d->p[0][1];
        const double e2x = d->p[3][0] - d->p[1][0], e2y = d->p[3][1] - d->p[1][1];
        const std::array<mrpt::math::TPoint2D, 4> quad{mrpt::math::TPoint2D{d->p[0][0], d->p[0][1]},
                                                       {d->p[1][0], d->p[1][1]},
                                                       {d->p[2][0], d->p[2][1]},
                                                       {d->p[3][0], d->p[3][1]}};
        out.push_back({d->id, d->c[0], d->c[1], std::sqrt(0.5 * std::abs(e1x * e2y - e1y * e2x)),
                       verticalEdgeHeight(quad), quad});
    }
    apriltag_detections_destroy(detections);
    std::sort(out.begin(), out.end(),
              [](const MarkerSighting& a, const MarkerSighting& b) { return a.id < b.id; });
    return out;
}

MarkerSighting sightingFromCorners(int id, const std::array<mrpt::math::TPoint2D, 4>& c) {
    const mrpt::math::TPoint2D d1 = c[2] - c[0], d2 = c[3] - c[1], w = c[1] - c[0];
    const double cross = d1.x * d2.y - d1.y * d2.x;
    const double t = std::abs(cross) > 1e-12 ? (w.x * d2.y - w.y * d2.x) / cross : 0.5;
    return {id,
            c[0].x + t * d1.x,
            c[0].y + t * d1.y,
            std::sqrt(0.5 * std::abs(cross)),
            verticalEdgeHeight(c),
            c};
}

double verticalEdgeHeight(const std::array<mrpt::math::TPoint2D, 4>& c) {
    std::array<double, 4> rise;
    for (size_t i = 0; i < 4; ++i) rise[i] = std::abs(c[(i + 1) % 4].y - c[i].y);
    // opposite edges: (0, 2) and (1, 3); the pair that rises more is the vertical one
    return rise[0] + rise[2] > rise[1] + rise[3] ? 0.5 * (rise[0] + rise[2])
                                                 : 0.5 * (rise[1] + rise[3]);
}

std::optional<MarkerSighting> project(const mrpt::img::TCamera& k,
                                      const mrpt::poses::CPose3D& cameraPose,
                                      const mrpt::math::TPoint3D& point) {
    const auto local = cameraPose.inverseComposePoint(point);  // +Z forward, +X right, +Y down
    if (local.z <= 0) return std::nullopt;
    const double u = k.cx() + k.fx() * local.x / local.z;
    const double v = k.cy() + k.fy() * local.y / local.z;
    if (u < 0 || v < 0 || u >= double(k.ncols) || v >= double(k.nrows)) return std::nullopt;
    return MarkerSighting{-1, u, v, 0, 0};
}

}  // namespace mrloc::formation
