// Impossible values in a rawlog (issue 26): each method's rawlog, mutated one way at a time
// (NaN, infinity, huge, negative, time stamps negative, zero or backwards, copies of one
// observation), is refused with one line naming the entry or skipped and counted in
// metrics.json: never taken as data (exit 0 with nothing counted), and no NaN reaches an
// output. The counts are printed; scripts/mutate.sh is not needed: this is the run.
#include <gtest/gtest.h>
#include <mrloc/common/Metrics.h>
#include <mrloc/common/Rawlog.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservationBeaconRanges.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CObservationRange.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <optional>

#include "MrlocCli.h"
#include "TestPaths.h"

namespace fs = std::filesystem;
using namespace mrloc;
using namespace mrloc::testing_cli;
using mrpt::obs::CObservation;

namespace {

/** Changes one observation's value; false if it has none of that kind. */
using Mutation = std::function<bool(CObservation&, double value)>;

bool setMainValue(CObservation& o, double v) {
    using namespace mrpt::obs;
    if (auto* b = dynamic_cast<CObservationBeaconRanges*>(&o); b && !b->sensedData.empty())
        return b->sensedData.front().sensedDistance = float(v), true;
    if (auto* r = dynamic_cast<CObservationRange*>(&o); r && !r->sensedData.empty())
        return r->sensedData.front().sensedDistance = float(v), true;
    if (auto* br = dynamic_cast<CObservationBearingRange*>(&o); br && !br->sensedData.empty())
        return br->sensedData.front().yaw = float(v), br->sensedData.front().range = float(v), true;
    if (auto* s = dynamic_cast<CObservation2DRangeScan*>(&o); s && s->getScanSize() > 0)
        return s->setScanRange(0, float(v)), s->setScanRangeValidity(0, true), true;
    if (auto* odo = dynamic_cast<CObservationOdometry*>(&o))
        return odo->odometry.x(odo->odometry.x() + v), true;
    return false;
}

struct Outcome {
    int refused = 0, counted = 0, silent = 0;
    double longest = 0;
    std::vector<std::string> silentCases;
};

/** Writes `in` to `out` with one observation of class `cls` changed by `m` (the second of
 *  the label of that class's first: it has one of its own label before it), or every
 *  observation of the class (`all`; every observation with `cls` empty), with `copies` more
 *  copies of it after it. False when the rawlog has no such observation. */
using Change = std::function<void(CObservation&, double stampBefore)>;

bool mutate(const std::string& in, const std::string& out, const std::string& cls, bool all,
            const Change& m, size_t copies = 0) {
    common::RawlogReader r(in);
    common::RawlogWriter w(out);
    std::optional<std::string> label;  // of the class's first observation
    size_t ofLabel = 0;
    double stampBefore = 0;  // of the last observation of `label`
    bool changed = false;
    for (mrpt::obs::CObservation::Ptr o; r.next(o);) {
        const bool mine = cls.empty() || o->GetRuntimeClass()->className == cls;
        if (mine && !label) label = o->sensorLabel;
        const bool target = mine && (all || (o->sensorLabel == *label && ++ofLabel == 2));
        const double stamp = mrpt::Clock::toDouble(o->timestamp);
        if (target) {
            m(*o, stampBefore);
            changed = true;
        }
        if (label && o->sensorLabel == *label) stampBefore = stamp;
        w.write(*o);
        if (target)
            for (size_t c = 0; c < copies; ++c) w.write(*o);
    }
    w.commit();
    return changed;
}

void classify(const std::string& ini, const std::string& rawlog, const std::string& what,
              Outcome& outcome) {
    const std::string out = tmp("mutant_" + fs::path(rawlog).stem().string());
    const auto t0 = std::chrono::steady_clock::now();
    const auto r = mrlocCmd("localize " + ini + " " + rawlog + " -q --out " + out);
    outcome.longest =
        std::max(outcome.longest,
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    if (r.code == 1 && std::count(r.output.begin(), r.output.end(), '\n') == 1) {
        ++outcome.refused;
        return;
    }
    ASSERT_EQ(r.code, 0) << what << ": neither one line nor a run: " << r.output;
    const auto m = common::readJsonFile(out + "/metrics.json");
    // no NaN in what was written (covariance files say nan for terms a method has none of)
    for (const auto& e : fs::directory_iterator(out))
        if (e.path().filename().string().rfind("estimates.", 0) == 0) {
            const std::string text = slurp(e.path().string());
            EXPECT_EQ(text.find("nan"), std::string::npos) << what << ": " << e.path();
            EXPECT_EQ(text.find("inf"), std::string::npos) << what << ": " << e.path();
        }
    if (m.contains("copies_left_out") || m.contains("unstamped_left_out")) {
        ++outcome.counted;
        return;
    }
    ++outcome.silent;
    outcome.silentCases.push_back(what);
}

/** Every mutation of one method's rawlog. */
Outcome mutateEveryWay(const std::string& ini, const std::string& rawlog,
                       const std::vector<std::string>& classes) {
    Outcome o;
    // one file per method: ctest runs the methods' tests side by side
    const std::string tmpLog =
        testing::TempDir() + "/mutant_" + fs::path(rawlog).stem().string() + ".rawlog";
    const double nan = std::numeric_limits<double>::quiet_NaN(),
                 inf = std::numeric_limits<double>::infinity();
    for (const auto& cls : classes)
        for (const auto& [name, v] : std::vector<std::pair<std::string, double>>{
                 {"NaN", nan}, {"inf", inf}, {"-inf", -inf}, {"huge", 1e30}, {"negative", -5}}) {
            const double value = v;  // a lambda may not capture a structured binding (C++17)
            for (const bool all : {false, true}) {
                // every odometry reading shifted alike is another frame, not a bad value
                if (all && name == "negative" && cls.find("Odometry") != std::string::npos)
                    continue;
                bool changed = false;
                mutate(rawlog, tmpLog, cls, all, [&](CObservation& ob, double) {
                    changed = setMainValue(ob, value) || changed;
                });
                if (!changed) continue;
                classify(ini, tmpLog, cls + " " + name + (all ? " (all)" : " (one)"), o);
            }
        }
    using mrpt::Clock;
    const std::vector<std::pair<std::string, Change>> stamps{
        {"stamp negative",
         [](CObservation& ob, double) { ob.timestamp = Clock::fromDouble(-100); }},
        {"stamp 1e-3 s", [](CObservation& ob, double) { ob.timestamp = Clock::fromDouble(1e-3); }},
        {"stamp 1 s before the one before it",
         [](CObservation& ob, double before) { ob.timestamp = Clock::fromDouble(before - 1); }}};
    for (const auto& [name, m] : stamps)
        for (const auto& cls : classes)
            if (mutate(rawlog, tmpLog, cls, false, m)) classify(ini, tmpLog, cls + " " + name, o);
    mutate(rawlog, tmpLog, "", true,
           [](CObservation& ob, double) { ob.timestamp = Clock::fromDouble(1e-3); });
    classify(ini, tmpLog, "every stamp the same", o);
    for (const auto& cls : classes)
        if (mutate(
                rawlog, tmpLog, cls, false, [](CObservation&, double) {}, 20000))
            classify(ini, tmpLog, cls + " 20000 copies", o);
    return o;
}

/** Every mutation of `rawlog` through `ini`: the counts printed, no silent accept. */
void expectNoSilentAccept(const std::string& method, const std::string& ini,
                          const std::string& rawlog, const std::vector<std::string>& classes) {
    const auto o = mutateEveryWay(ini, rawlog, classes);
    std::cout << method << ": " << o.refused << " refused, " << o.counted << " counted skips, "
              << o.silent << " silent accepts, longest run " << o.longest << " s\n";
    for (const auto& s : o.silentCases) std::cout << "  silent: " << s << "\n";
    EXPECT_EQ(o.silent, 0);
    EXPECT_GT(o.refused, 10);  // the value mutations at least
}

/** A run folder's rawlog made by simulating config/<name>.ini. */
std::string simulated(const std::string& name) {
    const std::string out = tmp("mutate_src_" + name);
    const auto r = mrlocCmd("simulate " + config(name) + " -q --out " + out);
    EXPECT_EQ(r.code, 0) << r.output;
    return out + "/" + name + ".rawlog";
}

}  // namespace

// Measured: 0 silent accepts for every method; each mutant localizes in under 2 s (the
// 20,000 copies included); the counts are printed.
const std::string kOdometry = "mrpt::obs::CObservationOdometry";

TEST(Mutations, BeaconsRawlogIsRefusedOrCountedNeverSilentlyTaken) {
    expectNoSilentAccept("beacons", config("quickstart"),
                         std::string(MRLOC_SOURCE_DIR) + "/rawlogs/quickstart.rawlog",
                         {"mrpt::obs::CObservationBeaconRanges", kOdometry});
}

TEST(Mutations, PolymapRawlogIsRefusedOrCountedNeverSilentlyTaken) {
    expectNoSilentAccept("polymap", config("polymap_steps"), simulated("polymap_steps"),
                         {"mrpt::obs::CObservation2DRangeScan", kOdometry});
}

TEST(Mutations, OmnivisionRawlogIsRefusedOrCountedNeverSilentlyTaken) {
    expectNoSilentAccept("omnivision", config("omnivision_swarm"), simulated("omnivision_swarm"),
                         {"mrpt::obs::CObservationBearingRange", kOdometry});
}

TEST(Mutations, FramesyncRawlogIsRefusedOrCountedNeverSilentlyTaken) {
    expectNoSilentAccept("framesync",
                         writeIniFrom(config("framesync_team"), "mutate_framesync",
                                      "experiment_seeds       = 20", "experiment_seeds = 0"),
                         simulated("framesync_team"), {"mrpt::obs::CObservationRange", kOdometry});
}

TEST(Mutations, FormationRawlogIsRefusedOrCountedNeverSilentlyTaken) {
    expectNoSilentAccept("formation", config("formation_obstacles"),
                         simulated("formation_obstacles"),
                         {"mrpt::obs::CObservation2DRangeScan", kOdometry});
}
