#include "BatchPlan.h"

#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/FolderLock.h>
#include <mrloc/common/Metrics.h>
#include <mrloc/common/Names.h>
#include <mrloc/common/Seeds.h>

#include <filesystem>

namespace mrloc::app {

namespace fs = std::filesystem;

size_t BatchPlan::pointCount() const {
    size_t n = 1;
    for (const auto& a : grid) n *= a.values.size();
    return n;
}

std::vector<KeyOverride> BatchPlan::pointKeys(size_t p) const {
    std::vector<KeyOverride> keys(grid.size());
    for (size_t i = grid.size(); i-- > 0;) {  // the last axis varies fastest
        const auto& a = grid[i];
        keys[i] = {a.section, a.key, a.values[p % a.values.size()], "--grid"};
        p /= a.values.size();
    }
    return keys;
}

std::vector<KeyOverride> BatchPlan::trialKeys(size_t p) const {
    auto keys = sets;
    for (auto& k : pointKeys(p)) keys.push_back(std::move(k));
    return keys;
}

std::string BatchPlan::pointName(size_t p) const {
    std::string name;
    for (const auto& k : pointKeys(p)) name += (name.empty() ? "" : " ") + k.text();
    return name.empty() ? "all" : name;
}

namespace {

unsigned long seedNumber(const std::string& text, const std::string& all) {
    const bool digits = !text.empty() && text.size() <= 10 &&
                        text.find_first_not_of("0123456789") == std::string::npos;
    if (!digits || std::stoull(text) > common::kMaxSeed)
        throw Error("--seeds " + common::printable(all) + ": expected A..B, seeds in [0, " +
                    std::to_string(common::kMaxSeed) + "] (1..1000)");
    return (unsigned long)std::stoull(text);
}

}  // namespace

std::pair<unsigned long, unsigned long> parseSeeds(const std::string& text) {
    const auto dots = text.find("..");
    const unsigned long a = seedNumber(text.substr(0, dots), text);
    const unsigned long b = dots == std::string::npos ? a : seedNumber(text.substr(dots + 2), text);
    if (b < a) throw Error("--seeds " + text + ": the last seed is before the first");
    return {a, b};
}

GridAxis parseGridAxis(const std::string& text) {
    const KeyOverride o = parseOverride(text, "--grid");
    GridAxis a{o.section, o.key, {}};
    size_t from = 0;
    while (true) {
        const auto comma = o.value.find(',', from);
        std::string v = o.value.substr(from, comma == std::string::npos ? comma : comma - from);
        const auto b = v.find_first_not_of(' '), e = v.find_last_not_of(' ');
        v = b == std::string::npos ? "" : v.substr(b, e - b + 1);
        if (v.empty())
            throw Error("--grid " + common::printable(text) +
                        ": an empty value (section.key=v1,v2,...)");
        a.values.push_back(v);
        if (a.values.size() > BatchPlan::kMaxValues)
            throw Error("--grid " + a.name() + ": more than 1,000 values");
        if (comma == std::string::npos) break;
        from = comma + 1;
    }
    return a;
}

size_t wholeNumber(const nlohmann::json& v) {
    if (!v.is_number_unsigned())
        throw Error("expected a whole number, not " + v.dump().substr(0, 40));
    return v.get<size_t>();
}

nlohmann::json toJson(const BatchPlan& plan) {
    nlohmann::json j;
    j["ini"] = plan.ini;
    j["seeds"] = {plan.firstSeed, plan.lastSeed};
    j["chunk"] = plan.chunk;
    j["set"] = nlohmann::json::array();
    for (const auto& k : plan.sets) j["set"].push_back(k.text());
    j["grid"] = nlohmann::json::array();
    for (const auto& a : plan.grid) j["grid"].push_back({{"key", a.name()}, {"values", a.values}});
    j["points"] = plan.pointCount();
    j["trials"] = plan.trialCount();
    return j;
}

BatchPlan planFromJson(const nlohmann::json& j, const std::string& where) {
    BatchPlan p;
    try {
        p.ini = j.at("ini").get<std::string>();
        std::vector<unsigned long> seeds;
        for (const auto& v : j.at("seeds")) seeds.push_back(wholeNumber(v));
        if (seeds.size() != 2 || seeds[1] < seeds[0] || seeds[1] > common::kMaxSeed)
            throw Error("seeds: expected [first, last]");
        p.firstSeed = seeds[0], p.lastSeed = seeds[1];
        p.chunk = wholeNumber(j.at("chunk"));
        if (p.chunk < 1 || p.chunk > 100000) throw Error("chunk: expected 1 .. 100000");
        for (const auto& s : j.at("set"))
            p.sets.push_back(parseOverride(s.get<std::string>(), "--set"));
        for (const auto& g : j.at("grid")) {
            std::string text = g.at("key").get<std::string>() + "=";
            const auto values = g.at("values").get<std::vector<std::string>>();
            for (size_t i = 0; i < values.size(); ++i) text += (i ? "," : "") + values[i];
            p.grid.push_back(parseGridAxis(text));
            if (p.grid.back().values != values) throw Error("grid: a value holds ','");
        }
    } catch (const Error& e) {
        throw Error(where + ": " + e.what());
    } catch (const std::exception& e) {
        throw Error(where + ": not a batch plan (" + oneLine(e.what()) + ")");
    }
    if (p.pointCount() > BatchPlan::kMaxPoints || p.trialCount() > BatchPlan::kMaxTrials)
        throw Error(where + ": more trials than a batch holds (doc/batch.md)");
    return p;
}

namespace batch_dir {
std::string ini(const std::string& dir) { return (fs::path(dir) / "batch.ini").string(); }
std::string plan(const std::string& dir) { return (fs::path(dir) / "batch.json").string(); }
std::string jobs(const std::string& dir) { return (fs::path(dir) / "jobs.txt").string(); }
std::string joblog(const std::string& dir) { return (fs::path(dir) / "joblog.txt").string(); }
std::string record(const std::string& dir, size_t point, unsigned long seed) {
    return (fs::path(dir) / "trials" / ("p" + std::to_string(point)) /
            ("s" + std::to_string(seed) + ".json"))
        .string();
}
std::string summary(const std::string& dir) { return (fs::path(dir) / "summary.json").string(); }
std::string summaryText(const std::string& dir) { return (fs::path(dir) / "summary.txt").string(); }
bool isBatch(const std::string& dir) { return fs::is_regular_file(fs::symlink_status(plan(dir))); }
void checkFolder(const std::string& dir) {
    // a record per trial, a folder per point, the plan's files and the report's
    common::checkFolderHoldsNoLink(dir, "batch folder",
                                   BatchPlan::kMaxTrials + BatchPlan::kMaxPoints + 1000);
}
BatchPlan readPlan(const std::string& dir) {
    if (!isBatch(dir))
        throw Error(common::pathInWords(dir) +
                    ": not a batch folder (no batch.json; mrloc batch "
                    "<ini> --seeds A..B --out <folder> makes one)");
    return planFromJson(common::readJsonFile(plan(dir)), plan(dir));
}
}  // namespace batch_dir

nlohmann::json trialLine(const std::string& method, unsigned long seed,
                         const std::vector<KeyOverride>& keys, const common::Headline& h) {
    nlohmann::json j;
    j["method"] = method;
    j["seed"] = seed;
    j["set"] = nlohmann::json::object();
    for (const auto& k : keys) j["set"][k.section + "." + k.key] = k.value;
    j["reached"] = h.reached;
    j["status"] = h.status;
    j["figures"] = nlohmann::json::array();
    for (const auto& f : h.figures) {
        nlohmann::json fig = {{"name", f.name}, {"unit", f.unit}, {"baseline", f.baseline}};
        fig["value"] = f.value ? nlohmann::json(*f.value) : nlohmann::json();
        j["figures"].push_back(fig);
    }
    return j;
}

}  // namespace mrloc::app
