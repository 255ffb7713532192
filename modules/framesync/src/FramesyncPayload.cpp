#include <mrloc/common/Error.h>
#include <mrloc/framesync/FramesyncPayload.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>
#include <mrpt/obs/CObservationComment.h>

#include <algorithm>
#include <cmath>
#include <mutex>

namespace mrloc::framesync {

namespace {
const std::string kCommentPrefix = "framesync: ";
}

std::shared_ptr<const FloorSlices> sliceWorld(const sim::World& world, const SonarRigOptions& rig) {
    auto slices = std::make_shared<FloorSlices>();
    for (const auto& m : rig.mounts)
        if (!slices->count(m.pose.z())) slices->emplace(m.pose.z(), FloorSlice(world, m.pose.z()));
    return slices;
}

std::shared_ptr<const FloorSlices> sharedSlices(const std::shared_ptr<const sim::World>& world,
                                                const SonarRigOptions& rig) {
    std::vector<double> heights;
    for (const auto& m : rig.mounts) heights.push_back(m.pose.z());
    std::sort(heights.begin(), heights.end());
    heights.erase(std::unique(heights.begin(), heights.end()), heights.end());
    struct Last {  // the world is held, so its address names no other world
        std::shared_ptr<const sim::World> world;
        std::vector<double> heights;
        std::shared_ptr<const FloorSlices> slices;
    };
    static std::mutex mutex;
    static Last last;
    const std::lock_guard<std::mutex> lock(mutex);
    if (last.world != world || last.heights != heights)
        last = {world, heights, sliceWorld(*world, rig)};
    return last.slices;
}

std::string redefinitionText(const RedefinitionEvent& e) {
    return kCommentPrefix +
           mrpt::format(
               "%s redefined its frame to version %u on %s's wall %llu: turned %.3f "
               "deg, moved %.4f m",
               e.robot.c_str(), e.version, e.reference.c_str(), (unsigned long long)e.referenceWall,
               mrpt::RAD2DEG(e.redefinition.rotation), e.redefinition.shift);
}

bool isRedefinitionText(const std::string& text) {
    return text.rfind(kCommentPrefix, 0) == 0 &&
           text.find(" redefined its frame ") != std::string::npos;
}

FramesyncPayload::FramesyncPayload(const FramesyncConfig& config, double dt,
                                   std::shared_ptr<const FloorSlices> slices)
    : config_(config), team_(config.team), slices_(std::move(slices)) {
    const double steps = 1.0 / (config_.rig.rate * dt);
    every_ = std::max<long>(1, std::lround(steps));
    if (std::abs(steps - double(every_)) > 1e-6 * steps)
        throw Error(
            mrpt::format("[framesync] sonar_rate = %g Hz is not a whole number of "
                         "[scenario] dt = %g s steps",
                         config_.rig.rate, dt));
}

void FramesyncPayload::sense(sim::Step& step) {
    if (!slices_) slices_ = sliceWorld(step.world, config_.rig);
    // the decision layers' record of the redefinitions since the last step
    for (const auto& e : team_.takeNewEvents()) {
        auto c = mrpt::obs::CObservationComment::Create();
        c->sensorLabel = e.robot + ".framesync";
        c->timestamp = step.stamp;
        c->text = redefinitionText(e);
        step.emit(c);
    }
    if (step.index % every_ != 0) return;
    std::vector<const FloorSlice*> perMount;
    for (const auto& m : config_.rig.mounts) perMount.push_back(&slices_->at(m.pose.z()));
    for (size_t i = 0; i < step.fleet.size(); ++i) {
        const auto& robot = step.fleet.robot(i);
        auto obs = readSonars(perMount, robot.pose(), config_.rig, step.rng);
        obs->sensorLabel = robot.options().name + ".sonar";
        obs->timestamp = step.stamp;
        step.emit(obs);
    }
}

}  // namespace mrloc::framesync
