#pragma once
// A localization method is one module that registers everything about it here, in one
// call of its registerMethod(registry), as a MethodUnit<ItsLocalizer>: its name, the INI
// sections it owns, its localizer, its scenario builder (robots, sensors and on-board part
// for the simulator), an optional experiment step, its work estimate and its report section. The
// app, the simulator, the report and common know no method by name: they look it up here (like
// MRPT's TMetricMapTypesRegistry), and an INI that names no method gets the one whose sections it
// holds, or an error listing them all.
#include <mrloc/common/Error.h>
#include <mrloc/common/KeyTable.h>
#include <mrloc/common/Localizer.h>
#include <mrloc/common/Log.h>
#include <mrloc/method/Work.h>
#include <mrloc/report/Report.h>
#include <mrloc/sim/Payload.h>
#include <mrloc/sim/Scenario.h>
#include <mrpt/config/CConfigFileBase.h>

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <typeinfo>
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
 *  on the run's true layout, say. It reads only the resolved run (the configured localizer,
 *  the scenario as loaded, the seed), never the INI again, and returns the files it wrote
 *  (its report section reads them). */
struct ExperimentInput {
    const common::Localizer& localizer;  ///< configured, after the whole rawlog
    /** The simulated scenario with the run's seed; nullptr for a log recorded elsewhere. */
    const sim::ScenarioConfig* scenario;
    const common::Trajectories& truth;  ///< in the estimates' frame
    std::string outDir;
    /** The run's seed ([scenario] seed, or --seed): an experiment's random draws start
     *  from it, so that `--seed` reaches the experiment and effective.ini reproduces it. */
    unsigned long seed = 1;
    /** The app's log: the experiment's progress (none with -q) and warnings. */
    const common::Log& log = common::silentLog();
};

/** One trial of a method's Monte Carlo experiment (`mrloc trial`, `mrloc batch`): the
 *  scenario as loaded, with the trial's seed and its --set keys. */
struct TrialInput {
    const common::Localizer& localizer;   ///< configured from the INI and --set
    const sim::ScenarioConfig& scenario;  ///< scenario.seed is the trial's
};

/** What a method's headline is computed from, after localization and its experiment. */
struct HeadlineInput {
    const common::Localizer& localizer;   ///< configured, after the whole rawlog
    const sim::ScenarioConfig* scenario;  ///< nullptr for a log recorded elsewhere
    const nlohmann::json& metrics;        ///< metrics.json as written
    std::string outDir;                   ///< the run folder: the experiment's files
};

/** The type-erased form the app and the report use; a method registers a MethodUnit. */
struct Method {
    std::string name;
    /** Lower-case INI sections this method owns; with the framework's, these are the only
     *  lower-case sections an INI may have. */
    std::vector<std::string> sections;
    /** Sections of other programs (MRPT's apps) that this method reads: an INI without
     *  [scenario] method and without any method's own section is this method's if it holds
     *  one of these (and no other method's). */
    std::vector<std::string> foreignSections;
    /** The MRPT classes the method localizes from ("CObservationBeaconRanges"): a log that
     *  another method could not use is pointed to this one when it holds them. */
    std::vector<std::string> reads;
    /** The shipped INI a user starts from for a log of those classes ("config/quickstart.ini"). */
    std::string exampleConfig;
    std::function<std::unique_ptr<common::Localizer>()> localizer;
    /** The method's headline, after localization and its experiment: its own figures, the
     *  paper's beside them (with a sentence where this run's experiment differs from the
     *  paper's), baselines apart, and whether it reached its goal. Required. */
    std::function<common::Headline(const HeadlineInput&)> headline;
    /** Reads the scenario from the INI; throws mrloc::Error naming file, section and key.
     *  The method's localizer, already configured from the same INI, is handed over so
     *  that what it built (a map, say) is not built twice. */
    std::function<Scenario(const mrpt::config::CConfigFileBase&, const common::Localizer&)>
        scenario;
    std::function<std::vector<std::string>(const ExperimentInput&)> experiment;  ///< optional
    /** One seed of the method's experiment, computed as the experiment computes each of its
     *  runs, so that `mrloc batch` over seeds gives the experiment's figures; optional.
     *  Without it, `mrloc trial` simulates and localizes the scenario, runs the experiment
     *  and gives the run's headline, as `mrloc run --seed` would. */
    std::function<common::Headline(const TrialInput&)> trial;
    /** The work the configuration asks of the method (its sensing in the simulation, its
     *  experiment), before anything runs; `scenario` is nullptr when nothing is simulated
     *  (Work.h). Optional: a method that names none adds nothing to the simulation's. */
    std::function<std::vector<WorkItem>(const common::Localizer&, const sim::ScenarioConfig*)> work;
    report::Section report;
    /** The key tables of the sections it owns that are declared as a common::KeyTable, as
     *  doc/ini.md shows them (`mrloc keys`; a test holds doc/ini.md to them). */
    std::vector<common::SectionKeys> keys;
};

