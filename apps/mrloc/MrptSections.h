#pragma once
// The keys mrloc reads from MRPT's own INI sections ([ro-localization], [LocalizationExperiment],
// [OdometryEstimation], [MappingApplication], the metric maps' options), in one table
// (common/MrptKeys.h, where the readers take their names from): what `mrloc keys mrpt` and
// doc/ini.md list, and what a misspelt key there is checked against. Those sections also carry
// keys for MRPT's apps, which mrloc leaves to them: a key mrloc does not read is not an error,
// but one within an edit or two of a key it reads is a warning with "did you mean".
#include <mrpt/config/CConfigFileBase.h>

#include <string>
#include <vector>

namespace mrloc::app {

struct MrptKey {
    std::string section, key;
    std::string readBy;  ///< "beacons: the ranges' sigma when [beacons] range_sigma is absent"
};

/** Every key mrloc reads from a section of MRPT's. */
const std::vector<MrptKey>& mrptKeysRead();

/** One warning per key of those sections that looks like a misspelling of a key mrloc reads
 *  there ("<ini>: [ro-localization] groundTruthFle: not read (did you mean groundTruthFile?
 *  ...)"). Keys far from every key mrloc reads are MRPT's apps' own: left alone. */
std::vector<std::string> mrptKeyWarnings(const mrpt::config::CConfigFileBase& ini,
                                         const std::string& iniPath);

/** `mrloc keys mrpt`: the table, with what ignores the rest. */
std::string mrptKeysText();

}  // namespace mrloc::app
