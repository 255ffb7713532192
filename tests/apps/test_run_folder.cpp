// Runs a user can trust (issue 26): a run folder is a transaction (a failed, interrupted or
// concurrent run leaves the previous one byte-identical), nothing outside it is read, written
// or deleted whatever the folder holds, no name from a file runs code or reaches HTML
// unescaped, and --seed reaches the experiments.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <mrloc/common/Metrics.h>
#include <mrloc/common/Rawlog.h>
#include <mrloc/common/RunTransaction.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <thread>

#include "MrlocCli.h"
#include "TestPaths.h"

namespace fs = std::filesystem;
using namespace mrloc;
using namespace mrloc::testing_cli;

namespace {

/** name -> SHA-1 of every file under `dir` (a run's state, to compare before and after). */
std::map<std::string, std::string> snapshot(const std::string& dir) {
    std::map<std::string, std::string> s;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        if (e.is_regular_file())
            s[e.path().lexically_relative(dir).string()] = common::sha1OfFile(e.path().string());
    return s;
}

/** `now` is a whole new run of the same INI: `before`'s files, the same bytes but for those
 *  that hold wall times (metrics.json, the report, provenance's hashes of them). */
bool sameRunButWallTimes(std::map<std::string, std::string> before,
                         std::map<std::string, std::string> now) {
    for (const char* timed : {"metrics.json", "provenance.json", "report.html"}) {
        if (!now.count(timed)) return false;
        before.erase(timed);
        now.erase(timed);
    }
    return before == now;
}

/** The entries beside `dir` that mrloc keeps there while it works (staging, lock). */
std::vector<std::string> leftBeside(const std::string& dir) {
    std::vector<std::string> left;
    const std::string prefix = "." + fs::path(dir).filename().string() + ".";
    for (const auto& e : fs::directory_iterator(fs::path(dir).parent_path()))
        if (e.path().filename().string().rfind(prefix, 0) == 0)
            left.push_back(e.path().filename().string());
    return left;
}

/** A quickstart that simulates `seconds` of time (a run of seconds of work). */
std::string longQuickstart(const std::string& name, int seconds) {
    std::string text = slurp(config("quickstart"));
    const std::string n = "name     = quickstart", d = "duration = 60 ";
    text.replace(text.find(n), n.size(), "name = " + name);
    text.replace(text.find(d), d.size(), "duration = " + std::to_string(seconds) + " ");
    const std::string ini = testing::TempDir() + "/" + name + ".ini";
    std::ofstream(ini) << text;
    return ini;
}

/** Runs `mrloc run <ini> --out <out> -q`, sends `sig` after `delay`, returns the status. */
int runInterrupted(const std::string& ini, const std::string& out, int sig,
                   std::chrono::milliseconds delay) {
    const pid_t pid = startRun(ini, out, true);
    std::this_thread::sleep_for(delay);
    kill(pid, sig);
    return waitStatus(pid);
}

}  // namespace

// --- the transaction ---

// Measured: a 600 s quickstart runs for about 2 s on the CI machine; the signals fall at
// 0.1-1.5 s, inside the simulation, the localization or the report. scripts/interrupt-rerun.sh
// measures 20 random moments on framesync_corridor.ini and polymap_sweep.ini.
TEST(RunFolder, AnInterruptedReRunLeavesThePreviousRunByteIdentical) {
    const std::string ini = longQuickstart("rerun", 600);
    const std::string out = tmp("rerun");
    ASSERT_EQ(mrlocCmd("run " + ini + " -q --out " + out).code, 0);
    auto before = snapshot(out);
    ASSERT_GT(before.size(), 10u);
    int interrupted = 0;
    for (const int sig : {SIGINT, SIGTERM, SIGKILL})
        for (const int ms : {100, 700, 1500}) {
            const int code = runInterrupted(ini, out, sig, std::chrono::milliseconds(ms));
            if (code == 0) {  // finished first: a complete new run
                before = snapshot(out);
                continue;
            }
            ++interrupted;
            EXPECT_EQ(code, 128 + sig);
            // the previous run, or (a signal after the new run was put in place) the new one
            const auto now = snapshot(out);
            EXPECT_TRUE(now == before || sameRunButWallTimes(before, now))
                << "signal " << sig << " after " << ms << " ms";
            before = now;
            if (sig != SIGKILL) {
                EXPECT_TRUE(leftBeside(out).empty()) << leftBeside(out).front();
            }
        }
    EXPECT_GE(interrupted, 6);
    // what a SIGKILL left beside the folder is removed by the next run
    ASSERT_EQ(mrlocCmd("run " + ini + " -q --out " + out).code, 0);
    EXPECT_TRUE(leftBeside(out).empty());
}

