#pragma once
// A localization method is one module that registers everything about it here, in one
// call of its registerMethod(registry): its name, the INI sections it owns, its localizer,
// its scenario builder (robots, sensors and on-board part for the simulator), an optional
// experiment step and its report section. The app, the simulator, the report and common know
// no method by name: they look it up here (like MRPT's TMetricMapTypesRegistry), and an INI
// that names no method gets the one whose sections it holds, or an error listing them all.
#include <mrloc/common/Localizer.h>
#include <mrloc/report/Report.h>
#include <mrloc/sim/Payload.h>
#include <mrloc/sim/Scenario.h>
#include <mrpt/config/CConfigFileBase.h>

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace mrloc::method {

/** What a method adds to a simulation. */
struct Scenario {
    sim::ScenarioConfig config;             ///< scenario, world and robots
    std::unique_ptr<sim::Payload> payload;  ///< the method's sensors and on-board part
    /** Writes the options of the simulation sections the method owns beyond its
     *  localizer's (e.g. [sensors], [ultrasonic]) into effective.ini. */
    std::function<void(mrpt::config::CConfigFileBase&)> saveOptions;
};

/** An experiment step run after localization, on the run directory: a Monte Carlo sweep
 *  on the run's true layout, say. It decides from the INI whether there is anything to
 *  do and returns the files it wrote (its report section reads them). */
struct ExperimentInput {
    const mrpt::config::CConfigFileBase& ini;
    const common::Localizer& localizer;  ///< after the whole rawlog
    const common::Trajectories& truth;   ///< in the estimates' frame
    std::string outDir;
    /** The run's seed ([scenario] seed, or --seed): an experiment's random draws start
     *  from it, so that `--seed` reaches the experiment and effective.ini reproduces it. */
    unsigned long seed = 1;
};

struct Method {
    std::string name;
    /** Lower-case INI sections this method owns; with the framework's, these are the only
     *  lower-case sections an INI may have. */
    std::vector<std::string> sections;
    /** Sections of other programs (MRPT's apps) that this method reads: an INI without
     *  [scenario] method and without any method's own section is this method's if it holds
     *  one of these (and no other method's). */
    std::vector<std::string> foreignSections;
    std::function<std::unique_ptr<common::Localizer>()> localizer;
    /** Reads the scenario from the INI; throws mrloc::Error naming file, section and key.
     *  The method's localizer, already configured from the same INI, is handed over so
     *  that what it built (a map, say) is not built twice. */
    std::function<Scenario(const mrpt::config::CConfigFileBase&, const common::Localizer&)>
        scenario;
    std::function<std::vector<std::string>(const ExperimentInput&)> experiment;  ///< optional
    report::Section report;
};

class Registry {
 public:
    /** Throws mrloc::Error for a name registered twice, a section another method owns,
     *  or a method without a localizer or scenario. */
    void add(Method method);
    /** Throws mrloc::Error listing the known names if `name` is not registered. */
    const Method& get(const std::string& name) const;
    bool has(const std::string& name) const { return methods_.count(name) > 0; }
    std::vector<std::string> names() const;
    /** Sections of every method and of the framework ([scenario], [world], [robot.<name>],
     *  [report]). */
    std::vector<std::string> sections() const;

 private:
    std::map<std::string, Method> methods_;
};

/** Sections the framework owns, whatever the method. */
const std::vector<std::string>& frameworkSections();

}  // namespace mrloc::method
