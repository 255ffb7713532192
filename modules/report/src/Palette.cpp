#include <mrloc/report/Palette.h>
#include <mrpt/core/format.h>

#include <array>
#include <utility>

namespace mrloc::report::palette {

namespace {
const std::array<mrpt::img::TColor, 7> kSeries = {kBlue,   kVermillion, kGreen, kPurple,
                                                  kOrange, kSkyBlue,    kBlack};
}  // namespace

mrpt::img::TColor series(size_t i) { return kSeries[i % kSeries.size()]; }

std::string hex(mrpt::img::TColor c) { return mrpt::format("#%02x%02x%02x", c.R, c.G, c.B); }

std::string gnuplotDefinitions() {
    const std::pair<const char*, mrpt::img::TColor> named[] = {
        {"black", kBlack},           {"orange", kOrange}, {"sky", kSkyBlue},
        {"green", kGreen},           {"yellow", kYellow}, {"blue", kBlue},
        {"vermillion", kVermillion}, {"purple", kPurple}, {"grey", kGrey},
        {"lightgrey", kLightGrey}};
    std::string s;
    for (const auto& [name, c] : named) s += "pal_" + std::string(name) + " = '" + hex(c) + "'\n";
    for (size_t i = 0; i < kSeries.size(); ++i)
        s += mrpt::format("set linetype %zu lc rgb '%s'\n", i + 1, hex(kSeries[i]).c_str());
    return s + mrpt::format("set linetype cycle %zu\n", kSeries.size());
}

std::string gnuplotValueScale() {
    return "set palette defined (0 '#440154', 0.25 '#3b528b', 0.5 '#21918c', 0.75 '#5ec962', "
           "1 '#d8e219')\n";
}

}  // namespace mrloc::report::palette
