// Every input that once broke mrloc (tests/data/bad-inputs, from ../shared/bad-inputs) and the
// other bad inputs of doc/errors.md: each gives one line on stderr naming the file and what
// is wrong, exit status 1, and nothing under the output folder.
#include <gtest/gtest.h>
#include <mrloc/common/Metrics.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>
#include <zlib.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "MrlocCli.h"
#include "TestPaths.h"

namespace fs = std::filesystem;
using namespace mrloc;
using namespace mrloc::testing_cli;

namespace {

std::string badInput(const std::string& name) {
    return std::string(MRLOC_SOURCE_DIR) + "/tests/data/bad-inputs/" + name;
}

std::string quoted(const std::string& s) { return "'" + s + "'"; }

/** Runs `mrloc <command> <input> [more] --out <dir>` (localize: `<more> <input>`, the INI first;
 *  info takes no --out) and checks the contract: exit 1, one line of output, the file named,
 *  nothing written. The line. */
std::string refused(const std::string& command, const std::string& input,
                    const std::string& more = "") {
    const std::string out = tmp("bad_" + fs::path(input).filename().string());
    const bool writes = command != "info";
    // localize takes the INI first: `more` is the INI, the input the rawlog
    const std::string args =
        command == "localize" ? more + " " + quoted(input) : quoted(input) + " " + more;
    const auto r = mrlocCmd(command + " " + args + (writes ? " --quiet --out " + out : ""));
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_NE(r.output.find(fs::path(input).filename().string()), std::string::npos) << r.output;
    EXPECT_EQ(r.output.rfind("mrloc " + command + ": error: ", 0), 0u) << r.output;
    EXPECT_FALSE(fs::exists(out)) << "output left behind by " << input;
    return r.output;
}

void expectHas(const std::string& text, const std::string& part) {
    EXPECT_NE(text.find(part), std::string::npos) << "expected '" << part << "' in: " << text;
}

/** gunzip `from` into `to` (one layer), with zlib. */
void gunzip(const std::string& from, const std::string& to) {
    gzFile in = gzopen(from.c_str(), "rb");
    ASSERT_NE(in, nullptr);
    std::ofstream out(to, std::ios::binary);
    char buf[1 << 16];
    for (int n; (n = gzread(in, buf, sizeof buf)) > 0;) out.write(buf, n);
    gzclose(in);
}

}  // namespace

// --- rawlogs: every command that reads one goes through the same check ---

TEST(BadRawlog, CorruptGzipStreamIsAnErrorNotAnEmptyRawlog) {
    const auto line = refused("info", badInput("corrupt_gz_byte30.rawlog"));
    expectHas(line, "corrupt gzip stream near byte 105 (invalid literal/lengths set)");
}

TEST(BadRawlog, AStampBefore1970IsRefusedNotReadAsTheYear60425) {
    // -10.5 s: MRPT's unsigned toDouble made it 1844674407360.455 s, which the check's
    // "before 1970" never caught (common::stampSeconds is signed)
    expectHas(refused("localize", badInput("before_1970.rawlog"),
                      std::string(MRLOC_SOURCE_DIR) + "/config/quickstart.ini"),
              "entry 1, observation 1 ('robot.odometry', mrpt::obs::CObservationOdometry): time "
              "stamp -10.500000 s is before 1970");
    // info describes it, saying so
    const auto info = mrlocCmd("info " + badInput("before_1970.rawlog"));
    EXPECT_EQ(info.code, 0) << info.output;
    expectHas(info.output, "start: before 1970 (-10.500000)");
    expectHas(info.output, "1 before 1970: localize refuses them");
    // and the import that wrote it now refuses its source, at the line
    const std::string dir = tmp("import_before_1970");
    fs::create_directories(dir);
    const std::string clf = dir + "/a.clf";
    std::ofstream(clf) << "ODOM 1.0 2.0 0.5 0.3 0.1 0.0 -10.5 host 10.01\n";
    const auto r = mrlocCmd("import carmen " + clf + " --out " + dir + "/a.rawlog");
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_EQ(r.output, "mrloc import: error: " + clf + ":1: time stamp -10.500000 s is before 1970\n");
    EXPECT_FALSE(fs::exists(dir + "/a.rawlog"));
}

TEST(BadRawlog, HeaderOnlyGzipIsTruncated) {
    const auto line = refused("info", badInput("header_only_10B.rawlog"));
    expectHas(line,
              "the gzip stream stops at byte 10 before its end (truncated file, no data "
              "after the header)");
}

TEST(BadRawlog, MemoryBlowupIsCaughtByItsGzipCheck) {
    // The file as found: its gzip CRC fails too, which is found before any entry is read.
    const auto line = refused("info", badInput("memory_blowup.rawlog"));
    expectHas(line, "corrupt gzip stream near byte 169079 (incorrect data check)");
}

