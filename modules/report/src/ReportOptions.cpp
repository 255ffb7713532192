#include <mrloc/common/IniSection.h>
#include <mrloc/report/ReportOptions.h>
#include <mrpt/system/string_utils.h>

#include <cstdlib>

namespace mrloc::report {

void ReportOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& src,
                                       const std::string& section) {
    common::IniSection s(src, section);
    paperCaption = s.text("paper_caption", "");
    paperNote = s.text("paper_note", "");
    paperReception.clear();
    for (const auto& [id, key] : s.numberedKeys("paper_reception_")) {
        const auto rates = s.reals(key, {});
        for (double r : rates)
            if (r < 0 || r > 100) s.fail(key, "rates are percentages, 0 to 100");
        paperReception[id] = rates;
    }
    s.finish();
}

void ReportOptions::saveToConfigFile(mrpt::config::CConfigFileBase& t,
                                     const std::string& section) const {
    if (!paperCaption.empty()) t.write(section, "paper_caption", paperCaption);
    if (!paperNote.empty()) t.write(section, "paper_note", paperNote);
    for (const auto& [id, rates] : paperReception) {
        std::string v;
        for (double r : rates) v += (v.empty() ? "" : " ") + mrpt::format("%g", r);
        t.write(section, "paper_reception_" + std::to_string(id), v);
    }
}

}  // namespace mrloc::report
