// Fuzzes the text importers (`mrloc import`): the first byte picks the format (mrclam's
// measurement file in a folder of fixed others, sonar-text's measurement file beside a fixed
// pose file, librsf, carmen), the rest is the file. Any input must convert or throw
// mrloc::Error; nothing else may escape, and a conversion that succeeds must have written a
// rawlog that reads back. (A sonar text starts with a digit, "1" % 4 = 1; a librsf file with
// "r", 114 % 4 = 2; a CARMEN log with "#", 35 % 4 = 3; the MRCLAM seed with " ", 32 % 4 = 0.)
// fuzz-seeds: data/real/*/*.txt tests/data/carmen/*.clf tests/data/fuzz-import/*
// fuzz-max-len: 65536
#include <mrloc/common/Error.h>
#include <mrloc/common/Rawlog.h>
#include <mrloc/logimport/Format.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "FuzzInput.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 1) return 0;
    namespace li = mrloc::logimport;
    static const li::FormatRegistry registry = [] {
        li::FormatRegistry r;
        li::registerAllFormats(r);
        return r;
    }();
    const std::string& path = mrloc::fuzz::writeInput(data + 1, size - 1, ".txt");
    static const std::string poses = [] {
        const std::string p = mrloc::fuzz::inputPath(".poses.txt");
        std::ofstream(p) << "1000 0 0 0\n1200 60 0 0\n1400 120 0 0\n1600 180 0 0\n"
                            "1800 240 0 0\n2000 300 0 0\n2200 360 0 0\n";
        return p;
    }();
    // mrclam: the fuzzed file is robot 1's measurements, beside fixed odometry, truth,
    // barcodes (robot 1 is barcode 5, landmark 6 barcode 90) and landmarks
    static const std::string mrclam = [] {
        const std::string dir = mrloc::fuzz::inputPath(".mrclam");
        std::filesystem::create_directories(dir);
        std::ofstream(dir + "/Barcodes.dat") << "1 5\n6 90\n";
        std::ofstream(dir + "/Landmark_Groundtruth.dat") << "6 1.0 2.0 0 0\n";
        std::ofstream(dir + "/Robot1_Odometry.dat") << "100.0 0.1 0.0\n100.5 0.1 0.1\n";
        std::ofstream(dir + "/Robot1_Groundtruth.dat") << "100.0 0 0 0\n101.0 0.1 0 0\n";
        return dir;
    }();
    const std::string out = mrloc::fuzz::inputPath(".out.rawlog");
    try {
        switch (data[0] % 4) {
            case 0:
                std::filesystem::copy_file(path, mrclam + "/Robot1_Measurement.dat",
                                           std::filesystem::copy_options::overwrite_existing);
                li::runImport(registry.get("mrclam"), {mrclam}, {"robots=1"}, out);
                break;
            case 1:
                li::runImport(registry.get("sonar-text"), {path, poses},
                              {"bearings=-90,-37.5,-22.5,-7.5,7.5,22.5,37.5,90"}, out);
                break;
            case 2:
                li::runImport(registry.get("librsf"), {path}, {}, out);
                break;
            default:
                li::runImport(registry.get("carmen"), {path}, {}, out);
                break;
        }
    } catch (const mrloc::Error&) {
        return 0;
    }
    // what was written must read back (unchecked: the probe forks, too slow per input)
    mrloc::common::RawlogReader reader(out, mrloc::common::RawlogReader::kUnchecked);
    size_t n = 0;
    for (mrpt::obs::CObservation::Ptr o; reader.next(o);) ++n;
    if (n == 0) std::abort();
    return 0;
}