TEST(RunFolder, AFailedReRunLeavesThePreviousRunAndNoStaging) {
    const std::string out = tmp("failed_rerun");
    ASSERT_EQ(mrlocCmd("run " + config("polymap_steps") + " -q --out " + out).code, 0);
    const auto before = snapshot(out);
    // the same scenario with a scan too noisy to take (refused after simulating)
    const std::string bad =
        std::string(MRLOC_SOURCE_DIR) + "/tests/data/bad-inputs/steps_sigma8.ini";
    const auto r = mrlocCmd("run " + bad + " -q --out " + out);
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("left as it was): "), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find(".staging."), std::string::npos)
        << "names the staging folder: " << r.output;
    EXPECT_EQ(snapshot(out), before);
    EXPECT_TRUE(leftBeside(out).empty());
}

TEST(RunFolder, ASecondMrlocOnTheSameFolderIsRefused) {
    const std::string ini = longQuickstart("busy", 900);
    const std::string out = tmp("busy");
    const pid_t pid = startRun(ini, out);
    const std::string lock =
        (fs::path(out).parent_path() / ("." + fs::path(out).filename().string() + ".lock"))
            .string();
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (!fs::exists(lock) && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    const auto second = mrlocCmd("run " + config("polymap_steps") + " -q --out " + out);
    const int first = waitStatus(pid);
    EXPECT_EQ(second.code, 1);
    EXPECT_NE(second.output.find("in use by another mrloc process"), std::string::npos)
        << second.output;
    EXPECT_EQ(std::count(second.output.begin(), second.output.end(), '\n'), 1);
    ASSERT_EQ(first, 0);
    // the folder is the first run's alone
    EXPECT_TRUE(fs::exists(out + "/busy.rawlog"));
    EXPECT_FALSE(fs::exists(out + "/polymap_steps.rawlog"));
    EXPECT_EQ(common::readJsonFile(out + "/metrics.json")["method"], "beacons");
    EXPECT_TRUE(leftBeside(out).empty());  // the lock released and removed
}

// Needs a small file system: a tmpfs in a private mount namespace (unshare), skipped where the
// machine does not allow one. Measured: the quickstart's run folder is 1.29 MB (its estimates
// at the odometry's rate since issue 54); 3 MB less 1.3 MB of filler hold one run but not a
// re-run beside it (the staging copy).
TEST(RunFolder, AFullDiskFailsWithOneLineNamingTheFileAndKeepsThePreviousRun) {
    if (std::system("unshare -rm true >/dev/null 2>&1") != 0)
        GTEST_SKIP() << "no mount namespace here (unshare -rm): no small file system to fill";
    const std::string root = tmp("full_disk");
    fs::create_directories(root);
    const std::string script = root + ".sh";
    const std::string run =
        std::string(MRLOC_BINARY) + " run " + config("quickstart") + " -q --out " + root + "/q";
    std::ofstream(script) << "set -u\nmount -t tmpfs -o size=3m tmpfs " << root << " || exit 99\n"
                          << run << " > " << root << ".first 2>&1 || exit 98\n"
                          << "(cd " << root << "/q && sha1sum * > ../before)\n"
                          << "head -c 1300000 /dev/zero > " << root << "/fill\n"
                          << run << " > " << root << ".second 2>&1; echo $? > " << root << ".code\n"
                          << "(cd " << root << "/q && sha1sum * > ../after)\n"
                          << "cmp -s " << root << "/before " << root << "/after && echo same > "
                          << root << ".same\nls -a " << root << " > " << root << ".ls\n";
    const int rc = std::system(("unshare -rm bash " + script).c_str());
    if (WEXITSTATUS(rc) == 99) GTEST_SKIP() << "cannot mount a tmpfs here";
    ASSERT_EQ(WEXITSTATUS(rc), 0) << slurp(root + ".first");
    EXPECT_EQ(slurp(root + ".code"), "1\n") << slurp(root + ".second");
    const std::string line = slurp(root + ".second");
    EXPECT_EQ(std::count(line.begin(), line.end(), '\n'), 1) << line;
    EXPECT_NE(line.find("apps_full_disk/q/"), std::string::npos) << "names no file: " << line;
    EXPECT_NE(line.find("disk full"), std::string::npos) << line;
    EXPECT_EQ(slurp(root + ".same"), "same\n") << "the previous run changed";
    EXPECT_EQ(slurp(root + ".ls"), ".\n..\nafter\nbefore\nfill\nq\n");  // no staging, no lock
}

// --- hostile folders ---

TEST(RunFolder, ACraftedProvenanceOrSymlinksReachNothingOutsideTheFolder) {
    const std::string base = tmp("hostile_folder");
    const std::string out = base + "/run";
    ASSERT_EQ(mrlocCmd("run " + config("quickstart") + " -q --out " + out).code, 0);
    const std::string outside = base + "/outside.txt", target = base + "/target.txt";
    std::ofstream(outside) << "mine\n";
    std::ofstream(out + "/notes.txt") << "the user's\n";
    // provenance.json as a stranger might send it: names outside the folder, a link, a file
    // of the user's with a forged hash
    auto p = common::readJsonFile(out + "/provenance.json");
    auto& outputs = p["outputs"]["run"];
    outputs["../outside.txt"] = common::sha1OfFile(outside);
    outputs[outside] = common::sha1OfFile(outside);
    outputs["notes.txt"] = "0000000000000000000000000000000000000000";
    outputs["link.txt"] = common::sha1OfFile(outside);
    fs::create_symlink(outside, out + "/link.txt");
    std::ofstream(out + "/provenance.json") << p.dump();
    // a link at every temporary and at every final name of the run's outputs
    std::vector<std::string> names;
    for (const auto& [name, hash] : outputs.items())
        if (name.find('/') == std::string::npos) names.push_back(name);
    int n = 0;
    for (const auto& name : names) {
        if (name == "link.txt" || name == "notes.txt") continue;
        const std::string t = target + "." + std::to_string(n++);
        fs::create_symlink(t, out + "/" + name + ".tmp");
        fs::create_symlink(t, out + "/" + name + ".tmp.png");
    }
    fs::remove(out + "/report.html");
    fs::create_symlink(outside, out + "/report.html");
    const auto r =
        mrlocCmd("run " + config("quickstart") + " --out " + out);  // not -q: its warnings
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(slurp(outside), "mine\n");
    EXPECT_EQ(slurp(out + "/notes.txt"), "the user's\n");
    for (int i = 0; i < n; ++i)
        EXPECT_FALSE(fs::exists(target + "." + std::to_string(i))) << "written through a link";
    for (const auto& e : fs::directory_iterator(out))
        EXPECT_FALSE(fs::is_symlink(e.symlink_status())) << e.path() << " carried into the run";
    EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(out + "/report.html")));
    for (const auto& e : fs::directory_iterator(out))  // the staging folder is named nowhere
        if (e.path().extension() != ".png" && e.path().extension() != ".rawlog") {
            EXPECT_EQ(slurp(e.path().string()).find(".staging."), std::string::npos) << e.path();
        }
    EXPECT_NE(r.output.find("left out of the new run"), std::string::npos) << r.output;
    // the outputs recorded are the run's own names, each with its content's hash
    const auto now = common::readJsonFile(out + "/provenance.json")["outputs"]["run"];
    EXPECT_FALSE(now.contains("../outside.txt"));
    EXPECT_EQ(now["metrics.json"], common::sha1OfFile(out + "/metrics.json"));
}