/** ExperimentInput with the method's own localizer type. */
template <class LocalizerT>
struct ExperimentOf {
    const LocalizerT& localizer;
    const sim::ScenarioConfig* scenario;  ///< nullptr for a log recorded elsewhere
    const common::Trajectories& truth;
    const std::string& outDir;
    unsigned long seed;
    const common::Log& log;  ///< progress and warnings
};

/** TrialInput with the method's own localizer type. */
template <class LocalizerT>
struct TrialOf {
    const LocalizerT& localizer;
    const sim::ScenarioConfig& scenario;
};

/** HeadlineInput with the method's own localizer type. */
template <class LocalizerT>
struct HeadlineOf {
    const LocalizerT& localizer;
    const sim::ScenarioConfig* scenario;  ///< nullptr for a log recorded elsewhere
    const nlohmann::json& metrics;
    const std::string& outDir;
};

/** A method as it registers: every function takes its own localizer type (and through it
 *  its options), so no method downcasts; Registry::add binds them to the localizer it
 *  creates. */
template <class LocalizerT>
struct MethodUnit {
    std::string name;
    std::vector<std::string> sections;         ///< as Method::sections
    std::vector<std::string> foreignSections;  ///< as Method::foreignSections
    std::vector<std::string> reads;            ///< as Method::reads
    std::string exampleConfig;                 ///< as Method::exampleConfig
    std::function<common::Headline(const HeadlineOf<LocalizerT>&)> headline;  ///< as Method's
    std::function<Scenario(const mrpt::config::CConfigFileBase&, const LocalizerT&)> scenario;
    std::function<std::vector<std::string>(const ExperimentOf<LocalizerT>&)> experiment;
    std::function<common::Headline(const TrialOf<LocalizerT>&)> trial;  ///< as Method::trial
    std::function<std::vector<WorkItem>(const LocalizerT&, const sim::ScenarioConfig*)> work;
    report::Section report;
    std::vector<common::SectionKeys> keys;  ///< as Method::keys
};

class Registry {
 public:
    /** Throws mrloc::Error for a name registered twice, a section another method owns,
     *  or a method without a localizer or scenario. */
    void add(Method method);
    /** Registers a method whose functions take its localizer type. */
    template <class LocalizerT>
    void add(MethodUnit<LocalizerT> unit);
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

/** The localizer a Method's functions are given, as the type its unit was registered with;
 *  throws mrloc::Error for any other (a caller that mixed two methods' parts). */
template <class LocalizerT>
const LocalizerT& localizerOf(const common::Localizer& l, const std::string& method) {
    if (typeid(l) != typeid(LocalizerT))
        throw Error("method '" + method + "' was handed another method's localizer");
    return static_cast<const LocalizerT&>(l);
}

template <class LocalizerT>
void Registry::add(MethodUnit<LocalizerT> unit) {
    Method m;
    m.name = unit.name;
    m.sections = std::move(unit.sections);
    m.foreignSections = std::move(unit.foreignSections);
    m.reads = std::move(unit.reads);
    m.exampleConfig = std::move(unit.exampleConfig);
    m.localizer = [] { return std::make_unique<LocalizerT>(); };
    if (unit.headline)
        m.headline = [f = std::move(unit.headline), name = unit.name](const HeadlineInput& in) {
            return f(HeadlineOf<LocalizerT>{localizerOf<LocalizerT>(in.localizer, name),
                                            in.scenario, in.metrics, in.outDir});
        };
    if (unit.scenario)
        m.scenario = [f = std::move(unit.scenario), name = unit.name](
                         const mrpt::config::CConfigFileBase& ini, const common::Localizer& l) {
            return f(ini, localizerOf<LocalizerT>(l, name));
        };
    if (unit.experiment)
        m.experiment = [f = std::move(unit.experiment),
                        name = unit.name](const ExperimentInput& in) {
            return f(ExperimentOf<LocalizerT>{localizerOf<LocalizerT>(in.localizer, name),
                                              in.scenario, in.truth, in.outDir, in.seed, in.log});
        };
    if (unit.trial)
        m.trial = [f = std::move(unit.trial), name = unit.name](const TrialInput& in) {
            return f(TrialOf<LocalizerT>{localizerOf<LocalizerT>(in.localizer, name), in.scenario});
        };
    if (unit.work)
        m.work = [f = std::move(unit.work), name = unit.name](const common::Localizer& l,
                                                              const sim::ScenarioConfig* s) {
            return f(localizerOf<LocalizerT>(l, name), s);
        };
    m.report = std::move(unit.report);
    m.keys = std::move(unit.keys);
    add(std::move(m));
}

/** Sections the framework owns, whatever the method. */
const std::vector<std::string>& frameworkSections();
/** The key tables of the framework's sections declared as a common::KeyTable. */
std::vector<common::SectionKeys> frameworkKeys();

}  // namespace mrloc::method
