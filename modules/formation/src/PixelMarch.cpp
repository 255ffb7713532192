#include <mrloc/common/Error.h>
#include <mrloc/formation/FormationScene.h>
#include <mrloc/formation/PixelMarch.h>
#include <mrpt/math/wrap2pi.h>

#include <cmath>

namespace mrloc::formation {

CameraMoveOptions cameraMoveOptions(const FormationConfig& c) {
    CameraMoveOptions o;
    o.side = c.formation.side;
    o.intrinsics = c.cameraIntrinsics();
    o.algorithmOne.side = c.formation.side;
    o.algorithmOne.pixelTolerance = c.pixelTolerance;
    o.algorithmOne.lateral = c.lateral;
    o.algorithmOne.together = c.together;
    o.algorithmOne.noise = c.maneuverNoise;
    o.gateStop = c.gateStop;
    o.latticeFit = c.latticeFit;
    return o;
}

PixelMarchOptions pixelMarchOptions(const FormationConfig& c, double wheelSpeed) {
    PixelMarchOptions o;
    o.march.formation = c.formation;
    o.march.wheelRadius = c.wheelRadius;
    o.march.wheelSpeed = wheelSpeed;
    o.march.maxMoves = c.maxMoves;
    o.camera = cameraMoveOptions(c);
    o.lens = c.lens;
    o.maxTurnRate = c.maxTurnRate;
    return o;
}

mrpt::img::TCamera renderIntrinsics(const PixelMarchOptions& o) {
    return CameraModel(o.camera.intrinsics, o.lens).renderIntrinsics();
}

double latticeRotation(const std::vector<TPoint2D>& believed, const std::vector<TPoint2D>& truth) {
    TPoint2D cb{0, 0}, ct{0, 0};
    for (size_t i = 0; i < believed.size(); ++i) cb = cb + believed[i], ct = ct + truth[i];
    cb = cb * (1.0 / double(believed.size())), ct = ct * (1.0 / double(truth.size()));
    double cross = 0, dot = 0;
    for (size_t i = 0; i < believed.size(); ++i) {
        const TPoint2D a = believed[i] - cb, b = truth[i] - ct;
        cross += a.x * b.y - a.y * b.x;
        dot += a.x * b.x + a.y * b.y;
    }
    return std::atan2(cross, dot);
}

PixelMarchResult pixelMarch(size_t robots, const std::vector<TPoint2D>& route,
                            const std::vector<Obstacle>& obstacles, const PixelMarchOptions& o,
                            sim::PinholeCamera& camera, mrpt::random::CRandomGenerator& rng) {
    const double speed = o.march.wheelRadius * o.march.wheelSpeed;
    if (!(speed > 0) || !std::isfinite(speed))
        throw Error("formation: the robots' speed must be positive");
    if (!(o.maxTurnRate > 0)) throw Error("formation: the robots' turn rate must be positive");
    const auto& markers = o.camera.markers;
    const double cameraHeight = o.camera.algorithmOne.cameraHeight;
    PixelMarchResult r;
    auto& m = r.march;
    m.ideal = m.actual = initialStrip(robots, o.march.formation.side);
    std::vector<mrpt::poses::CPose2D> pose;  // every robot's true pose
    for (const auto& p : m.actual) pose.emplace_back(p.x, p.y, 0);
    std::vector<double> believedHeading(robots, 0);  // seed 003 sec. 5: all face east
    FormationScene scene(robots, markers);
    const CameraModel lens(o.camera.intrinsics, o.lens);
    if (camera.intrinsics().ncols != lens.renderIntrinsics().ncols ||
        camera.intrinsics().nrows != lens.renderIntrinsics().nrows)
        throw Error("formation: a pixel march's camera must render renderIntrinsics(options)");
    RoutePlanner planner(route, o.march.formation, o.march.maxMoves);
    double time = 0;
    for (;;) {
        const auto outcome = planner.plan(m.ideal, obstacles);
        if (outcome == RoutePlanner::Outcome::Stuck) return r;  // arrived stays false
        if (outcome == RoutePlanner::Outcome::Arrived) break;
        const Move& move = *planner.move();
        const size_t k = move.robot;
        // the scene about the mover (single precision), the mover not in its own view
        scene.setOrigin({pose[k].x(), pose[k].y()});
        for (size_t i = 0; i < robots; ++i) scene.place(i, pose[i]), scene.show(i, i != k);
        CameraMove cameraMove(move, m.ideal, believedHeading, o.camera);
        auto& p = pose[k];
        const auto execute = [&](const std::vector<Maneuver>& planned) {
            for (const auto& plan : planned) {
                const Maneuver e = executed(plan, o.camera.algorithmOne.noise, rng);
                applyManeuver(p, e);
                time +=
                    std::abs(e.amount) / (e.kind == Maneuver::Kind::Turn ? o.maxTurnRate : speed);
            }
        };
        execute(cameraMove.start());
        while (const auto which = cameraMove.camera()) {
            const auto local = scene.local(p);
            const auto cameraPose = *which == CameraMove::Camera::Front
                                        ? frontCameraPose(local, markers.bodySize, cameraHeight)
                                        : rearCameraPose(local, markers.bodySize, cameraHeight);
            const auto tags = lens.see(camera.render(scene.scene(), cameraPose), rng);
            ++r.frames;
            execute(cameraMove.decide(tags));
        }
        r.lostMoves += cameraMove.lost() ? 1 : 0;
        r.blindGates += size_t(cameraMove.blindGates());
        const TPoint2D end{p.x(), p.y()};
        const auto& a = m.actual;  // the step's own error, on the true beacons
        const auto e = stepError(a[move.base[0]], a[move.base[1]], a[move.anchor], end);
        r.lateral.push_back(e.lateral);
        r.longitudinal.push_back(e.longitudinal);
        believedHeading[k] = arrivalHeading(move, m.ideal);
        m.ideal[k] = move.target;
        m.actual[k] = end;
        m.moves.push_back({time, k, m.ideal[k], m.actual[k]});
        r.rotation.push_back(latticeRotation(m.ideal, m.actual));
    }
    m.arrived = true;
    return r;
}

}  // namespace mrloc::formation