TEST(RunFolder, ReportOfAFolderHoldingALinkIsOneLineNamingIt) {
    // report reads the folder as it is: a link where a result was (estimates.r1.txt ->
    // /etc/passwd) was left out of the new run with a warning, then missed as "no such file"
    // (two lines; found by scripts/mutate-folders.py report, 4 of 500)
    const std::string out = tmp("report_link");
    fs::remove_all(out);
    ASSERT_EQ(mrlocCmd("run " + config("quickstart") + " -q --out " + out).code, 0);
    fs::remove(out + "/estimates.r1.txt");
    fs::create_symlink("/etc/passwd", out + "/estimates.r1.txt");
    const auto before = slurp(out + "/report.html");
    const auto r = mrlocCmd("report " + out);
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_EQ(r.output, "mrloc report: error: " + out +
                            "/estimates.r1.txt: a symbolic link in the run folder (it holds "
                            "mrloc's files only; remove it)\n");
    EXPECT_TRUE(fs::is_symlink(fs::symlink_status(out + "/estimates.r1.txt")));
    EXPECT_EQ(slurp(out + "/report.html"), before);
}

TEST(RunFolder, OutFoldersThatCouldRunOrEscapeAreTakenLiterallyOrRefused) {
    const std::string base = tmp("hostile_out");
    fs::create_directories(base);
    const std::string marker = base + "/X";
    // a pipe: once `set output '|...'` in gnuplot; now a folder with that name, nothing run
    const std::string pipe = base + "/|touch " + marker + ";";
    EXPECT_EQ(mrlocCmd("run " + config("quickstart") + " -q --out '" + pipe + "'").code, 0);
    EXPECT_TRUE(fs::exists(pipe + "/report.html"));
    EXPECT_FALSE(fs::exists(marker));
    const auto newline = mrlocCmd("run " + config("quickstart") + " -q --out '" + base + "/a\nb'");
    EXPECT_EQ(newline.code, 1);
    EXPECT_NE(newline.output.find("control character"), std::string::npos) << newline.output;
    EXPECT_FALSE(fs::exists(base + "/a\nb"));
    // a leading dash: the folder of that name, in the current folder
    const int dash = std::system(("cd " + base + " && " + MRLOC_BINARY + " run " +
                                  config("quickstart") + " -q --out -x >/dev/null 2>&1")
                                     .c_str());
    EXPECT_EQ(WEXITSTATUS(dash), 0);
    EXPECT_TRUE(fs::exists(base + "/-x/report.html"));
    for (const char* dot : {".", "..", "/"}) {
        const auto r = mrlocCmd("run " + config("quickstart") + " -q --out " + dot);
        EXPECT_EQ(r.code, 1) << dot;
        EXPECT_NE(r.output.find("not a folder a run can be written to"), std::string::npos)
            << r.output;
    }
    // a non-empty folder that no run wrote (a home folder) is not taken over
    std::ofstream(base + "/mine.txt") << "x";
    const auto home = mrlocCmd("run " + config("quickstart") + " -q --out " + base);
    EXPECT_EQ(home.code, 1);
    EXPECT_NE(home.output.find("not written by mrloc"), std::string::npos) << home.output;
    EXPECT_EQ(slurp(base + "/mine.txt"), "x");
}

