// The layering doc/architecture.md states, read from the sources: dependencies point down
// (common; sim and logimport on common; report on common and sim; method on those three; the
// methods on method; the app on method and logimport), no method names another, no code
// outside a method's module names it but for the registration list, and the app's shared
// parts sit below its commands. With ToyMethod.PlugsInThroughTheRegistryAlone (a method from
// tests/ alone), these hold the recipe's claim that a new method touches only the files the
// recipe lists.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>

#include "TestPaths.h"

namespace fs = std::filesystem;

namespace {

const fs::path kRoot = MRLOC_SOURCE_DIR;

std::string readText(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

/** The C++ sources under `dir` (.cpp and .h). */
std::vector<fs::path> sourcesUnder(const fs::path& dir) {
    std::vector<fs::path> out;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        if (e.is_regular_file() && (e.path().extension() == ".cpp" || e.path().extension() == ".h"))
            out.push_back(e.path());
    std::sort(out.begin(), out.end());
    return out;
}

/** The mrloc modules a source includes (<mrloc/<module>/...>). */
std::set<std::string> modulesIncluded(const fs::path& source) {
    static const std::regex include(R"(#include\s*<mrloc/([a-z_]+)/)");
    std::set<std::string> out;
    const std::string text = readText(source);
    for (std::sregex_iterator it(text.begin(), text.end(), include), end; it != end; ++it)
        out.insert((*it)[1]);
    return out;
}

/** The modules built by mrloc_add_method (the methods), and all modules. */
std::set<std::string> methodModules() {
    std::set<std::string> out;
    for (const auto& e : fs::directory_iterator(kRoot / "modules"))
        if (readText(e.path() / "CMakeLists.txt").find("mrloc_add_method(") != std::string::npos)
            out.insert(e.path().filename().string());
    return out;
}

std::string inRepo(const fs::path& p) { return fs::relative(p, kRoot).string(); }

}  // namespace

TEST(Layering, DependenciesPointDown) {
    const auto methods = methodModules();
    ASSERT_EQ(methods, (std::set<std::string>{"beacons", "formation", "framesync", "omnivision",
                                              "polymap"}));
    std::map<std::string, std::set<std::string>> allowed{
        {"common", {"common"}},
        {"sim", {"common", "sim"}},
        {"logimport", {"common", "logimport"}},
        {"report", {"common", "sim", "report"}},
        {"method", {"common", "sim", "report", "method"}}};
    for (const auto& m : methods) allowed[m] = {"common", "sim", "report", "method", m};
    size_t checked = 0;
    for (const auto& [module, may] : allowed)
        for (const auto& source : sourcesUnder(kRoot / "modules" / module)) {
            for (const auto& used : modulesIncluded(source))
                EXPECT_TRUE(may.count(used)) << inRepo(source) << " includes mrloc/" << used;
            ++checked;
        }
    EXPECT_GT(checked, 200u);  // the walk found the sources
}

TEST(Layering, OnlyTheRegistrationListNamesAMethodOutsideItsModule) {
    const auto methods = methodModules();
    size_t checked = 0;
    for (const auto& source : sourcesUnder(kRoot / "apps")) {
        const std::string name = source.filename().string();
        for (const auto& used : modulesIncluded(source)) {
            if (methods.count(used)) {
                EXPECT_TRUE(name == "AllMethods.cpp")
                    << inRepo(source) << " names the method " << used
                    << " (only AllMethods.cpp may: doc/architecture.md)";
            }
        }
        ++checked;
    }
    EXPECT_GT(checked, 20u);
    // each method: its subdirectory line and its registration, nothing more to add
    const std::string top = readText(kRoot / "CMakeLists.txt");
    const std::string all = readText(kRoot / "apps/mrloc/AllMethods.cpp");
    for (const auto& m : methods) {
        EXPECT_NE(top.find("add_subdirectory(modules/" + m + ")"), std::string::npos) << m;
        EXPECT_NE(all.find("#include <mrloc/" + m + "/"), std::string::npos) << m;
        EXPECT_NE(all.find(m + "::registerMethod("), std::string::npos) << m;
    }
}

TEST(Layering, TheAppsSharedPartsSitBelowItsCommands) {
    // the commands' files may use these; these never use a command's file or Commands.h
    const std::set<std::string> below{"CommandLine",  "RunSteps", "RunSetup",    "IniFile",
                                      "StderrLog",    "Advice",   "MrptTruth",   "BatchPlan",
                                      "BatchSummary", "KeysDoc",  "MrptSections"};
    static const std::regex local(R"(#include\s*"([A-Za-z]+)\.h")");
    size_t checked = 0;
    for (const auto& source : sourcesUnder(kRoot / "apps/mrloc")) {
        if (!below.count(source.stem().string())) continue;
        const std::string text = readText(source);
        for (std::sregex_iterator it(text.begin(), text.end(), local), end; it != end; ++it) {
            const std::string header = (*it)[1];
            EXPECT_TRUE(below.count(header) || header == source.stem().string())
                << inRepo(source) << " includes " << header << ".h, above it";
        }
        ++checked;
    }
    EXPECT_GE(checked, 2 * below.size() - 1);  // each part's .cpp and .h (KeysDoc's too)
}
