#include <mrloc/common/Error.h>
#include <mrloc/formation/AlgorithmOne.h>
#include <mrloc/formation/CameraModel.h>
#include <mrpt/math/wrap2pi.h>

#include <cmath>
#include <optional>

namespace mrloc::formation {

mrpt::poses::CPose3D rearCameraPose(const mrpt::poses::CPose2D& robot, double bodySize,
                                    double height) {
    const double back = bodySize / 2;
    return sim::cameraPoseLooking({robot.x() - back * std::cos(robot.phi()),
                                   robot.y() - back * std::sin(robot.phi()), height},
                                  robot.phi() + M_PI);
}

mrpt::poses::CPose3D frontCameraPose(const mrpt::poses::CPose2D& robot, double bodySize,
                                     double height) {
    const double ahead = bodySize / 2;
    return sim::cameraPoseLooking({robot.x() + ahead * std::cos(robot.phi()),
                                   robot.y() + ahead * std::sin(robot.phi()), height},
                                  robot.phi());
}

namespace {

/** What Algorithm 1 reads from a frame: the anchor's and the base beacons' centres (px),
 *  each from the beacon's largest tag in view (the side facing the camera), moved from the
 *  tag to the robot's centre by `shift` (the believed offset of that side's tag); and the
 *  base tags' sizes over the sizes predicted at the vertex (`size`): inverse depth ratios. */
struct Reading {
    double ua = 0, u1 = 0, u2 = 0;
    double near1 = 1, near2 = 1;
};

template <typename Shift, typename Size>
std::optional<Reading> read(const std::vector<MarkerSighting>& tags, const BeaconTriangle& b,
                            Shift shift, Size size) {
    std::array<std::optional<MarkerSighting>, 3> best;
    for (const auto& t : tags)
        for (int i = 0; i < 3; ++i)
            if (size_t(t.id / 4) == b.robot[i] && (!best[i] || t.size > best[i]->size)) best[i] = t;
    if (!best[0] || !best[1] || !best[2]) return std::nullopt;
    const auto centre = [&](int i) { return best[i]->u - shift(i, Side(best[i]->id % 4)); };
    const auto near = [&](int i) {
        const double predicted = size(i, Side(best[i]->id % 4));
        return predicted > 0 ? best[i]->height / predicted : 1.0;
    };
    return Reading{centre(2), centre(0), centre(1), near(0), near(1)};
}

/** A tag's height in the picture (verticalEdgeHeight, as the detector measures it). */
double projectedHeight(const mrpt::img::TCamera& k, const mrpt::poses::CPose3D& camera,
                       const mrpt::poses::CPose2D& robot, Side side, const MarkerOptions& m) {
    const auto c = markerCentre(robot, side, m);
    const double facing = robot.phi() + double(int(side)) * M_PI / 2;
    const double a = m.tagSize / 2;
    const mrpt::math::TPoint3D across{-std::sin(facing) * a, std::cos(facing) * a, 0}, up{0, 0, a};
    std::array<std::optional<MarkerSighting>, 4> p{
        project(k, camera, c - across - up), project(k, camera, c + across - up),
        project(k, camera, c + across + up), project(k, camera, c - across + up)};
    for (const auto& q : p)
        if (!q) return 0;
    return verticalEdgeHeight({mrpt::math::TPoint2D{p[0]->u, p[0]->v},
                               {p[1]->u, p[1]->v},
                               {p[2]->u, p[2]->v},
                               {p[3]->u, p[3]->v}});
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

AlgorithmOneController::AlgorithmOneController(const BeaconTriangle& beacons,
                                               const mrpt::img::TCamera& k,
                                               const MarkerOptions& markers,
                                               const AlgorithmOneOptions& o)
    : beacons_(beacons), k_(k), o_(o) {
    const double f = k.fx(), h = o.side * std::sqrt(3.0) / 2;
    dt_ = targetDisparity(k, markers, o.side);
    // How the readings answer the robot's motion, to first order about the perfect vertex: the
    // pictures move with the tags (the shift to the centres is a constant), the base tags at
    // depth Db and the anchor's at Da from the camera. Asymmetry d_m1 - d_m2 per metre of
    // lateral offset towards b1: -gain; d_m per metre of depth: -slope.
    const double Db = h - markers.bodySize, Da = 2 * h - markers.bodySize;
    gain_ = 2 * f * (1 / Db - 1 / Da);
    slope_ = f * (o.side / 2) / (Db * Db);
    // Where each tag shows beside its robot's centre, seen from the perfect vertex (seed 003's
    // robots carry tags on their sides, not on their centres).
    const auto& bp = beacons.pose;
    const mrpt::math::TPoint2D vertex{bp[0].x() + bp[1].x() - bp[2].x(),
                                      bp[0].y() + bp[1].y() - bp[2].y()};
    const auto idealCamera =
        rearCameraPose({vertex.x, vertex.y, std::atan2(vertex.y - bp[2].y(), vertex.x - bp[2].x())},
                       markers.bodySize, o.cameraHeight);
    for (int b = 0; b < 3; ++b)
        for (int side = 0; side < 4; ++side) {
            const auto tag = project(k, idealCamera, markerCentre(bp[b], Side(side), markers));
            const auto centre = project(k, idealCamera, {bp[b].x(), bp[b].y(), markers.tagHeight});
            // Out of the perfect vertex's picture, the beacon is out of the real one too and is
            // never read: its shift is not used.
            shift_[b][side] = tag && centre ? tag->u - centre->u : 0.0;
            size_[b][side] = projectedHeight(k, idealCamera, bp[b], Side(side), markers);
        }
}

std::optional<std::vector<Maneuver>> AlgorithmOneController::decide(
    const std::vector<MarkerSighting>& tags) {
    const auto reading = read(
        tags, beacons_, [&](int b, Side side) { return shift_[b][int(side)]; },
        [&](int b, Side side) { return size_[b][int(side)]; });
    if (!reading) return std::nullopt;  // a beacon out of view: Algorithm 1 cannot go on
    const double f = k_.fx();
    const double ec = reading->ua - k_.cx();
    dm1_ = std::abs(reading->u1 - reading->ua);
    dm2_ = std::abs(reading->u2 - reading->ua);
    // seed 003 Algorithm 1, step 1: the anchor at the centre of the rear image. A point
    // right of centre lies right of the camera, left of the robot: turn towards it.
    std::vector<Maneuver> out;
    if (std::abs(ec) > o_.pixelTolerance) {
        out.push_back(Maneuver::turn(-std::atan2(ec, f)));
        if (!o_.together) return out;  // and look again
    }
    // Steps 3-9: while d_m1 != d_m2, turn towards the beacon that looks farther and move
    // sideways (the robot is a unicycle: turn a right angle, drive, turn back).
    double es = dm1_ - dm2_;
    if (o_.lateral == AlgorithmOneOptions::Lateral::Midpoint) {
        // the base midpoint's image: the base tags' weighted by depth (1 / nearness)
        const double z1 = 1 / reading->near1, z2 = 1 / reading->near2;
        const double uM = (reading->u1 * z1 + reading->u2 * z2) / (z1 + z2);
        // in the paper's terms, es = 2 (midpoint of the images - anchor), signed by b1's side
        es = 2 * (uM - reading->ua) * (reading->u1 > reading->u2 ? 1 : -1);
    }
    if (std::abs(es) > o_.pixelTolerance) {
        const double offset = -es / gain_;  // m, the robot's offset towards b1
        // b1 right of the anchor in the image: on the camera's right, the robot's left.
        const double towardsB1 = reading->u1 > reading->ua ? M_PI / 2 : -M_PI / 2;
        for (const auto& m :
             {Maneuver::turn(towardsB1), Maneuver::drive(-offset), Maneuver::turn(-towardsB1)})
            out.push_back(m);
        if (!o_.together) return out;
    }
    // Steps 10-17: forward (away) while d_m1 > d_t, back while d_m1 < d_t.
    const double dm = 0.5 * (dm1_ + dm2_);
    if (std::abs(dm - dt_) > o_.pixelTolerance) out.push_back(Maneuver::drive((dm - dt_) / slope_));
    return out;
}

void applyManeuver(mrpt::poses::CPose2D& pose, const Maneuver& m) {
    if (m.kind == Maneuver::Kind::Turn) {
        pose.phi(mrpt::math::wrapToPi(pose.phi() + m.amount));
    } else {
        pose.x(pose.x() + m.amount * std::cos(pose.phi()));
        pose.y(pose.y() + m.amount * std::sin(pose.phi()));
    }
}

Maneuver executed(Maneuver m, const ManeuverNoise& noise, mrpt::random::CRandomGenerator& rng) {
    const double sd = m.kind == Maneuver::Kind::Turn ? noise.turn : noise.drive;
    m.amount *= 1 + sd * rng.drawGaussian1D_normalized();
    if (noise.slip > 0) m.amount *= 1 - std::abs(noise.slip * rng.drawGaussian1D_normalized());
    return m;
}

AlgorithmOneResult runAlgorithmOne(const mrpt::opengl::COpenGLScene& scene,
                                   const BeaconTriangle& beacons, mrpt::poses::CPose2D start,
                                   sim::PinholeCamera& camera, const MarkerOptions& markers,
                                   const AlgorithmOneOptions& o,
                                   mrpt::random::CRandomGenerator& rng, const CameraModel* lens) {
    AlgorithmOneController controller(beacons, lens ? lens->intrinsics() : camera.intrinsics(),
                                      markers, o);
    AlgorithmOneResult r;
    auto pose = start;
    const auto execute = [&](const Maneuver& planned) {
        applyManeuver(pose, executed(planned, o.noise, rng));
        ++r.maneuvers;
    };
    while (r.maneuvers < o.maxManeuvers) {
        const auto frame =
            camera.render(scene, rearCameraPose(pose, markers.bodySize, o.cameraHeight));
        ++r.frames;
        const auto maneuvers =
            controller.decide(lens ? lens->see(frame, rng) : detectMarkers(frame));
        r.dm1 = controller.dm1(), r.dm2 = controller.dm2();
        if (!maneuvers) break;
        if (maneuvers->empty()) {
            r.converged = true;
            break;
        }
        for (const auto& m : *maneuvers) execute(m);
    }
    r.end = pose;
    return r;
}

}  // namespace mrloc::formation
