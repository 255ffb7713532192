#pragma once
// Where common and the methods tell the person running mrloc something: warnings, and the
// progress of long work. The app passes its own down (app::StderrLog: "warning: ..." lines
// and the progress bar on stderr); a test, a batch or a program embedding mrloc passes
// another, or silentLog(). Below the app, nothing writes to stderr itself.
#include <string>

namespace mrloc::common {

class Log {
 public:
    virtual ~Log() = default;
    /** One warning, without the "warning: " the stderr log puts before it. */
    virtual void warning(const std::string& line) const = 0;
    /** Whether progress is wanted at all (-q: not). */
    virtual bool showsProgress() const = 0;
    /** Whether progress is redrawn in place (a terminal) rather than a line at a time. */
    virtual bool redraws() const = 0;
    /** A progress text: drawn in place when redraws(), else one line. */
    virtual void progress(const std::string& text) const = 0;
    /** Removes a progress text drawn in place. */
    virtual void clearProgress() const = 0;
};

/** Says nothing: the default of library calls that take a Log. */
const Log& silentLog();

}  // namespace mrloc::common
