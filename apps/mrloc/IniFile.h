#pragma once
// Reading an INI as mrloc does: its bytes read once (a regular file, bounded), mrloc's sections
// checked line by line, other programs' sections left alone but a near miss of one of ours
// refused ("did you mean"), and the method the INI is for when [scenario] names none.
#include <mrloc/method/Registry.h>
#include <mrpt/config/CConfigFile.h>

#include <memory>
#include <string>

namespace mrloc::app {

/** A rawlog by its name or its first bytes (gzip's magic, or MRPT's binary archive). */
bool looksLikeRawlog(const std::string& path);
/** An INI by its name (.ini, .cfg) or its first line of text ("[section]", "; comment").  */
bool looksLikeIni(const std::string& path);
/** Refuses an INI given where a rawlog is expected, with one line saying so: MRPT's reader
 *  would otherwise call it a corrupt rawlog. */
void checkNotAnIni(const std::string& rawlogPath);

/** The INI's bytes, as read once: checked, parsed and copied into config.ini from these. */
std::string readIniText(const std::string& path);

/** A section mrloc reads: a registered method's, the framework's, or a robot's (any case). */
bool isMrlocSection(const std::string& section, const method::Registry& registry);

/** Opens an INI. Sections of other programs (MRPT's apps: [ro-localization],
 *  [MetricMap_...]) are left alone; a section that looks like a misspelling of one of mrloc's
 *  ([sensor], [Beacons], [robto.r1]) would otherwise be ignored silently, and is refused. */
std::unique_ptr<mrpt::config::CConfigFile> openIni(const std::string& path, const std::string& text,
                                                   const method::Registry& registry);

/** An INI without [scenario] method: the one method whose own sections it holds, else the
 *  one whose foreign sections (MRPT's) it holds; otherwise an error listing the methods. */
std::string methodOfSections(const method::Registry& registry,
                             const mrpt::config::CConfigFileBase& ini);

}  // namespace mrloc::app
