#include <mrloc/common/Error.h>
#include <mrloc/report/PictureLayout.h>
#include <mrpt/core/format.h>

#include <boost/crc.hpp>
#include <cstring>
#include <fstream>
#include <iterator>
#include <regex>
#include <sstream>

namespace mrloc::report {

namespace {

constexpr const char* kKeyword = "mrloc layout";

void putBigEndian(std::string& s, uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8) s += char((v >> shift) & 0xff);
}

uint32_t getBigEndian(const std::string& s, size_t at) {
    uint32_t v = 0;
    for (size_t k = 0; k < 4; ++k) v = (v << 8) | uint8_t(s[at + k]);
    return v;
}

std::string boxText(const char* name, const PixelBox& b) {
    return mrpt::format("%s %d %d %d %d\n", name, b.x0, b.y0, b.x1, b.y1);
}

}  // namespace

void writeLayout(const std::string& pngPath, const PictureLayout& l) {
    std::string text = mrpt::format("picture %d %d\n", l.width, l.height) + boxText("data", l.data);
    if (l.legend) text += boxText("legend", *l.legend);
    text += "key " + l.key + "\n" + mrpt::format("panels %d\n", l.panels);
    for (const auto& b : l.labels) text += boxText("label", b);
    if (l.inkShare) text += mrpt::format("ink %.4f\n", *l.inkShare);
    std::string png;
    {
        std::ifstream in(pngPath, std::ios::binary);
        png.assign(std::istreambuf_iterator<char>(in), {});
    }
    // the IEND chunk is the last 12 bytes of a whole PNG
    if (png.size() < 20 || png.compare(png.size() - 8, 4, "IEND") != 0)
        throw Error("cannot add the layout to " + pngPath + ": not a whole PNG");
    const std::string data = std::string(kKeyword) + '\0' + text;
    std::string chunk;
    putBigEndian(chunk, uint32_t(data.size()));
    const std::string typed = "tEXt" + data;
    boost::crc_32_type crc;
    crc.process_bytes(typed.data(), typed.size());
    chunk += typed;
    putBigEndian(chunk, crc.checksum());
    png.insert(png.size() - 12, chunk);
    std::ofstream out(pngPath, std::ios::binary | std::ios::trunc);
    out.write(png.data(), std::streamsize(png.size()));
    if (!out) throw Error("cannot write " + pngPath + " (is the disk full?)");
}

std::optional<PictureLayout> readLayout(const std::string& pngPath) {
    std::ifstream in(pngPath, std::ios::binary);
    const std::string png((std::istreambuf_iterator<char>(in)), {});
    for (size_t at = 8; at + 12 <= png.size();) {
        const uint32_t length = getBigEndian(png, at);
        if (at + 12 + size_t(length) > png.size()) break;
        const std::string type = png.substr(at + 4, 4);
        if (type == "tEXt") {
            const std::string data = png.substr(at + 8, length);
            const size_t nul = data.find('\0');
            if (nul != std::string::npos && data.compare(0, nul, kKeyword) == 0) {
                PictureLayout l;
                std::istringstream lines(data.substr(nul + 1));
                std::string word;
                while (lines >> word) {
                    PixelBox b;
                    if (word == "picture")
                        lines >> l.width >> l.height;
                    else if (word == "key")
                        lines >> l.key;
                    else if (word == "panels")
                        lines >> l.panels;
                    else if (word == "ink") {
                        double ink = 0;
                        lines >> ink;
                        l.inkShare = ink;
                    } else if (lines >> b.x0 >> b.y0 >> b.x1 >> b.y1) {
                        if (word == "data") l.data = b;
                        if (word == "legend") l.legend = b;
                        if (word == "label") l.labels.push_back(b);
                    }
                }
                return l;
            }
        }
        if (type == "IEND") break;
        at += 12 + size_t(length);
    }
    return std::nullopt;
}

std::string gnuplotKeyPlacement(const std::string& body) {
    // the last key statement wins, as in gnuplot; runGnuplot's preamble puts it outside
    static const std::regex statement(R"((^|\n|;)\s*(set|unset)\s+key\b([^\n;]*))");
    static const std::regex off(R"(\boff\b)");
    static const std::regex outside(R"(\b(outside|below|above|bmargin|tmargin|lmargin|rmargin)\b)");
    static const std::regex inside(R"(\b(inside|at)\b)");
    static const std::regex sideOrNothing(R"(^\s*$|\b(left|right|top|bottom|center)\b)");
    std::string placement = "outside";
    for (std::sregex_iterator it(body.begin(), body.end(), statement), end; it != end; ++it) {
        const std::string verb = (*it)[2], rest = (*it)[3];
        if (verb == "unset" || std::regex_search(rest, off))
            placement = "none";
        else if (std::regex_search(rest, outside))
            placement = "outside";
        else if (std::regex_search(rest, inside))
            placement = "inside";
        else if (placement == "none" && std::regex_search(rest, sideOrNothing))
            placement = "inside";  // `set key` or a side alone turns it on, inside by default
        // otherwise a side alone keeps the key inside or outside, as gnuplot does
    }
    return placement;
}

}  // namespace mrloc::report
