#pragma once
// The INI's key tables as doc/ini.md shows them, from the common::KeyTable each section
// declares: `mrloc keys` prints them, `mrloc keys --update doc/ini.md` rewrites the tables
// between the doc's markers, and a test fails when the doc and the code differ.
#include <mrloc/common/KeyTable.h>
#include <mrloc/method/Registry.h>

#include <string>
#include <vector>

namespace mrloc::app {

/** The framework's tables, then each method's, by method name. */
std::vector<common::SectionKeys> allKeyTables(const method::Registry& registry);

/** One section's table (or every one, `section` empty) with its heading; throws
 *  mrloc::Error naming the sections that have one when `section` has none. */
std::string keysText(const method::Registry& registry, const std::string& section);

/** `doc` (doc/ini.md's text) with every block between `<!-- keys [<section>] ... -->` and
 *  `<!-- end keys -->` replaced by that section's table. Throws mrloc::Error for a marker
 *  without its end or naming a section without a table, and for a table no marker shows. */
std::string updateKeyDoc(const method::Registry& registry, const std::string& doc);

}  // namespace mrloc::app
