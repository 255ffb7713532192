// Fuzzes the rawlog reader as every command uses it: open (the gzip check and the isolated
// deserialization of every entry), then read every observation. Any input must either read
// or throw mrloc::Error; a crash, a leak of another exception, a hang or an allocation
// beyond the memory cap in this process is a finding.
// fuzz-seeds: rawlogs/*.rawlog /usr/share/mrpt/datasets/*.rawlog tests/data/bad-inputs/*.rawlog*
// fuzz-max-len: 1048576
// fuzz-malloc-limit-mb: 1000000 (the probe's child deserializes corrupt sizes on purpose; its
// own cap is 2048 MiB of resident memory)
#include <mrloc/common/Error.h>
#include <mrloc/common/Rawlog.h>
#include <mrpt/core/Clock.h>

#include "FuzzInput.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string& path = mrloc::fuzz::writeInput(data, size, ".rawlog");
    try {
        mrloc::common::RawlogReader reader(path);
        for (mrpt::obs::CObservation::Ptr obs; reader.next(obs);) {
            (void)obs->sensorLabel.size();
            (void)mrpt::Clock::toDouble(obs->timestamp);
        }
    } catch (const mrloc::Error&) {
    }
    return 0;
}