// --- hostile names ---

namespace {

/** Names with every way a string once reached a shell, gnuplot or HTML. */
const std::vector<std::string>& hostileNames() {
    static const std::vector<std::string> names{"a'b",
                                                "a\"b",
                                                "a`touch X`b",
                                                "$(touch X)",
                                                "x';system(\"touch X\");'",
                                                "<script>alert(1)</script>",
                                                "a;b",
                                                "a|b",
                                                "@m"};
    return names;
}

/** The quickstart's rawlog with `from` labels renamed `to`. */
std::string relabelled(const std::string& from, const std::string& to, const std::string& name) {
    const std::string path = testing::TempDir() + "/" + name + ".rawlog";
    common::RawlogReader in(std::string(MRLOC_SOURCE_DIR) + "/rawlogs/quickstart.rawlog");
    common::RawlogWriter w(path);
    for (mrpt::obs::CObservation::Ptr o; in.next(o);) {
        if (o->sensorLabel == from) o->sensorLabel = to;
        w.write(*o);
    }
    w.commit();
    return path;
}

}  // namespace

TEST(HostileNames, InAnIniAreRefusedWithOneLine) {
    const std::string cwd = tmp("names_ini");
    fs::create_directories(cwd);
    for (const auto& name : hostileNames()) {
        if (name.find(';') != std::string::npos) continue;  // an INI comment: another name
        for (const auto& [from, key] : std::map<std::string, std::string>{
                 {"robots   = r1", "robots"}, {"name     = quickstart", "name"}}) {
            const std::string ini =
                writeIniFrom(config("quickstart"), "hostile", from,
                             key == "robots" ? "robots = " + name : "name = " + name);
            const auto r = mrlocCmd("run " + ini + " -q --out " + cwd + "/run");
            EXPECT_EQ(r.code, 1) << name << ": " << r.output;
            EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
            EXPECT_NE(r.output.find("[scenario] " + key), std::string::npos) << r.output;
            EXPECT_FALSE(fs::exists(cwd + "/run"));
        }
    }
    EXPECT_FALSE(fs::exists("X")) << "a name ran a command";
}

