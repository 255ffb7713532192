#pragma once
// One INI resolved for a run: read and validated before anything is written (the INI, --seed
// written into it so that everything downstream reads the seed the run uses, the method, its
// configured localizer, the scenario), and what a run folder records of it: effective.ini
// (the resolved configuration, which runs again byte for byte) and provenance.json.
#include <mrloc/method/Registry.h>
#include <mrloc/report/ReportOptions.h>
#include <mrloc/sim/Scenario.h>
#include <mrpt/config/CConfigFile.h>

#include <memory>
#include <optional>
#include <string>

namespace mrloc::app {

/** `--set section.key=value`: one INI key given on the command line (`mrloc trial`,
 *  `mrloc batch`). It is read as if the INI held it, through the same checks. */
struct KeyOverride {
    std::string section, key, value;
    std::string from = "--set";  ///< what gave it, for messages: --set, --grid
    std::string text() const { return section + "." + key + "=" + value; }
};

/** Parses "section.key=value": the key is after the last dot before '=', so that a
 *  robot's section keeps its own (robot.r1.speed=0.3). Throws mrloc::Error naming `what`
 *  ("--set", "--grid") for a malformed one, a value over one line or 1,000 characters, or
 *  [scenario] seed (the seed is --seed's). */
KeyOverride parseOverride(const std::string& text, const std::string& what);

/** Everything one INI asks for, read and validated before anything is written. */
struct Setup {
    std::string iniPath;
    std::string iniText;  ///< the file as read, copied to config.ini
    std::unique_ptr<mrpt::config::CConfigFile> ini;
    sim::ScenarioOptions scenario;  ///< [scenario], with --seed applied
    const method::Method* method = nullptr;
    std::unique_ptr<common::Localizer> localizer;  ///< configured
    /** Built when the INI describes a simulation (it has [scenario]). */
    std::optional<method::Scenario> simulation;
    report::ReportOptions reportOptions;
    /** What the reading warns of (a near miss of a key mrloc reads in an MRPT section): the
     *  command prints them through its log, so that --quiet holds them back. */
    std::vector<std::string> warnings;
};

/** Everything read from an INI fails as mrloc::Error naming the INI (MRPT's parser throws
 *  its own exceptions, without the file's name). `needSimulation`: build the scenario even
 *  when the INI's [scenario] holds only localize keys. `rawlog`: the log the run will read,
 *  if any, for the advice given on an MRPT app's INI that mrloc does not replace. */
Setup loadSetup(const method::Registry& registry, const std::string& iniPath,
                std::optional<long> seed, bool needSimulation, const std::string& rawlog = "",
                const std::vector<KeyOverride>& overrides = {});

/** What the run's steps will cost (method/Work.h): the simulation's steps when `simulating`,
 *  and the method's parts for the steps asked. */
std::vector<method::WorkItem> workOf(const Setup& s, bool simulating, bool localizing);

/** effective.ini: every section of the INI as given (MRPT's own sections too), then every
 *  section mrloc reads rewritten with its defaults filled in. `simulate`, `localize` and
 *  `run` write the same file for the same INI and seed. */
std::string effectiveIni(const Setup& s);

/** Reads and validates everything an INI asks for, as `simulate`, `localize` and `run` do
 *  before they write anything (the scenario built when it has [scenario]), and renders its
 *  effective.ini; throws mrloc::Error naming file, section, key or line. Writes nothing. */
std::string checkIni(const method::Registry& registry, const std::string& iniPath);

/** config.ini (a copy of the INI), effective.ini and provenance.json, with this step's
 *  command line added to the steps already recorded there, and the rawlog `localize` read
 *  (none for a simulated run). */
void writeProvenance(const Setup& s, const std::string& dir, const std::string& step,
                     const std::string& command, const std::string& rawlog = "");

/** The run folder name of an INI without [scenario] name: its file's stem, each character a
 *  name cannot hold as '_' ("run" when nothing is left). */
std::string nameFromFile(const std::string& path);

/** "out/x holds a run of a.ini; this one, of b.ini, replaces it" when the run already in
 *  `dir` was made from another INI (or, localizing, another rawlog): the line a user reads
 *  before a default folder is reused. Empty when the folder is new or from the same files. */
std::string replacedRunNote(const std::string& dir, const std::string& iniPath,
                            const std::string& rawlog = "");

}  // namespace mrloc::app
