// `mrloc batch`: trials over seeds and a grid of keys, run through GNU parallel (one machine,
// or ssh hosts sharing the batch folder), or written out as a Slurm job array or a plain
// list of commands; `--collect` sums them up (BatchSummary.cpp). mrloc schedules nothing
// itself: parallel's job log is what `--resume` continues (doc/batch.md).
#include <fcntl.h>
#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/FolderLock.h>
#include <mrloc/common/Metrics.h>
#include <mrloc/common/Names.h>
#include <mrloc/common/Outcome.h>
#include <mrloc/common/RunTransaction.h>
#include <mrloc/common/ShellWord.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <thread>

#include "BatchPlan.h"
#include "BatchSummary.h"
#include "CommandLine.h"
#include "Commands.h"
#include "IniFile.h"

namespace mrloc::app {

namespace fs = std::filesystem;

namespace {

using common::shellWord;

/** This executable's absolute path: what the trials run (ssh hosts: the same path). */
std::string selfPath() {
    std::error_code ec;
    const auto p = fs::read_symlink("/proc/self/exe", ec);
    if (ec) throw Error("cannot find mrloc's own path (/proc/self/exe); give --mrloc");
    return p.string();
}

/** GNU parallel's -S, parsed against its grammar ("[@groups/][ncpus/]sshlogin,..."): each
 *  entry is `[N/][user@]host`, or `[N/]:` (this machine). Refused: the special sshlogins
 *  `-` (read logins from standard input) and `..` (from ~/.parallel/sshloginfile), an ssh
 *  command of its own (`/path/ssh -p 22 host`: a word with a blank or a '/'), `user:password@`
 *  (sshpass), host groups, ports and anything a shell or ssh would read as an option. */
void checkHosts(const std::string& hosts) {
    const auto refuse = [&](const std::string& entry, const std::string& why) {
        throw Error("--hosts " + common::printable(hosts.substr(0, 80)) + ": " +
                    (entry.empty() ? std::string("an empty entry")
                                   : "'" + common::printable(entry.substr(0, 80)) + "'") +
                    " " + why + " (expected [N/][user@]host or [N/]: entries, comma-separated: "
                    "2/user@node1,node2,:)");
    };
    if (hosts.empty() || hosts.size() > 4096) refuse(hosts, "is not a host list");
    const auto isName = [](const std::string& w, const char* extra) {
        if (w.empty() || w.size() > 253 || w[0] == '-' || w[0] == '.') return false;
        const std::string allowed = std::string("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                "0123456789-") + extra;
        return w.find_first_not_of(allowed) == std::string::npos && w.find("..") == std::string::npos;
    };
    size_t from = 0;
    while (true) {
        const auto comma = hosts.find(',', from);
        std::string entry = hosts.substr(from, comma == std::string::npos ? comma : comma - from);
        from = comma + 1;
        if (entry == "-") refuse(entry, "reads ssh logins from standard input");
        if (entry == "..") refuse(entry, "reads ~/.parallel/sshloginfile");
        std::string login = entry;
        if (const auto slash = login.find('/'); slash != std::string::npos) {
            const std::string cpus = login.substr(0, slash);
            if (cpus.empty() || cpus.size() > 4 ||
                cpus.find_first_not_of("0123456789") != std::string::npos || std::stoul(cpus) == 0)
                refuse(entry, "has a '/' that is not after a number of CPUs (N/host)");
            login = login.substr(slash + 1);
        }
        if (login != ":") {
            const auto at = login.find('@');
            const std::string user = at == std::string::npos ? "" : login.substr(0, at);
            const std::string host = at == std::string::npos ? login : login.substr(at + 1);
            if (at != std::string::npos && !isName(user, "._"))
                refuse(entry, "has no user name a login can have before '@'");
            if (!isName(host, "."))
                refuse(entry, "is not a host name (letters, digits, '-' and '.'; no port, "
                              "password, blank or ssh command)");
        }
        if (comma == std::string::npos) break;
    }
}

/** The child run by waitChild, for the signal handler to pass SIGINT / SIGTERM on. */
volatile sig_atomic_t childPid = 0;
volatile sig_atomic_t childSignal = 0;
extern "C" void forwardSignal(int sig) {
    childSignal = sig;
    if (childPid > 0) kill(pid_t(childPid), sig);
}

/** What runProgram's child gets besides its arguments: a working folder and environment. */
struct ChildSetting {
    std::string workdir;                                       ///< "" : this process's
    std::vector<std::pair<std::string, std::string>> environment;  ///< set in the child
};

/** Runs `argv` (no shell) with stdout to /dev/null (trials write their records) or to
 *  `captured`; passes SIGINT and SIGTERM on to it. Its exit status, or 128 + its signal. */
int runProgram(const std::vector<std::string>& argv, std::string* captured = nullptr,
               const ChildSetting& setting = {}) {
    int pipeFds[2] = {-1, -1};
    if (captured && pipe(pipeFds) != 0) throw Error("cannot make a pipe");
    const pid_t pid = fork();
    if (pid < 0) throw Error("cannot start " + argv[0]);
    if (pid == 0) {
        if (captured) {
            dup2(pipeFds[1], STDOUT_FILENO);
            close(pipeFds[0]);
            close(pipeFds[1]);
        } else if (const int null = open("/dev/null", O_WRONLY); null >= 0) {
            dup2(null, STDOUT_FILENO);
        }
        if (!setting.workdir.empty() && chdir(setting.workdir.c_str()) != 0) _exit(126);
        for (const auto& [name, value] : setting.environment) setenv(name.c_str(), value.c_str(), 1);
        std::vector<char*> args;
        for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
        args.push_back(nullptr);
        execvp(args[0], args.data());
        _exit(127);
    }
    if (captured) {
        close(pipeFds[1]);
        char buf[4096];
        for (ssize_t n; (n = read(pipeFds[0], buf, sizeof buf)) > 0;)
            if (captured->size() < (1u << 20)) captured->append(buf, size_t(n));
        close(pipeFds[0]);
    }
    struct sigaction forward {
    }, oldInt{}, oldTerm{};
    forward.sa_handler = forwardSignal;
    sigemptyset(&forward.sa_mask);
    childPid = pid;
    sigaction(SIGINT, &forward, &oldInt);
    sigaction(SIGTERM, &forward, &oldTerm);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    sigaction(SIGINT, &oldInt, nullptr);
    sigaction(SIGTERM, &oldTerm, nullptr);
    childPid = 0;
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

/** GNU parallel, checked to be GNU's (moreutils installs another `parallel`). */
void checkGnuParallel() {
    std::string version;
    const int code = runProgram({"parallel", "--version"}, &version);
    if (code == 127)
        throw Error(
            "GNU parallel is not installed (scripts/install-deps.sh installs it: apt-get install "
            "parallel); --emit commands or --emit slurm need none");
    if (code != 0 || version.find("GNU parallel") == std::string::npos)
        throw Error(
            "`parallel` on the PATH is not GNU parallel (moreutils' is another program); "
            "install Debian's package parallel");
}

/** The batch's trial command, as parallel, the command list and Slurm run it. */
std::vector<std::string> trialCommand(const std::string& mrloc, const std::string& dir,
                                      const std::string& point, const std::string& first,
                                      const std::string& last) {
    return {mrloc, "trial", "--batch", dir, "--point", point, "--seed", first, "--last-seed", last};
}

/** The environment that carries the batch's folder and mrloc's path to parallel's jobs. */
constexpr const char* kEnvMrloc = "MRLOC_BATCH_MRLOC";
constexpr const char* kEnvFolder = "MRLOC_BATCH_FOLDER";

/** GNU parallel's command line, run in the batch folder. GNU parallel expands replacement
 *  strings ({}, {1}, {= perl =}) in every word of the command, -q or not, and in some of its
 *  options' values: so no word of it holds anything but mrloc's own text and the job's
 *  numbers from jobs.txt. The folder and mrloc's path are environment variables that the
 *  job's shell expands, quoted ("$VAR": one word, never parsed again); --env carries them to
 *  ssh hosts, quoted by parallel as values, never expanded. The one user string, -S's host
 *  list, holds only what checkHosts lets through: letters, digits and - . _ @ / : (no '{'). */
std::vector<std::string> parallelCommand(unsigned jobs, bool resume, const std::string& hosts) {
    std::vector<std::string> argv = {"parallel",   "--will-cite", "--joblog", batch_dir::joblog("."),
                                     "--jobs",     std::to_string(jobs),  "--colsep", " ",
                                     "--arg-file", batch_dir::jobs(".")};
    if (resume) argv.push_back("--resume-failed");
    if (!hosts.empty())
        argv.insert(argv.end(), {"-S", hosts, "--env", kEnvMrloc, "--env", kEnvFolder});
    std::string command;
    for (const auto& word : trialCommand(std::string("\"$") + kEnvMrloc + "\"",
                                         std::string("\"$") + kEnvFolder + "\"", "{1}", "{2}", "{3}"))
        command += (command.empty() ? "" : " ") + word;
    argv.push_back(command);
    return argv;
}

/** The jobs in order: point, first seed, last seed. */
std::vector<std::array<unsigned long, 3>> jobsOf(const BatchPlan& plan) {
    std::vector<std::array<unsigned long, 3>> jobs;
    for (size_t p = 0; p < plan.pointCount(); ++p)
        for (unsigned long s = plan.firstSeed; s <= plan.lastSeed; s += plan.chunk)
            jobs.push_back({p, s, std::min<unsigned long>(plan.lastSeed, s + plan.chunk - 1)});
    return jobs;
}

std::string jobsText(const BatchPlan& plan) {
    std::string text;
    for (const auto& [p, first, last] : jobsOf(plan))
        text += std::to_string(p) + " " + std::to_string(first) + " " + std::to_string(last) + "\n";
    return text;
}

std::string commandsText(const BatchPlan& plan, const std::string& mrloc, const std::string& dir) {
    std::string text;
    for (const auto& [p, first, last] : jobsOf(plan)) {
        std::string line;
        for (const auto& a : trialCommand(mrloc, dir, std::to_string(p), std::to_string(first),
                                          std::to_string(last)))
            line += (line.empty() ? "" : " ") + shellWord(a);
        text += line + "\n";
    }
    return text;
}

/** A Slurm job array: task k runs line k + 1 of jobs.txt. Slurm's MaxArraySize (1001 by
 *  default) bounds one array; a larger batch is split into arrays by --array's offset
 *  (doc/batch.md). */
std::string slurmScript(const BatchPlan& plan, const std::string& mrloc, const std::string& dir,
                        const std::string& name, size_t throttle) {
    std::ostringstream s;
    const size_t n = plan.jobCount();
    s << "#!/bin/bash\n"
      << "# mrloc batch " << common::printable(name) << ": " << plan.trialCount() << " trials ("
      << plan.seedCount() << " seeds x " << plan.pointCount() << " points) in " << n
      << " jobs of up to " << plan.chunk << (plan.chunk == 1 ? " seed" : " seeds")
      << ", one per task of a job array.\n"
      << "# Submit: sbatch " << shellWord(dir + "/batch.slurm") << "   then: mrloc batch --collect "
      << shellWord(dir) << "\n"
      << "# The folder must be on a file system every node shares, and mrloc installed at\n"
      << "# the same path on every node (doc/batch.md). Arrays over MaxArraySize: submit\n"
      << "# again with --array=1000-1999 etc. A trial whose record exists is not run again.\n"
      << "#SBATCH --job-name=mrloc-" << common::printable(name).substr(0, 40) << "\n"
      << "#SBATCH --array=0-" << (n - 1) << (throttle ? "%" + std::to_string(throttle) : "") << "\n"
      << "#SBATCH --ntasks=1\n"
      << "#SBATCH --cpus-per-task=1\n"
      // sbatch would read a folder's blanks, quotes and '%' in --output: the task's output
      // goes where the shell, quoting it, sends it
      << "#SBATCH --output=/dev/null\n"
      << "set -euo pipefail\n"
      << "exec >> " << shellWord(dir + "/slurm/")
      << "\"${SLURM_ARRAY_JOB_ID:-0}_${SLURM_ARRAY_TASK_ID}.out\" 2>&1\n"
      << "line=$(sed -n \"$((SLURM_ARRAY_TASK_ID + 1))p\" " << shellWord(dir + "/jobs.txt") << ")\n"
      << "read -r point first last <<< \"$line\"\n"
      << "exec";
    for (const auto& a : trialCommand(mrloc, dir, "POINT", "FIRST", "LAST"))
        s << " "
          << (a == "POINT"   ? std::string("\"$point\"")
              : a == "FIRST" ? std::string("\"$first\"")
              : a == "LAST"  ? std::string("\"$last\"")
                             : shellWord(a));
    s << "\n";
    return s.str();
}

/** The summary of a batch folder checked by batch_dir::checkFolder (before parallel ran, or
 *  by --collect itself), written and printed; exit 3 while trials failed or are missing. */
int collectAndPrint(const std::string& dir) {
    const BatchSummary summary = collectBatch(dir);
    writeSummary(dir, summary);
    std::cout << summaryText(summary);
    std::cout << "summary: " << batch_dir::summary(dir) << "\n";
    if (summary.failed.empty() && summary.missing.empty()) return 0;
    std::cerr << "mrloc batch: " << summary.failed.size() << " of " << summary.trials
              << " trials failed and " << summary.missing.size()
              << " are missing (listed in summary.txt; mrloc batch ... --resume runs them)\n";
    return common::kFailedExit;
}

/** The batch's plan from its arguments: seeds, chunk, --set keys and --grid axes, bounded. */
BatchPlan planOf(const std::string& ini, const std::string& seeds, unsigned chunk,
                 const std::vector<std::string>& sets, const std::vector<std::string>& grid) {
    BatchPlan plan;
    plan.ini = ini;
    std::tie(plan.firstSeed, plan.lastSeed) = parseSeeds(seeds);
    if (chunk < 1 || chunk > 100000)
        throw Error("--chunk " + std::to_string(chunk) + ": 1 .. 100000 seeds per job");
    plan.chunk = chunk;
    for (const auto& k : sets) plan.sets.push_back(parseOverride(k, "--set"));
    for (const auto& g : grid) {
        plan.grid.push_back(parseGridAxis(g));
        for (const auto& other : plan.grid)
            if (&other != &plan.grid.back() && other.name() == plan.grid.back().name())
                throw Error("--grid " + other.name() + ": given twice");
        if (plan.pointCount() > BatchPlan::kMaxPoints)
            throw Error("--grid: more than 10,000 points");
    }
    if (double(plan.seedCount()) * double(plan.pointCount()) > double(BatchPlan::kMaxTrials))
        throw Error("--seeds and --grid: more than 1,000,000 trials in one batch");
    return plan;
}

/** A batch folder already there, for --resume or --emit: the same plan and INI text, or
 *  the job log's numbers would name other trials. */
void checkSameBatch(const std::string& dir, const nlohmann::json& planJson,
                    const std::string& iniText) {
    batch_dir::checkFolder(dir);
    auto held = common::readJsonFile(batch_dir::plan(dir));
    auto given = planJson;
    held.erase("ini"), given.erase("ini");
    if (held != given || readIniText(batch_dir::ini(dir)) != iniText)
        throw Error(common::pathInWords(dir) +
                    ": its batch has other seeds, keys or INI text than these (batch.json, "
                    "batch.ini); give the same to --resume, or another --out");
}

/** A new batch folder (batch.ini, jobs.txt, batch.json), written whole beside it and then
 *  renamed into its place: a full disk leaves no half batch that neither a new batch nor
 *  --resume would take. */
void makeBatchFolder(const std::string& dir, const std::string& dirAbs, const BatchPlan& plan,
                     const nlohmann::json& planJson, const std::string& iniText) {
    if (fs::exists(fs::symlink_status(dir)) &&
        (!fs::is_directory(fs::symlink_status(dir)) || !fs::is_empty(dir)))
        throw Error(common::pathInWords(dir) +
                    ": exists and is not a batch folder; give another --out");
    const fs::path abs = fs::path(dirAbs);
    const std::string staging = (abs.parent_path() / ("." + abs.filename().string() + ".staging." +
                                                      std::to_string(getpid())))
                                    .string();
    std::error_code ec;
    const int slot = common::holdTemporaryOnSignal(staging);  // Ctrl-C leaves none
    try {
        fs::remove_all(staging, ec);
        common::makeDirectories(staging);
        common::writeFileAtomically(batch_dir::ini(staging), iniText);
        common::writeFileAtomically(batch_dir::jobs(staging), jobsText(plan));
        common::saveJson(batch_dir::plan(staging), planJson);
        if (::rename(staging.c_str(), dirAbs.c_str()) != 0)  // replaces an empty folder
            throw Error(common::pathInWords(dir) +
                        ": cannot make the batch folder: " + std::strerror(errno));
    } catch (...) {
        fs::remove_all(staging, ec);
        common::releaseTemporaryOnSignal(slot);
        throw;
    }
    common::releaseTemporaryOnSignal(slot);
}

/** --emit: batch.slurm (a job array, its output folder made) or commands.txt; prints it. */
int emitJobs(const std::string& what, const BatchPlan& plan, const std::string& mrloc,
             const std::string& dir, const std::string& dirAbs, const std::string& name,
             unsigned throttle) {
    const bool slurm = what == "slurm";
    const std::string path = (fs::path(dir) / (slurm ? "batch.slurm" : "commands.txt")).string();
    common::writeFileAtomically(path, slurm ? slurmScript(plan, mrloc, dirAbs, name, throttle)
                                            : commandsText(plan, mrloc, dirAbs));
    if (slurm) {
        fs::permissions(path, fs::perms::owner_exec, fs::perm_options::add);
        // Slurm opens each task's --output there and makes no folder
        common::makeDirectories((fs::path(dir) / "slurm").string());
    }
    std::cout << path << "\n";
    return 0;
}

/** The batch's jobs through GNU parallel, `jobs` at once, then its summary; the exit code. */
int runThroughParallel(const BatchPlan& plan, const std::string& mrloc, const std::string& dir,
                       const std::string& dirAbs, unsigned jobs, bool resume,
                       const std::string& hosts) {
    checkGnuParallel();
    const std::vector<std::string> argvParallel = parallelCommand(jobs, resume, hosts);
    std::cerr << "mrloc batch: " << plan.trialCount() << " trials (" << plan.seedCount()
              << " seeds x " << plan.pointCount() << " points) in " << plan.jobCount() << " jobs, "
              << jobs << " at once, through GNU parallel; job log " << batch_dir::joblog(dir)
              << "\n";
    // parallel runs in the batch folder, and the folder and mrloc's path reach the trials
    // through the environment: no argument parallel parses holds a user's string
    // The command is POSIX sh: PARALLEL_SHELL says so to parallel, here and on hosts, whatever
    // the login shell (with SHELL unset, as under cron or CI, a host's job ran nothing, exit 0)
    const int code = runProgram(
        argvParallel, nullptr,
        {dirAbs, {{kEnvMrloc, mrloc}, {kEnvFolder, dirAbs}, {"PARALLEL_SHELL", "/bin/sh"}}});
    if (code >= 128 + 1 && code <= 128 + 64) return code;  // interrupted: --resume continues
    if (childSignal) return 128 + int(childSignal);
    return collectAndPrint(dir);
}

}  // namespace

int batch(const method::Registry& registry, int argc, char** argv) {
    CommandLine cmd(
        "mrloc batch: the INI's trials (mrloc trial) over a range of seeds and a grid of keys, "
        "run through GNU parallel (--jobs on this machine, --hosts over ssh), or written as a "
        "Slurm job array (--emit slurm) or a list of commands (--emit commands). Everything "
        "goes to one folder; --collect sums it up per grid point, `mrloc report <folder>` "
        "renders it (doc/batch.md).");
    TCLAP::UnlabeledValueArg<std::string> ini("ini", "scenario INI file", false, "", "INI", cmd);
    TCLAP::ValueArg<std::string> seeds("", "seeds", "seeds A..B (inclusive)", false, "", "A..B",
                                       cmd);
    TCLAP::MultiArg<std::string> grid(
        "", "grid", "section.key=v1,v2,...: a key's values; several --grid make their product",
        false, "KEY=VALUES", cmd);
    TCLAP::MultiArg<std::string> set("", "set", "section.key=value: every trial's (repeatable)",
                                     false, "KEY=VALUE", cmd);
    TCLAP::ValueArg<unsigned> jobs("j", "jobs", "jobs at once (default: the cores)", false, 0, "N",
                                   cmd);
    TCLAP::ValueArg<unsigned> chunk("", "chunk",
                                    "seeds per job, run by one process in a row (default 10: "
                                    "mrloc's start-up shared; 1: a job per trial)",
                                    false, 10, "K", cmd);
    TCLAP::ValueArg<std::string> out(
        "o", "out", "the batch folder (default: out/<scenario name>-batch)", false, "", "DIR", cmd);
    TCLAP::SwitchArg resume("", "resume",
                            "continue the batch in the folder: jobs its job log holds as done, "
                            "and seeds with a record, are not run again",
                            cmd);
    TCLAP::ValueArg<std::string> hosts(
        "", "hosts", "GNU parallel's -S: ssh hosts sharing the folder (2/user@node1,node2,:)",
        false, "", "HOSTS", cmd);
    TCLAP::ValueArg<std::string> emit("", "emit",
                                      "write instead of running: slurm (batch.slurm, a job "
                                      "array) or commands (commands.txt, one job a line)",
                                      false, "", "slurm|commands", cmd);
    TCLAP::ValueArg<std::string> mrlocPath(
        "", "mrloc", "the mrloc the trials run (default: this one; hosts: the same path)", false,
        "", "PATH", cmd);
    TCLAP::ValueArg<std::string> collect("", "collect", "sum up the batch in DIR", false, "", "DIR",
                                         cmd);
    if (const auto code = parseArgs(cmd, argc, argv)) return *code;

    if (collect.isSet()) {
        if (ini.isSet() || seeds.isSet())
            throw Error("--collect takes the batch folder alone (mrloc batch --collect DIR)");
        batch_dir::readPlan(collect.getValue());  // a batch folder, before its lock is made
        common::FolderLock lock(collect.getValue());
        batch_dir::checkFolder(collect.getValue());
        return collectAndPrint(collect.getValue());
    }
    if (!ini.isSet()) throw Error("missing <INI> (mrloc batch <ini> --seeds A..B)");
    if (!seeds.isSet()) throw Error("missing --seeds A..B");
    if (emit.isSet() && emit.getValue() != "slurm" && emit.getValue() != "commands")
        throw Error("--emit " + common::printable(emit.getValue()) + ": slurm or commands");
    if (hosts.isSet()) checkHosts(hosts.getValue());

    const BatchPlan plan =
        planOf(ini.getValue(), seeds.getValue(), chunk.getValue(), set.getValue(), grid.getValue());

    // every point's keys through the configuration's checks before anything is written
    Setup first = loadSetup(registry, plan.ini, long(plan.firstSeed), true, "", plan.trialKeys(0));
    if (!first.simulation)
        throw Error(plan.ini + ": [scenario] describes no simulation; a batch simulates it");
    for (const auto& w : first.warnings)
        std::cerr << "warning: " << w << "\n";  // once, not per trial
    for (size_t p = 1; p < plan.pointCount(); ++p)
        loadSetup(registry, plan.ini, long(plan.firstSeed), true, "", plan.trialKeys(p));

    const std::string dir = out.isSet() ? out.getValue() : "out/" + first.scenario.name + "-batch";
    common::checkRunFolderPath(dir, out.isSet() ? "--out" : "[scenario] name");
    const std::string dirAbs = fs::absolute(dir).lexically_normal().string();
    const std::string mrloc = mrlocPath.isSet() ? mrlocPath.getValue() : selfPath();
    const nlohmann::json planJson = toJson(plan);

    // one mrloc at a time in a batch folder (the rule of run folders), and nothing in it a
    // link: parallel's job log, the records and the summary are written where they seem
    common::FolderLock lock(dir);
    if (batch_dir::isBatch(dir)) {
        if (!resume.isSet() && !emit.isSet()) {
            batch_dir::checkFolder(dir);
            throw Error(common::pathInWords(dir) +
                        ": holds a batch already (--resume continues it; another --out starts "
                        "a new one)");
        }
        checkSameBatch(dir, planJson, first.iniText);
    } else {
        if (resume.isSet())
            throw Error(common::pathInWords(dir) + ": no batch to resume (no batch.json)");
        makeBatchFolder(dir, dirAbs, plan, planJson, first.iniText);
    }
    if (emit.isSet())
        return emitJobs(emit.getValue(), plan, mrloc, dir, dirAbs, first.scenario.name,
                        jobs.getValue());
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    return runThroughParallel(plan, mrloc, dir, dirAbs,
                              jobs.isSet() && jobs.getValue() > 0 ? jobs.getValue() : cores,
                              resume.isSet(), hosts.getValue());
}

}  // namespace mrloc::app
