#include <mrloc/common/Error.h>
#include <mrloc/common/Names.h>
#include <mrloc/method/Registry.h>
#include <mrloc/report/ReportOptions.h>
#include <mrloc/sim/Scenario.h>

#include <algorithm>

namespace mrloc::method {

const std::vector<std::string>& frameworkSections() {
    static const std::vector<std::string> s = {"scenario", "world", "robot.<name>", "report"};
    return s;
}

std::vector<common::SectionKeys> frameworkKeys() {
    return {sim::ScenarioOptions::keysDocs(), sim::WorldOptions::keys().docs(),
            sim::RobotOptions::keys().docs(), report::ReportOptions::keys().docs()};
}

void Registry::add(Method m) {
    if (m.name.empty() || !m.localizer || !m.scenario || !m.headline)
        throw Error("method '" + m.name +
                    "': a method needs a name, a localizer, a scenario and a headline");
    if (methods_.count(m.name)) throw Error("method '" + m.name + "' registered twice");
    for (const auto& s : m.sections) {
        const auto& fw = frameworkSections();
        if (std::find(fw.begin(), fw.end(), s) != fw.end())
            throw Error("method '" + m.name + "': section [" + s + "] belongs to the framework");
        for (const auto& [name, other] : methods_)
            if (std::find(other.sections.begin(), other.sections.end(), s) != other.sections.end())
                throw Error("method '" + m.name + "': section [" + s + "] is owned by '" + name +
                            "'");
    }
    methods_.emplace(m.name, std::move(m));
}

const Method& Registry::get(const std::string& name) const {
    const auto it = methods_.find(name);
    if (it == methods_.end()) {
        std::string known;
        for (const auto& n : names()) known += (known.empty() ? "" : ", ") + n;
        const auto near = common::nearMiss(name, names());
        throw Error("unknown localization method '" + name + "' (" +
                    (near ? "did you mean '" + *near + "'? " : std::string()) + "known: " + known +
                    ")");
    }
    return it->second;
}

std::vector<std::string> Registry::names() const {
    std::vector<std::string> out;
    for (const auto& [name, m] : methods_) out.push_back(name);
    return out;
}

std::vector<std::string> Registry::sections() const {
    std::vector<std::string> out = frameworkSections();
    for (const auto& [name, m] : methods_)
        out.insert(out.end(), m.sections.begin(), m.sections.end());
    return out;
}

}  // namespace mrloc::method