TEST(BadRawlog, CorruptSizeMeetsTheMemoryCap) {
    // The same entries in an intact gzip stream: entry 56 asks MRPT for gigabytes. The probe's
    // child gets bad_alloc at the cap (or, under AddressSanitizer, dies of it): either way the
    // entry and the cap are named. Localize refuses it before writing anything.
    const auto line = refused("info", badInput("memory_blowup_regz.rawlog"));
    expectHas(line, "entry 56 ");
    expectHas(line, "2048 MiB");
    refused("localize", badInput("memory_blowup_regz.rawlog"), config("quickstart"));
}

TEST(BadRawlog, CrashInsideMrptsDeserializerIsACleanError) {
    // A corrupt estimationMethod of a CActionRobotMovement2D: MRPT dereferences a null pose.
    const auto line = refused("info", badInput("sena_byte39803.rawlog.gz"));
    expectHas(line, "entry 36 is corrupt: MRPT's deserializer");
    refused("localize", badInput("sena_byte39803.rawlog.gz"), config("quickstart"));
}

TEST(BadRawlog, DoublyCompressedAndCorruptSize3DScan) {
    const auto twice = refused("info", badInput("rgbd_insert.rawlog.gz"));
    expectHas(twice, "a gzip stream inside a gzip stream");
    // Decompressed once, as its user meant it: a CObservation3DRangeScan with a corrupt size
    // (MRPT's aligned allocator returns NULL and writes through it).
    const std::string once = testing::TempDir() + "/rgbd_insert.rawlog";
    gunzip(badInput("rgbd_insert.rawlog.gz"), once);
    const auto line = refused("info", once);
    expectHas(line, "entry 1 is corrupt: MRPT's deserializer");
}

TEST(BadRawlog, MrptExampleRawlogsWithInvalidBoolBytesRead) {
    // hasEncodersInfo holds 8 or 249 in these: read as its byte (undefined behaviour before,
    // fatal under UBSan). Both must read to the end: every entry, every observation.
    for (const auto& [name, entries] : std::map<std::string, std::string>{
             {"localization_demo.rawlog", "entries: 74, observations: 74"},
             {"uwb_ro-localization_demo.rawlog", "entries: 686, observations: 1025"}}) {
        const std::string path = "/usr/share/mrpt/datasets/" + name;
        ASSERT_TRUE(fs::exists(path)) << "mrpt-common is installed by scripts/install-deps.sh";
        const auto r = mrlocCmd("info " + path);
        EXPECT_EQ(r.code, 0) << r.output;
        expectHas(r.output, entries);
    }
}

// --- maps ---

TEST(BadPoly, HolesSharingAVertexAreRefused) {
    // Two pillars meeting at one vertex: the map is refused in one line before anything runs
    // (it once passed validation and stopped the triangulation with an internal error).
    const std::string ini = testing::TempDir() + "/pinched_pillars.ini";
    std::ofstream(ini) << "[scenario]\nname = pinched\nmethod = polymap\nseed = 1\n"
                          "[polymap]\nmap = "
                       << badInput("holes_sharing_vertex.poly") << "\nstart = 1 1\n";
    const std::string out = tmp("bad_pinched_pillars");
    const auto r = mrlocCmd("run " + quoted(ini) + " --quiet --out " + out);
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    expectHas(r.output,
              "mrloc run: error: " + badInput("holes_sharing_vertex.poly") +
                  ": two rings cross or touch: ring 3 (line 14) and ring 2 (line 10) share the "
                  "vertex (5 5)");
    EXPECT_FALSE(fs::exists(out));
}

// --- INI files ---

TEST(BadIni, NulByteIsRefusedWithItsLine) {
    expectHas(refused("run", badInput("nul_in_comment.ini")),
              "nul_in_comment.ini:3: a NUL byte (MRPT's parser would silently drop the rest of "
              "the file)");
}

TEST(BadIni, LineWithoutEqualsIsRefused) {
    expectHas(refused("run", badInput("no_equals.ini")),
              "no_equals.ini:11: [polymap]: 'heading 45' is not key = value (missing '=')");
}

TEST(BadIni, KeyGivenTwiceIsRefused) {
    expectHas(refused("run", badInput("dup_key.ini")),
              "dup_key.ini:10: [polymap] heading: given twice (first at line 9)");
}

TEST(BadIni, MrptParserErrorsNameTheFile) {
    // Found by fuzz_ini: MRPT's parser throws its own exception, without the file's name, for
    // a `$env{` left open (it escaped the INI reader as "unexpected error").
    const std::string ini = testing::TempDir() + "/env_open.ini";
    std::ofstream(ini) << "[scenario]\nname = $env{HOME\n";
    expectHas(refused("run", ini), "env_open.ini: Line 2: Expected closing `}` near: `$env{HOME`");
}

TEST(BadIni, HugeWorldIsBoundedBeforeAnythingIsBuilt) {
    // [world] size = 1e23: building it never finished. Refused while reading the INI.
    expectHas(refused("run", badInput("huge_world.ini")),
              "huge_world.ini: [world] size: at most 1000 x 1000 x 100 m");
}

