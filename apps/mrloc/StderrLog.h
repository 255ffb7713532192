#pragma once
// The log the app passes down to common and the methods (common/Log.h): warnings as
// "warning: <line>" and the progress on stderr, redrawn in place on a terminal; neither with
// -q (errors only: a run's warnings stay in its metrics.json and report). The only place
// mrloc's libraries' words reach stderr.
#include <mrloc/common/Log.h>

namespace mrloc::app {

class StderrLog final : public common::Log {
 public:
    explicit StderrLog(bool quiet);
    void warning(const std::string& line) const override;
    bool showsProgress() const override { return !quiet_; }
    bool redraws() const override { return terminal_; }
    void progress(const std::string& text) const override;
    void clearProgress() const override;

 private:
    bool quiet_;
    bool terminal_;
};

}  // namespace mrloc::app
