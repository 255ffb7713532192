#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/DataFile.h>
#include <mrloc/common/Error.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace mrloc::common {

double DataLine::number(size_t i) const {
    if (i >= fields.size()) throw Error(where + ": field " + std::to_string(i + 1) + " missing");
    const std::string& f = fields[i];
    char* end = nullptr;
    const double v = std::strtod(f.c_str(), &end);
    if (end == f.c_str() || *end) throw Error(where + ": '" + f + "' is not a number");
    return v;
}

void DataLine::expectFields(size_t n) const {
    if (fields.size() != n)
        throw Error(where + ": expected " + std::to_string(n) + " fields, found " +
                    std::to_string(fields.size()));
}

std::vector<DataLine> readDataLines(const std::string& path) {
    checkReadableFile(path, "data file", 256u << 20);
    std::ifstream in(path);
    if (!in) throw Error(path + ": cannot open");
    std::vector<DataLine> lines;
    std::string line;
    for (int lineNo = 1; std::getline(in, line); ++lineNo) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream ls(line);
        DataLine d{path + ":" + std::to_string(lineNo), {}};
        for (std::string f; ls >> f;) d.fields.push_back(f);
        if (!d.fields.empty()) lines.push_back(std::move(d));
    }
    return lines;
}

std::string formatNumber(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

}  // namespace mrloc::common
