#include <mrloc/common/IniSection.h>
#include <mrloc/report/ReportOptions.h>

namespace mrloc::report {

void ReportOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& src,
                                       const std::string& section) {
    *this = ReportOptions{};  // every key absent takes the struct's default: written once
    common::IniSection s(src, section);
    paperCaption = s.text("paper_caption", paperCaption);
    paperNote = s.text("paper_note", paperNote);
    title = s.text("title", title);
    s.finish();
}

void ReportOptions::saveToConfigFile(mrpt::config::CConfigFileBase& t,
                                     const std::string& section) const {
    if (!paperCaption.empty()) t.write(section, "paper_caption", paperCaption);
    if (!paperNote.empty()) t.write(section, "paper_note", paperNote);
    if (!title.empty()) t.write(section, "title", title);
}

}  // namespace mrloc::report
