// Issue 57's command line: one help style for every command (top level included), --version
// at the top, the bash completion generated from the commands' own parsers, "next:" hints,
// default run folders named after the INI, a line when a run replaces another INI's, and
// MRPT's sections checked for near misses of the keys mrloc reads there.
#include <gtest/gtest.h>
#include <mrloc/common/Version.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "MrlocCli.h"
#include "TestPaths.h"

namespace fs = std::filesystem;
using namespace mrloc;
using namespace mrloc::testing_cli;

namespace {

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);) out.push_back(l);
    return out;
}

/** The output of a bash snippet (stdout and stderr). */
std::string bash(const std::string& script) {
    const std::string file = testing::TempDir() + "/snippet.sh";
    std::ofstream(file) << script;
    FILE* p = popen(("bash " + file + " 2>&1").c_str(), "r");
    std::string out;
    char buf[4096];
    while (size_t n = fread(buf, 1, sizeof buf, p)) out.append(buf, n);
    pclose(p);
    return out;
}

}  // namespace

TEST(CommandLine, EveryCommandHasTheSameHelpWithItsOptionsAndTheExitCodes) {
    const auto top = mrlocCmd("--help");
    ASSERT_EQ(top.code, 0);
    const auto names = lines(mrlocCmd("--commands").output);
    ASSERT_GE(names.size(), 11u);
    for (const auto& name : names) {
        EXPECT_TRUE(contains(top.output, "\n  " + name + " ")) << name << " not in --help";
        const auto h = mrlocCmd(name + " --help");
        EXPECT_EQ(h.code, 0) << name;
        EXPECT_EQ(h.output.rfind("usage: mrloc " + name + " ", 0), 0u) << h.output;
        EXPECT_TRUE(contains(h.output, "\noptions:\n")) << name;
        EXPECT_TRUE(contains(h.output, "\n  -h, --help          this help\n")) << h.output;
        EXPECT_TRUE(contains(h.output, "\nexit codes: 0 done")) << name;
        // TCLAP's own style is gone ("Displays usage information", "USAGE:")
        EXPECT_FALSE(contains(h.output, "Displays usage")) << h.output;
        EXPECT_FALSE(contains(h.output, "USAGE:")) << h.output;
    }
    // every import format, rosbag included, and the exit codes at the top level
    for (const char* format : {"carmen", "librsf", "mrclam", "rosbag", "sonar-text"})
        EXPECT_TRUE(contains(top.output, format)) << format;
    EXPECT_TRUE(contains(top.output, "130\ninterrupted") || contains(top.output, "130 interrupted"))
        << top.output;
    // import's help lists its formats with their options, in the same style
    const auto import = mrlocCmd("import --help");
    EXPECT_TRUE(contains(import.output, "\nformats:\n  carmen <log.clf>")) << import.output;
    const auto rosbag = mrlocCmd("import rosbag --help");
    EXPECT_TRUE(contains(rosbag.output, "\nformat:\n  rosbag ")) << rosbag.output;
    EXPECT_FALSE(contains(rosbag.output, "  carmen ")) << rosbag.output;
}

TEST(CommandLine, VersionUnknownCommandsAndBareMrloc) {
    const auto v = mrlocCmd("--version");
    EXPECT_EQ(v.code, 0);
    EXPECT_EQ(v.output.rfind(std::string("mrloc ") + kVersion + " (commit ", 0), 0u) << v.output;
    EXPECT_TRUE(contains(v.output, ", MRPT 2.")) << v.output;
    EXPECT_EQ(mrlocCmd("run --version").output, v.output);
    const auto typo = mrlocCmd("locaize x.ini y.rawlog");
    EXPECT_EQ(typo.code, 2);
    EXPECT_EQ(typo.output,
              "mrloc: unknown command 'locaize': did you mean 'localize'? (mrloc --help lists "
              "them)\n");
    EXPECT_EQ(mrlocCmd("frobnicate").code, 2);
    const auto bare = mrlocCmd("");
    EXPECT_EQ(bare.code, 2);
    EXPECT_EQ(bare.output.rfind("usage: mrloc <command>", 0), 0u);
    EXPECT_EQ(mrlocCmd("--completion zsh").code, 2);
}

