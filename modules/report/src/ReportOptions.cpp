#include <mrloc/common/KeyTable.h>
#include <mrloc/report/ReportOptions.h>

namespace mrloc::report {

const common::KeyTable<ReportOptions>& ReportOptions::keys() {
    static const auto table =
        common::KeyTable<ReportOptions>("report")
            .text("paper_caption", MRLOC_KEY_FIELD(paperCaption),
                  "what the paper's numbers are, e.g. `paper 001 Table 3`")
            .savedOnlyIf([](const ReportOptions& o) { return !o.paperCaption.empty(); })
            .text("paper_note", MRLOC_KEY_FIELD(paperNote), "free text shown under the table")
            .savedOnlyIf([](const ReportOptions& o) { return !o.paperNote.empty(); })
            .text("title", MRLOC_KEY_FIELD(title),
                  "the report's title; without it, `[scenario] name` and the method's subject "
                  "(`quickstart: active ultrasonic beacons (paper 001)`)")
            .savedOnlyIf([](const ReportOptions& o) { return !o.title.empty(); });
    return table;
}

void ReportOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& src,
                                       const std::string& section) {
    *this = ReportOptions{};  // every key absent takes the struct's default: written once
    common::IniSection s(src, section);
    keys().load(s, *this);
    s.finish();
}

void ReportOptions::saveToConfigFile(mrpt::config::CConfigFileBase& t,
                                     const std::string& section) const {
    keys().save(*this, t, section);
}

}  // namespace mrloc::report
