#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/DataFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/GroundTruthFile.h>

#include <fstream>
#include <sstream>

namespace mrloc::common {

const std::vector<std::string>& GroundTruthSource::formats() {
    static const std::vector<std::string> f{"tum", "index_x_y_phi", "x_y_z_yaw_pitch_roll"};
    return f;
}

Trajectory loadGroundTruth(const GroundTruthSource& source, const std::vector<double>& stepTimes) {
    Trajectory out;
    if (source.format == "tum") {
        for (auto p : loadTum(source.path)) out.push_back({p.t, source.offset + p.pose});
        return out;
    }
    checkReadableFile(source.path, "ground truth", TrajectoryLimits::kMaxBytes);
    std::ifstream in(source.path);
    if (!in) throw Error("ground truth " + source.path + ": cannot open");
    const bool indexed = source.format == "index_x_y_phi";
    const size_t fields = indexed ? 4 : 6;
    size_t row = 0, lineNo = 0;
    for (std::string line; std::getline(in, line);) {
        ++lineNo;
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '%' || line[first] == '#') continue;
        std::istringstream words(line);
        std::vector<double> v;
        for (std::string w; words >> w;) {
            char* end = nullptr;
            const double x = std::strtod(w.c_str(), &end);
            if (*end != '\0' || !std::isfinite(x))
                throw Error(source.path + ":" + std::to_string(lineNo) + ": '" + w +
                            "' is not a number");
            v.push_back(x);
        }
        if (v.size() != fields)
            throw Error(source.path + ":" + std::to_string(lineNo) + ": expected " +
                        std::to_string(fields) + " numbers (" +
                        (indexed ? "i x y phi" : "x y z yaw pitch roll") + "), got " +
                        std::to_string(v.size()));
        const double step = indexed ? v[0] : double(row);
        ++row;
        if (step < 0 || step != std::floor(step))
            throw Error(source.path + ":" + std::to_string(lineNo) + ": the step index " +
                        std::to_string(step) + " is not a whole number");
        if (size_t(step) >= stepTimes.size()) continue;  // past the log's last step
        checkTrajectoryPose(stepTimes[size_t(step)], v[indexed ? 1 : 0], v[indexed ? 2 : 1],
                            indexed ? 0.0 : v[2], source.path + ":" + std::to_string(lineNo));
        if (out.size() >= TrajectoryLimits::kMaxPoses)
            throw Error(source.path + ":" + std::to_string(lineNo) +
                        ": more than 2,000,000 poses in one trajectory");
        const mrpt::poses::CPose3D pose =
            indexed ? mrpt::poses::CPose3D(v[1], v[2], 0, v[3], 0, 0)
                    : mrpt::poses::CPose3D(v[0], v[1], v[2], v[3], v[4], v[5]);
        out.push_back({stepTimes[size_t(step)], source.offset + pose});
    }
    if (out.empty())
        throw Error("ground truth " + source.path + ": no row matches a step of the log (" +
                    std::to_string(stepTimes.size()) + " odometry readings)");
    std::stable_sort(out.begin(), out.end(),
                     [](const StampedPose& a, const StampedPose& b) { return a.t < b.t; });
    return out;
}

std::optional<std::string> groundTruthFormatOf(const std::string& path) {
    std::ifstream in(path);
    std::string line;
    for (int lines = 0; lines < 100 && std::getline(in, line); ++lines) {
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '%' || line[first] == '#') continue;
        std::istringstream words(line);
        size_t n = 0;
        for (std::string w; words >> w;) ++n;
        if (n == 4) return std::string("index_x_y_phi");
        if (n == 6) return std::string("x_y_z_yaw_pitch_roll");
        if (n == 8) return std::string("tum");
        return std::nullopt;
    }
    return std::nullopt;
}

}  // namespace mrloc::common