TEST(CommandLine, BashCompletionCompletesCommandsTheirOptionsAndImportFormats) {
    const auto script = mrlocCmd("--completion bash");
    ASSERT_EQ(script.code, 0);
    const std::string file = testing::TempDir() + "/mrloc.bash";
    std::ofstream(file) << script.output;
    const auto complete = [&](const std::string& words, int cword) {
        return bash("source " + file + "\nCOMP_WORDS=(" + words + ")\nCOMP_CWORD=" +
                    std::to_string(cword) + "\n_mrloc\necho \"${COMPREPLY[*]}\"\n");
    };
    EXPECT_EQ(complete("mrloc ru", 1), "run\n");
    EXPECT_EQ(complete("mrloc lo", 1), "localize\n");
    EXPECT_EQ(complete("mrloc run x.ini --se", 3), "--seed\n");
    EXPECT_EQ(complete("mrloc batch x.ini --re", 3), "--resume\n");
    EXPECT_EQ(complete("mrloc import ro", 2), "rosbag\n");
    EXPECT_EQ(complete("mrloc import rosbag x.bag --o", 4), "--opt --out\n");
    // every option of every command is offered: the lists come from the parsers
    for (const auto& name : lines(mrlocCmd("--commands").output)) {
        const auto opts = lines(mrlocCmd(name + " --list-options").output);
        EXPECT_GE(opts.size(), 2u) << name;  // --help and --version at least
        std::string offered;
        for (const auto& l : lines(script.output))
            if (l.rfind("    " + name + ") opts=\"", 0) == 0) offered = l;
        std::replace(offered.begin(), offered.end(), '"', ' ');
        for (const auto& o : opts)
            EXPECT_TRUE(contains(offered, " " + o + " ")) << name << " " << o;
    }
}

TEST(CommandLine, SimulateAndLocalizeSayWhatToRunNextAndQuietSaysNothingOfIt) {
    const std::string out = tmp("next");
    const std::string ini = config("quickstart");
    const auto sim = mrlocCmd("simulate " + ini + " --out " + out);
    ASSERT_EQ(sim.code, 0) << sim.output;
    const std::string localize =
        "mrloc localize " + ini + " " + out + "/quickstart.rawlog --out " + out;
    EXPECT_TRUE(contains(sim.output, "next: " + localize + "\n")) << sim.output;
    EXPECT_EQ(lines(sim.output).back(), out + "/quickstart.rawlog");  // a script's last line
    // the hint runs as it is written
    const auto loc = mrlocCmd(localize.substr(std::string("mrloc ").size()));
    ASSERT_EQ(loc.code, 0) << loc.output;
    EXPECT_TRUE(contains(loc.output, "next: mrloc report " + out + " ")) << loc.output;
    EXPECT_EQ(lines(loc.output).back().rfind("beacons: ", 0), 0u) << loc.output;
    const auto quiet = mrlocCmd(localize.substr(std::string("mrloc ").size()) + " -q");
    EXPECT_FALSE(contains(quiet.output, "next:")) << quiet.output;
    // a path a shell would split is quoted in the hint
    const std::string spaced = tmp("next with space");
    const auto s2 = mrlocCmd("simulate " + ini + " --out '" + spaced + "'");
    ASSERT_EQ(s2.code, 0) << s2.output;
    EXPECT_TRUE(contains(s2.output, "'" + spaced + "/quickstart.rawlog' --out '" + spaced + "'"))
        << s2.output;
}

TEST(CommandLine, AnIniWithoutANameRunsIntoAFolderNamedAfterItAndAReplacedRunIsSaid) {
    // quickstart.ini without its [scenario] name: out/<the INI's stem>, from the current folder
    std::string text = slurp(config("quickstart"));
    const std::string name = "name     = quickstart\n";
    ASSERT_TRUE(contains(text, name));
    text.erase(text.find(name), name.size());
    const std::string dir = tmp("unnamed");
    fs::create_directories(dir);
    std::ofstream(dir + "/my quick+start.ini") << text;
    std::ofstream(dir + "/other.ini") << text;
    const auto r = mrlocCmd("--version > /dev/null && cd '" + dir + "' && " + MRLOC_BINARY +
                            " simulate -q 'my quick+start.ini'");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_TRUE(fs::is_regular_file(dir + "/out/my_quick_start/my_quick_start.rawlog")) << r.output;
    // another INI into the same folder: said in one line, and done
    const std::string out = dir + "/out/my_quick_start";
    const auto again = mrlocCmd("simulate " + dir + "/other.ini --out " + out);
    ASSERT_EQ(again.code, 0) << again.output;
    EXPECT_TRUE(contains(again.output, "warning: " + out +
                                           " holds a run of my quick+start.ini; "
                                           "this one, of " +
                                           dir +
                                           "/other.ini, replaces it (--out DIR "
                                           "keeps both)\n"))
        << again.output;
    // the same INI again: nothing to say
    const auto same = mrlocCmd("simulate " + dir + "/other.ini --out " + out);
    EXPECT_FALSE(contains(same.output, "replaces it")) << same.output;
    // localize on another rawlog into a folder localized from this one
    const std::string sample = std::string(MRLOC_SOURCE_DIR) + "/rawlogs/quickstart.rawlog";
    ASSERT_EQ(mrlocCmd("localize " + dir + "/other.ini " + sample + " -q --out " + dir + "/l").code,
              0);
    const auto other =
        mrlocCmd("localize " + dir + "/other.ini " + out + "/other.rawlog --out " + dir + "/l");
    EXPECT_TRUE(contains(other.output, " holds a run on " + sample + "; this one, on " + out +
                                           "/other.rawlog, replaces it"))
        << other.output;
}

