#pragma once
// Section [report]: the paper's figures a run is compared with, shown beside ours.
//   paper_caption          = seed 001 Table 3 (fixed angle)
//   paper_reception_<id>   = r1 r2 ...   successful receiving rate (%) of beacon <id>, one
//                                        value per robot of [scenario] robots, in order
//   paper_note             = free text (the paper's claims on errors, say)
#include <mrpt/config/CLoadableOptions.h>

#include <map>
#include <string>
#include <vector>

namespace mrloc::report {

struct ReportOptions : public mrpt::config::CLoadableOptions {
    std::string paperCaption;
    std::map<int, std::vector<double>> paperReception;  ///< beacon id -> % per robot
    std::string paperNote;

    void loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                            const std::string& section) override;
    void saveToConfigFile(mrpt::config::CConfigFileBase& target,
                          const std::string& section) const override;
};

}  // namespace mrloc::report
