#pragma once
// Section [report] (the framework's): what the run is compared with, shown on the page.
//   paper_caption = seed 001 Table 3 (fixed angle)    which of the paper's figures
//   paper_note    = free text (the paper's claims on errors, say)
//   title         = the page's title (default: the scenario's name and the method's subject)
// A method's own paper figures (seed 001's reception rates, say) are keys of its section.
#include <mrpt/config/CLoadableOptions.h>

#include <string>

namespace mrloc::report {

struct ReportOptions : public mrpt::config::CLoadableOptions {
    std::string paperCaption;
    std::string paperNote;
    std::string title;

    void loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                            const std::string& section) override;
    void saveToConfigFile(mrpt::config::CConfigFileBase& target,
                          const std::string& section) const override;
};

}  // namespace mrloc::report