TEST(CommandLine, ANearMissOfAKeyMrlocReadsInAnMrptSectionIsAWarning) {
    std::string text = slurp(config("quickstart"));
    text +=
        "\n[MetricMap_landmarksMap_00_likelihoodOpts]\nbeaconRangeStd = 0.2\n"
        "rangeScan2D_decimation = 20\n[ro-localization]\ngroundTruthFle = gt.txt\n"
        "particles_count = 500\n";
    const std::string dir = tmp("mrptkeys");
    fs::create_directories(dir);
    std::ofstream(dir + "/q.ini") << text;
    const auto r = mrlocCmd("simulate " + dir + "/q.ini --out " + dir + "/out");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_TRUE(contains(r.output, "warning: " + dir +
                                       "/q.ini: [MetricMap_landmarksMap_00_likelihoodOpts] "
                                       "beaconRangeStd: not a key mrloc reads, so its default is "
                                       "used (did you mean beaconRangesStd?"))
        << r.output;
    EXPECT_TRUE(contains(r.output, "[ro-localization] groundTruthFle: not a key mrloc reads"))
        << r.output;
    // MRPT's apps' own keys, far from any mrloc reads, are theirs
    EXPECT_FALSE(contains(r.output, "rangeScan2D_decimation")) << r.output;
    EXPECT_FALSE(contains(r.output, "particles_count")) << r.output;
    // --quiet: errors only; stdout the rawlog written, nothing else on either stream
    const auto q = mrlocCmd("simulate " + dir + "/q.ini -q --out " + dir + "/out");
    ASSERT_EQ(q.code, 0) << q.output;
    EXPECT_EQ(q.output, dir + "/out/quickstart.rawlog\n");
    const auto keys = mrlocCmd("keys mrpt");
    EXPECT_EQ(keys.code, 0);
    EXPECT_TRUE(contains(keys.output,
                         "[MetricMap_landmarksMap_00_likelihoodOpts]\n  "
                         "beaconRangesStd"))
        << keys.output;
}

TEST(CommandLine, CmakeInstallPutsTheProgramItsCompletionTheInisAndTheDocsUnderThePrefix) {
    const std::string prefix = tmp("install");
    const auto r = mrlocCmd("--version > /dev/null && cmake --install " +
                            std::string(MRLOC_BUILD_DIR) + " --prefix " + prefix + " > /dev/null");
    ASSERT_EQ(r.code, 0) << r.output;
    // the installed program runs from anywhere and is this one
    EXPECT_EQ(mrlocCmd("--version > /dev/null && " + prefix + "/bin/mrloc --version").output,
              mrlocCmd("--version").output);
    EXPECT_EQ(slurp(prefix + "/share/bash-completion/completions/mrloc"),
              mrlocCmd("--completion bash").output);
    // the man page: the top-level help and every command's, in roff
    const std::string man = slurp(prefix + "/share/man/man1/mrloc.1");
    EXPECT_EQ(man, mrlocCmd("--man").output);
    EXPECT_EQ(man.rfind(".TH MRLOC 1 ", 0), 0u) << man.substr(0, 80);
    for (const char* section : {".SS run\n", ".SS import\n", ".SS keys\n", ".SH COMMANDS\n"})
        EXPECT_TRUE(contains(man, section)) << section;
    EXPECT_TRUE(contains(man, "usage: mrloc run <INI> [options]")) << man.substr(0, 400);
    // the INIs with what they name by relative paths: a shipped INI runs from there
    EXPECT_EQ(slurp(prefix + "/share/mrloc/config/quickstart.ini"), slurp(config("quickstart")));
    EXPECT_TRUE(fs::is_regular_file(prefix + "/share/mrloc/maps/two_rooms.poly"));
    EXPECT_TRUE(fs::is_regular_file(prefix + "/share/mrloc/rawlogs/quickstart.rawlog"));
    EXPECT_EQ(slurp(prefix + "/share/doc/mrloc/ini.md"),
              slurp(std::string(MRLOC_SOURCE_DIR) + "/doc/ini.md"));
    const auto run = mrlocCmd("simulate " + prefix +
                              "/share/mrloc/config/polymap_file.ini -q --out " + prefix + "/run");
    EXPECT_EQ(run.code, 0) << run.output;
}
