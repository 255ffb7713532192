#pragma once
// Checks an INI's text before MRPT parses it. MRPT's parser is lenient where a run should
// not be: a NUL byte ends the file early, a line without '=' is skipped, a key given twice
// keeps its last value, all silently. mrloc refuses each, naming the file and line.
#include <functional>
#include <string>

namespace mrloc::common {

/** Throws mrloc::Error "<origin>:<line>: <problem>" for the first of:
 *  - a NUL byte anywhere (MRPT would drop the rest of the file);
 *  - in a section `checked(section)` accepts (and before the first section): a line that is
 *    neither blank, a comment (# ; //), an MRPT directive (@...), a [section] nor key = value;
 *    a key given twice (keys are case-insensitive, also across repeated [section] headers);
 *    bytes that are not UTF-8 (values end up in JSON and HTML);
 *  - a [section header without its closing bracket.
 *  Lines ending in '\' continue on the next line, as MRPT reads them. */
void lintIni(const std::string& text, const std::string& origin,
             const std::function<bool(const std::string& section)>& checked);

/** True if `s` is well-formed UTF-8. */
bool isUtf8(const std::string& s);
/** Length of the well-formed UTF-8 sequence starting at s[i] (i < s.size()); 0 if none. */
size_t utf8Length(const std::string& s, size_t i);

}  // namespace mrloc::common
