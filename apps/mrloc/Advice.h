#pragma once
// What to tell a user whose INI or rawlog is not for the method they ran: which registered
// method reads what a log holds, and what an INI of one of MRPT's own apps that mrloc does
// not replace is for.
#include <mrloc/method/Registry.h>
#include <mrpt/config/CConfigFileBase.h>

#include <map>
#include <optional>
#include <string>

namespace mrloc::app {

/** Which registered method (other than `current`) reads a log of these classes, and the INI
 *  to start from ("method 'polymap' reads CObservation2DRangeScan: start from
 *  config/polymap_file.ini"); or that none does. */
std::string fitHintOf(const method::Registry& registry, const std::string& current,
                      const std::map<std::string, size_t>& classCounts);

/** Observations of a rawlog by MRPT class, short names ("CObservationOdometry"). Reads the
 *  whole log (checked first, as every read is). */
std::map<std::string, size_t> classesOf(const std::string& rawlogPath);

/** The INI of one of MRPT's apps for a task mrloc does not do (pf-localization on an
 *  occupancy grid, the SLAM apps), in words; nullopt for any other INI. */
std::optional<std::string> mrptAppOf(const mrpt::config::CConfigFileBase& ini);

/** The rawlog an MRPT app's INI names (rawlog_file of [LocalizationExperiment],
 *  [ro-localization] or [MappingApplication]), resolved from the INI's folder as MRPT's apps
 *  do when run from there; empty when it names none or the file is not there. */
std::string rawlogNamedBy(const mrpt::config::CConfigFileBase& ini, const std::string& iniPath);

/** One line for an MRPT app's INI that mrloc does not replace: what it is, what the log
 *  (`rawlog`, or the one the INI names) holds and which mrloc method and INI read that. */
std::string foreignIniAdvice(const method::Registry& registry, const std::string& iniPath,
                             const std::string& what, const std::string& rawlog);

}  // namespace mrloc::app
