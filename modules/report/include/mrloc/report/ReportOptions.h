#pragma once
// Section [report] (the framework's): what the run is compared with, shown on the page
// (keys(): paper_caption, paper_note, title).
// A method's own paper figures (seed 001's reception rates, say) are keys of its section.
#include <mrloc/common/KeyTable.h>
#include <mrpt/config/CLoadableOptions.h>

#include <string>

namespace mrloc::report {

struct ReportOptions : public mrpt::config::CLoadableOptions {
    std::string paperCaption;
    std::string paperNote;
    std::string title;

    /** Every key of [report], declared once (loading, effective.ini, doc/ini.md). */
    static const common::KeyTable<ReportOptions>& keys();

    void loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                            const std::string& section) override;
    void saveToConfigFile(mrpt::config::CConfigFileBase& target,
                          const std::string& section) const override;
};

}  // namespace mrloc::report
