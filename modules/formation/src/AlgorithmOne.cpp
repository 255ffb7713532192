#include <mrloc/common/Error.h>
#include <mrloc/formation/AlgorithmOne.h>
#include <mrpt/math/wrap2pi.h>

#include <cmath>
#include <optional>

namespace mrloc::formation {

namespace {

/** The rear camera sits on the robot's back face, looking backwards. */
mrpt::poses::CPose3D rearCameraPose(const mrpt::poses::CPose2D& robot, double bodySize,
                                    double height) {
    const double back = bodySize / 2;
    return sim::cameraPoseLooking({robot.x() - back * std::cos(robot.phi()),
                                   robot.y() - back * std::sin(robot.phi()), height},
                                  robot.phi() + M_PI);
}

/** What Algorithm 1 reads from a frame: the anchor's and the base beacons' centres (px),
 *  each from the beacon's largest tag in view (the side facing the camera), moved from the
 *  tag to the robot's centre by `shift` (the believed offset of that side's tag). */
struct Reading {
    double ua = 0, u1 = 0, u2 = 0;
};

template <typename Shift>
std::optional<Reading> read(const std::vector<MarkerSighting>& tags, const BeaconTriangle& b,
                            Shift shift) {
    std::array<std::optional<MarkerSighting>, 3> best;
    for (const auto& t : tags)
        for (int i = 0; i < 3; ++i)
            if (size_t(t.id / 4) == b.robot[i] && (!best[i] || t.size > best[i]->size)) best[i] = t;
    if (!best[0] || !best[1] || !best[2]) return std::nullopt;
    const auto centre = [&](int i) { return best[i]->u - shift(i, Side(best[i]->id % 4)); };
    return Reading{centre(2), centre(0), centre(1)};
}

}  // namespace

BuildingStep buildingStep(double side, const MarkerOptions& markers) {
    const double h = side * std::sqrt(3.0) / 2;
    BuildingStep b;
    sim::WorldOptions world;
    world.sizeX = world.sizeY = 20;
    b.scene = sim::makeWorldScene(world, false);
    b.beacons.pose = {mrpt::poses::CPose2D(0, 0, 0), mrpt::poses::CPose2D(side, 0, 0),
                      mrpt::poses::CPose2D(side / 2, h, 0)};
    for (size_t r = 0; r < 3; ++r) addRobot(*b.scene, b.beacons.pose[r], r, markers);
    b.vertex = mrpt::poses::CPose2D(side / 2, -h, -M_PI / 2);
    return b;
}

mrpt::img::TCamera cameraIntrinsics(double f) {
    mrpt::img::TCamera k;
    k.ncols = 1280;
    k.nrows = 720;
    k.setIntrinsicParamsFromValues(f, f, 640, 360);
    return k;
}

double targetDisparity(const mrpt::img::TCamera& k, const MarkerOptions& m, double side) {
    const double h = side * std::sqrt(3.0) / 2;
    return k.fx() * (side / 2) / (h - m.bodySize / 2);
}

AlgorithmOneResult runAlgorithmOne(const mrpt::opengl::COpenGLScene& scene,
                                   const BeaconTriangle& beacons, mrpt::poses::CPose2D start,
                                   sim::PinholeCamera& camera, const MarkerOptions& markers,
                                   const AlgorithmOneOptions& o,
                                   mrpt::random::CRandomGenerator& rng) {
    const auto& k = camera.intrinsics();
    const double f = k.fx(), h = o.side * std::sqrt(3.0) / 2;
    const double dt = targetDisparity(k, markers, o.side);
    // How the readings answer the robot's motion, to first order about the perfect vertex: the
    // pictures move with the tags (the shift to the centres is a constant), the base tags at
    // depth Db and the anchor's at Da from the camera. Asymmetry d_m1 - d_m2 per metre of
    // lateral offset towards b1: -gain; d_m per metre of depth: -slope.
    const double Db = h - markers.bodySize, Da = 2 * h - markers.bodySize;
    // Where each tag shows beside its robot's centre, seen from the perfect vertex (seed 003's
    // robots carry tags on their sides, not on their centres).
    const auto& bp = beacons.pose;
    const mrpt::math::TPoint2D vertex{bp[0].x() + bp[1].x() - bp[2].x(),
                                      bp[0].y() + bp[1].y() - bp[2].y()};
    const auto idealCamera =
        rearCameraPose({vertex.x, vertex.y, std::atan2(vertex.y - bp[2].y(), vertex.x - bp[2].x())},
                       markers.bodySize, o.cameraHeight);
    const auto shift = [&](int beacon, Side side) {
        const auto tag = project(k, idealCamera, markerCentre(bp[beacon], side, markers));
        const auto centre =
            project(k, idealCamera, {bp[beacon].x(), bp[beacon].y(), markers.tagHeight});
        // Out of the perfect vertex's picture, the beacon is out of the real one too and is
        // never read: its shift is not used.
        return tag && centre ? tag->u - centre->u : 0.0;
    };
    const double gain = 2 * f * (1 / Db - 1 / Da);
    const double slope = f * (o.side / 2) / (Db * Db);
    AlgorithmOneResult r;
    auto pose = start;
    const auto turn = [&](double angle) {  // in place, with its relative error
        pose.phi(mrpt::math::wrapToPi(pose.phi() +
                                      angle * (1 + o.turnNoise * rng.drawGaussian1D_normalized())));
        ++r.maneuvers;
    };
    const auto drive = [&](double distance) {  // along the heading (negative: backwards)
        const double d = distance * (1 + o.driveNoise * rng.drawGaussian1D_normalized());
        pose.x(pose.x() + d * std::cos(pose.phi()));
        pose.y(pose.y() + d * std::sin(pose.phi()));
        ++r.maneuvers;
    };
    while (r.maneuvers < o.maxManeuvers) {
        const auto cameraPose = rearCameraPose(pose, markers.bodySize, o.cameraHeight);
        const auto frame = camera.render(scene, cameraPose);
        ++r.frames;
        const auto reading = read(detectMarkers(frame), beacons, shift);
        if (!reading) break;  // a beacon out of view: Algorithm 1 cannot go on
        const double ec = reading->ua - k.cx();
        r.dm1 = std::abs(reading->u1 - reading->ua);
        r.dm2 = std::abs(reading->u2 - reading->ua);
        // seed 003 Algorithm 1, step 1: the anchor at the centre of the rear image. A point
        // right of centre lies right of the camera, left of the robot: turn towards it.
        if (std::abs(ec) > o.pixelTolerance) {
            turn(-std::atan2(ec, f));
            continue;
        }
        // Steps 3-9: while d_m1 != d_m2, turn towards the beacon that looks farther and move
        // sideways (the robot is a unicycle: turn a right angle, drive, turn back).
        const double es = r.dm1 - r.dm2;
        if (std::abs(es) > o.pixelTolerance) {
            const double offset = -es / gain;  // m, the robot's offset towards b1
            // b1 right of the anchor in the image: on the camera's right, the robot's left.
            const double towardsB1 = reading->u1 > reading->ua ? M_PI / 2 : -M_PI / 2;
            turn(towardsB1);
            drive(-offset);
            turn(-towardsB1);
            continue;
        }
        // Steps 10-17: forward (away) while d_m1 > d_t, back while d_m1 < d_t.
        const double dm = 0.5 * (r.dm1 + r.dm2);
        if (std::abs(dm - dt) > o.pixelTolerance) {
            drive((dm - dt) / slope);
            continue;
        }
        r.converged = true;
        break;
    }
    r.end = pose;
    return r;
}

}  // namespace mrloc::formation
