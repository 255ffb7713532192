#include <mrloc/common/Log.h>

namespace mrloc::common {

namespace {
class SilentLog final : public Log {
 public:
    void warning(const std::string&) const override {}
    bool showsProgress() const override { return false; }
    bool redraws() const override { return false; }
    void progress(const std::string&) const override {}
    void clearProgress() const override {}
};
}  // namespace

const Log& silentLog() {
    static const SilentLog log;
    return log;
}

}  // namespace mrloc::common
