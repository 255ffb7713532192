// Fuzzes every reader of the JSON and trajectory files of a run or batch folder (issue 51):
// what `mrloc report`, `mrloc index`, `mrloc trial --batch`, `mrloc batch --resume` and
// `--collect` read from a folder that may come from someone else. The input's first byte picks
// the reader, the rest is the file:
//   0 metrics.json (readMetricsFile, the headline)   1 provenance.json (readProvenanceFile)
//   2 batch.json (batch_dir::readPlan)               3 a trial record (collectBatch over a
//   4 summary.json (readSummary)                       one-seed batch that holds it)
//   5 beacons.study.json (BeaconStudyFile::read)     6 a TUM trajectory (loadTum)
// One target rather than seven: each costs CI its fuzzing time and a link, and libFuzzer finds
// the selector byte at once. Any input must be read or refused with mrloc::Error, in bounded
// time and memory.
// fuzz-seeds: tests/data/fuzz-json/*
// fuzz-max-len: 65536
#include <mrloc/beacons/BeaconStudyFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/Metrics.h>
#include <mrloc/common/Outcome.h>
#include <mrloc/common/Trajectory.h>

#include <filesystem>
#include <fstream>

#include "BatchPlan.h"
#include "BatchSummary.h"
#include "FuzzInput.h"

namespace fs = std::filesystem;
using namespace mrloc;

namespace {

/** A folder of this process's own, emptied for each input. */
const std::string& folder() {
    static const std::string dir = [] {
        const std::string d = fuzz::inputPath(".d");
        fs::create_directories(d);
        return d;
    }();
    return dir;
}

void write(const std::string& path, const uint8_t* data, size_t size) {
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(data), long(size));
}

/** A batch of one seed, whose record is the input. */
void oneSeedBatch(const std::string& dir) {
    std::ofstream(dir + "/batch.json")
        << R"({"ini":"x.ini","seeds":[1,1],"chunk":10,"set":[],"grid":[],"points":1,"trials":1})";
    fs::create_directories(dir + "/trials/p0");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size == 0) return 0;
    const int reader = data[0] % 7;
    ++data, --size;
    const std::string& dir = folder();
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec)) fs::remove_all(e.path(), ec);
    try {
        switch (reader) {
            case 0: {
                write(dir + "/metrics.json", data, size);
                const auto m = common::readMetricsFile(dir + "/metrics.json");
                if (m.contains("headline")) common::headlineFromJson(m["headline"], "metrics.json");
                break;
            }
            case 1:
                write(dir + "/provenance.json", data, size);
                common::readProvenanceFile(dir + "/provenance.json");
                break;
            case 2:
                write(dir + "/batch.json", data, size);
                app::batch_dir::readPlan(dir);
                break;
            case 3:
                oneSeedBatch(dir);
                write(dir + "/trials/p0/s1.json", data, size);
                app::collectBatch(dir);
                break;
            case 4:
                write(dir + "/summary.json", data, size);
                app::readSummary(dir + "/summary.json");
                break;
            case 5:
                write(beacons::BeaconStudyFile::path(dir), data, size);
                beacons::BeaconStudyFile::read(dir);
                break;
            default:
                write(dir + "/estimates.txt", data, size);
                common::loadTum(dir + "/estimates.txt");
        }
    } catch (const Error&) {
    }
    return 0;
}
