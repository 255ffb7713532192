#pragma once
// The text files a method writes into the run directory for its report section: '#'
// comment lines, then one record per line of whitespace-separated fields. Each such file
// is defined once, as a small struct with write() and read() side by side in the module
// that writes it; these are the pieces they share.
#include <string>
#include <vector>

namespace mrloc::common {

/** A data line: where it is ("file:line", for errors) and its fields. */
struct DataLine {
    std::string where;
    std::vector<std::string> fields;
    /** Field i as a number ("nan" allowed); throws mrloc::Error naming the place. */
    double number(size_t i) const;
    /** Throws mrloc::Error naming the place unless there are exactly n fields. */
    void expectFields(size_t n) const;
};

/** Reads every data line; throws mrloc::Error if the file cannot be opened. */
std::vector<DataLine> readDataLines(const std::string& path);

/** A value with 17 significant digits: it reads back as the same double (time stamps of
 *  1.7e9 s keep their fraction). */
std::string formatNumber(double value);

}  // namespace mrloc::common