TEST(HostileNames, InARawlogsLabelsAreRefusedOrShownEscaped) {
    const std::string cwd = tmp("names_rawlog");
    fs::create_directories(cwd);
    int n = 0;
    for (const auto& name : hostileNames()) {
        // the robot part of a label: refused, the entry named
        const std::string robotPart =
            relabelled("r1.beacons", name + ".beacons", "robot" + std::to_string(n));
        auto r = mrlocCmd("localize " + config("quickstart") + " " + robotPart + " -q --out " +
                          cwd + "/a" + std::to_string(n));
        EXPECT_EQ(r.code, 1) << name << ": " << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
        EXPECT_NE(r.output.find("is not a robot name"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("entry "), std::string::npos) << r.output;
        // a label without a dot belongs to robot "robot": taken in, and never runs anything
        if (name.find('.') == std::string::npos) {
            const std::string whole = relabelled("r1.odom", name, "whole" + std::to_string(n));
            const std::string out = cwd + "/b" + std::to_string(n);
            r = mrlocCmd("localize " + config("quickstart") + " " + whole + " -q --out " + out);
            EXPECT_EQ(r.code, 0) << name << ": " << r.output;
            ASSERT_EQ(mrlocCmd("report " + out).code, 0);
            const std::string page = slurp(out + "/report.html");
            EXPECT_EQ(page.find("<script>"), std::string::npos);
            if (name.find_first_of("<>&'\"") != std::string::npos) {
                EXPECT_EQ(page.find(name), std::string::npos) << "shown unescaped: " << name;
            }
        }
        ++n;
    }
    EXPECT_FALSE(fs::exists("X")) << "a label ran a command";
    EXPECT_FALSE(fs::exists(cwd + "/X"));
}

// --- one resolved configuration: --seed reaches the experiments ---

namespace {

/** The experiment's file of a run of `ini` with `--seed seed` (none: the INI's), and the same
 *  file from a re-run of that run's effective.ini. */
/** The experiment's file of a run of `ini` with `seedArg`, and (`again`) the same file from a
 *  re-run of that run's effective.ini. */
std::pair<std::string, std::string> experimentOf(const std::string& ini, const std::string& file,
                                                 const std::string& seedArg,
                                                 const std::string& name, bool again) {
    const std::string out = tmp("seed_" + name);
    const auto r = mrlocCmd("run " + ini + " -q " + seedArg + " --out " + out);
    EXPECT_EQ(r.code, 0) << r.output;
    if (!again) return {slurp(out + "/" + file), ""};
    const std::string rerun = tmp("seed_again_" + name);
    fs::copy_file(out + "/effective.ini", testing::TempDir() + "/eff_" + name + ".ini",
                  fs::copy_options::overwrite_existing);
    const auto a =
        mrlocCmd("run " + testing::TempDir() + "/eff_" + name + ".ini -q --out " + rerun);
    EXPECT_EQ(a.code, 0) << a.output;
    return {slurp(out + "/" + file), slurp(rerun + "/" + file)};
}

}  // namespace

/** A run with --seed 7 gives another experiment than the INI's seed, and its effective.ini
 *  gives the same experiment again, byte for byte (three runs: the sanitized suite's cost). */
void expectSeedReachesTheExperiment(const std::string& ini, const std::string& file) {
    if (std::getenv("MRLOC_SANITIZED"))  // set by scripts/sanitize.sh
        GTEST_SKIP() << "sanitized build: three whole runs per experiment, code their own "
                        "tests run sanitized; the Release suite checks the seeds";
    const std::string name = fs::path(ini).stem().string();
    const auto own = experimentOf(ini, file, "", name, false).first;
    const auto [seven, sevenAgain] = experimentOf(ini, file, "--seed 7", name + "7", true);
    ASSERT_FALSE(own.empty()) << file;
    EXPECT_NE(own, seven) << file << ": --seed 7 did not reach the experiment";
    EXPECT_EQ(seven, sevenAgain) << file << ": effective.ini does not reproduce --seed 7";
}

TEST(Seed, ReachesFramesyncsExperimentAndEffectiveIniReproducesIt) {
    expectSeedReachesTheExperiment(
        writeIniFrom(config("framesync_corridor"), "seed_framesync",
                     "experiment_seeds       = 50\nexperiment_sweep_seeds = 20",
                     "experiment_seeds = 2\nexperiment_sweep_seeds = 1"),
        "framesync.experiment.txt");
}

TEST(Seed, ReachesFormationsExperimentAndEffectiveIniReproducesIt) {
    // two marches per speed on one route, robots 4 and 5, no camera grid: the seed's path,
    // at a third of the shipped experiment's cost; the run itself cut to its first 200 s
    // (the experiment's marches are its own: measured 13.3 s a run whole, 2.0 s cut)
    const std::string ini =
        writeIniFrom(config("formation_many_turns"), "seed_formation", "runs        = 100",
                     "runs = 2\nexperiment_routes = many_turns\nexperiment_robots_max = 5\n"
                     "camera_starts = 0");
    expectSeedReachesTheExperiment(
        writeIniFrom(ini, "seed_formation_short", "duration          = 3200", "duration = 200"),
        "formation.experiment.txt");
}

TEST(Seed, ReachesTheBeaconStudyAndEffectiveIniReproducesIt) {
    // every evaluation of the study draws from seedOf(the run's seed, what it evaluates); the
    // study cut short (fewer trials, a coarser grid)
    expectSeedReachesTheExperiment(paperRoomWithAShortStudy("seed_beacons"), "beacons.study.json");
}

TEST(Seed, ReachesOmnivisionsAccuracySweepAndEffectiveIniReproducesIt) {
    expectSeedReachesTheExperiment(writeIniFrom(config("omnivision_5robots"), "seed_omni",
                                                "accuracy_trials = 100", "accuracy_trials = 5"),
                                   "accuracy.txt");
}