TEST(BadIni, FinerWorldThanTheVoxelBudgetIsRefused) {
    const std::string ini = writeIniFrom(config("quickstart"), "voxels", "size       = 3.0 3.0 2.5",
                                         "size = 700 700 10");
    expectHas(refused("simulate", ini),
              "[world] resolution: walls and obstacles would fill 1.13e+07 voxels, more than "
              "the 1e+07 allowed");
}

TEST(BadIni, NonUtf8ScenarioNameIsRefused) {
    const std::string ini =
        writeIniFrom(config("quickstart"), "latin1", "name     = quickstart", "name = q\xe9");
    const auto line = refused("run", ini);
    expectHas(line, "latin1.ini:");
    expectHas(line, "bytes that are not valid UTF-8");
    // A control character would end up in file names.
    const std::string tab =
        writeIniFrom(config("quickstart"), "tab", "name     = quickstart", "name = q\x1bx");
    expectHas(refused("run", tab), "[scenario] name: 'q\\x1bx' is not a name");
    // nor a name that climbs out of out/ or hides the run
    for (const char* name : {"..", ".", ".hidden", "a/b", "a b", "-x"})
        expectHas(refused("run", writeIniFrom(config("quickstart"), "dots", "name     = quickstart",
                                              std::string("name = ") + name)),
                  "is not a name");
}

TEST(BadIni, RunThatFailsAfterSimulatingLeavesNothing) {
    const auto line = refused("run", badInput("steps_sigma8.ini"));
    expectHas(line, "fewer than 3 corners");
    expectHas(line, "left as it was): ");
}

// --- paths that are not UTF-8 ---

TEST(BadPath, NonUtf8RawlogPathRunsToTheEnd) {
    // Linux paths are bytes: such a path is read and its outputs written in full, the JSON
    // holding U+FFFD for the byte (it threw after half the outputs were written).
    const std::string dir = tmp("latin1_path");
    fs::create_directories(dir);
    const std::string rawlog = dir + "/q\xe9.rawlog";
    fs::copy_file(std::string(MRLOC_SOURCE_DIR) + "/rawlogs/quickstart.rawlog", rawlog);
    const std::string out = dir + "/out";
    const auto r = mrlocCmd("localize " + config("quickstart") + " " + quoted(rawlog) +
                            " --quiet --out " + out);
    ASSERT_EQ(r.code, 0) << r.output;
    const auto m = common::readJsonFile(out + "/metrics.json");
    expectHas(m["rawlog"].get<std::string>(), "q\xef\xbf\xbd.rawlog");
    EXPECT_EQ(m["observations"].get<int>(), 1499);  // all of quickstart.rawlog
}

// --- signals ---

namespace {

/** Starts `mrloc run <ini> --out <out> -q` (its stderr to `stderrFile`), waits until the
 *  rawlog is being written (in the staging folder beside `out`), sends `sig`, and returns the
 *  exit status. */
int interruptedRun(const std::string& ini, const std::string& out, int sig,
                   const std::string& stderrFile) {
    const pid_t pid = startRun(ini, out, false, stderrFile);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    const fs::path o(out);
    const std::string staging =
        (o.parent_path() / ("." + o.filename().string() + ".staging." + std::to_string(pid)))
            .string();
    while (!fs::exists(staging + "/long.rawlog.tmp") && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    kill(pid, sig);
    return waitStatus(pid);
}

}  // namespace

TEST(Signals, SigtermAndSigintEndARunAndRemoveEverything) {
    // A long quickstart: 3000 s simulated, seconds of work.
    std::string text = slurp(config("quickstart"));
    const std::string name = "name     = quickstart", duration = "duration = 60 ";
    text.replace(text.find(name), name.size(), "name = long");
    text.replace(text.find(duration), duration.size(), "duration = 3000 ");
    const std::string ini = testing::TempDir() + "/long.ini";
    std::ofstream(ini) << text;
    for (const auto& [sig, code] : std::map<int, int>{{SIGTERM, 143}, {SIGINT, 130}}) {
        const std::string out = tmp("signal_" + std::to_string(sig));
        const std::string said = out + ".stderr";
        EXPECT_EQ(interruptedRun(ini, out, sig, said), code);
        EXPECT_FALSE(fs::exists(out)) << "left behind after signal " << sig;
        // the last line says what stopped the run and what is left
        std::string last = slurp(said);
        while (!last.empty() && last.back() == '\n') last.pop_back();
        last = last.substr(last.rfind('\n') + 1);
        EXPECT_EQ(last, std::string("mrloc: ") + (sig == SIGINT ? "interrupted" : "terminated") +
                            ": " + out + " left as it was");
        for (const auto& e : fs::directory_iterator(fs::path(out).parent_path()))  // no staging
            EXPECT_EQ(e.path().filename().string().find("." + fs::path(out).filename().string()),
                      std::string::npos)
                << e.path() << " left behind after signal " << sig;
    }
}
