#include <mrloc/beacons/RfBeacon.h>

namespace mrloc::beacons {

double RfBeaconOptions::shotAge(int id) const {
    // beacons in turn: the epoch's k shots in its order, whichever they are; their mean age
    if (beaconsPerEpoch > 0)
        return (double(beaconsPerEpoch * shotsPerBeacon) - 1) / 2 * shotInterval;
    for (const auto& s : sections.sections())
        for (size_t k = 0; k < s.beacons.size(); ++k)
            if (s.beacons[k] == id) {
                // round j fires it at j n + k of R n shots: the mean age over the R rounds
                const double n = double(s.beacons.size()), R = shotsPerBeacon;
                return (R * n - 1 - double(k) - n * (R - 1) / 2) * shotInterval;
            }
    return 0;
}

RfBeacon::RfBeacon(RfBeaconOptions options)
    : o_(std::move(options)), scheduler_(o_.scheduling, o_.minSpeed) {}

std::optional<size_t> RfBeacon::servingSection(double t, const RobotReport& r) {
    const mrpt::math::TPoint2D p(r.receiver.x, r.receiver.y);
    const size_t here = o_.sections.at(p);
    auto& ready = tableReadyAt_[r.robot];
    if (ready.empty()) ready[here] = t;  // the start section's table is loaded beforehand
    const auto ask = [&](size_t s) {
        if (ready.emplace(s, t + o_.registrationTime).second) ++stats_.registrations;
    };
    ask(here);
    if (o_.handoverMargin > 0)
        for (size_t s = 0; s < o_.sections.size(); ++s)
            if (o_.sections[s].distanceTo(p) <= o_.handoverMargin) ask(s);
    if (ready.at(here) > t + 1e-12) return std::nullopt;
    return here;
}

std::optional<RangingEpoch> RfBeacon::nextEpoch(double t,
                                                const std::vector<RobotReport>& requests) {
    std::vector<RobotReport> candidates;
    std::vector<size_t> sectionOf;
    for (const auto& r : requests) {
        if (const auto s = servingSection(t, r)) {
            candidates.push_back(r);
            sectionOf.push_back(*s);
        } else {
            ++stats_.waits;
        }
    }
    if (candidates.empty()) return std::nullopt;
    const size_t i = scheduler_.pick(t, candidates);
    scheduler_.served(candidates[i].robot, t);
    ++stats_.epochs;
    const Section& sec = o_.sections[sectionOf[i]];
    RangingEpoch e;
    e.robot = candidates[i].robot;
    e.section = sec.name;
    std::vector<int> fired = sec.beacons;
    if (o_.beaconsPerEpoch > 0 && !sec.beacons.empty()) {
        // the next k of the section's beacons, in turn
        size_t& next = nextBeacon_[e.robot];
        fired.clear();
        for (int k = 0; k < o_.beaconsPerEpoch; ++k)
            fired.push_back(sec.beacons[next++ % sec.beacons.size()]);
    }
    for (int round = 0; round < o_.shotsPerBeacon; ++round)
        e.beacons.insert(e.beacons.end(), fired.begin(), fired.end());
    e.shotInterval = o_.shotInterval;
    e.aimPoints.assign(e.beacons.size(), o_.activeAiming ? candidates[i].receiver : sec.aim);
    return e;
}

}  // namespace mrloc::beacons
