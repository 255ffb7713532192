#include <mrloc/common/Error.h>
#include <mrloc/common/JsonFile.h>
#include <mrloc/common/Names.h>
#include <mrloc/logimport/Format.h>
#include <mrloc/logimport/TextLog.h>
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

namespace mrloc::logimport {

namespace fs = std::filesystem;

FormatOptions::FormatOptions(const std::string& format, const std::vector<FormatOption>& declared,
                             const std::vector<std::string>& given)
    : format_(format) {
    for (const auto& o : declared) values_[o.key] = o.defaultValue;
    for (const auto& g : given) {
        const size_t eq = g.find('=');
        if (eq == std::string::npos || eq == 0)
            throw Error("--opt " + common::printable(g) + ": expected key=value");
        const std::string key = g.substr(0, eq);
        if (!values_.count(key)) {
            std::vector<std::string> keys;
            for (const auto& o : declared) keys.push_back(o.key);
            const auto near = common::nearMiss(key, keys);
            std::string known;
            for (const auto& k : keys) known += (known.empty() ? "" : ", ") + k;
            throw Error("--opt " + common::printable(key) + ": not an option of format '" + format +
                        "'" + (near ? " (did you mean '" + *near + "'?)" : "") +
                        "; its options: " + (known.empty() ? "none" : known));
        }
        if (given_.count(key)) throw Error("--opt " + key + " is given twice");
        values_[key] = g.substr(eq + 1);
        given_[key] = true;
    }
}

const std::string& FormatOptions::text(const std::string& key) const { return values_.at(key); }

double FormatOptions::number(const std::string& key) const {
    const std::string& s = text(key);
    const auto v = parseNumber<double>(s);
    if (!v) throw Error("--opt " + key + "=" + common::printable(s) + ": not a finite number");
    return *v;
}

bool FormatOptions::flag(const std::string& key) const {
    const std::string& s = text(key);
    if (s == "yes" || s == "true" || s == "1") return true;
    if (s == "no" || s == "false" || s == "0") return false;
    throw Error("--opt " + key + "=" + common::printable(s) + ": expected yes or no");
}

std::vector<double> FormatOptions::numbers(const std::string& key) const {
    std::vector<double> out;
    const std::string& s = text(key);
    size_t i = 0;
    while (i < s.size()) {
        while (i < s.size() && (s[i] == ',' || s[i] == ' ')) ++i;
        const size_t start = i;
        while (i < s.size() && s[i] != ',' && s[i] != ' ') ++i;
        if (i == start) break;
        const auto v = parseNumber<double>(std::string_view(s).substr(start, i - start));
        if (!v)
            throw Error("--opt " + key + ": '" + common::printable(s.substr(start, i - start)) +
                        "' is not a finite number");
        out.push_back(*v);
        if (out.size() > 1000) throw Error("--opt " + key + ": more than 1000 numbers");
    }
    return out;
}

void FormatRegistry::add(Format format) {
    const std::string name = format.name;
    if (!formats_.emplace(name, std::move(format)).second)
        throw Error("import format '" + name + "' registered twice");
}

const Format& FormatRegistry::get(const std::string& name) const {
    if (const auto it = formats_.find(name); it != formats_.end()) return it->second;
    std::vector<std::string> names;
    std::string list;
    for (const auto& [n, f] : formats_) names.push_back(n), list += (list.empty() ? "" : ", ") + n;
    const auto near = common::nearMiss(name, names);
    throw Error("no import format '" + common::printable(name) + "'" +
                (near ? " (did you mean '" + *near + "'?)" : "") + "; the formats: " + list);
}

std::string formatHelp(const Format& f) {
    std::string out = "  " + f.name + " " + f.inputs + "\n      " + f.summary + "\n";
    for (const auto& o : f.options)
        out += "      --opt " + o.key + "=" + (o.defaultValue.empty() ? "..." : o.defaultValue) +
               "   " + o.help + "\n";
    return out;
}

std::string formatsHelp(const FormatRegistry& registry) {
    std::string out = "formats:\n";
    for (const auto& [name, f] : registry.all()) out += formatHelp(f);
    return out;
}

std::string realLogBeaconKeys() {
    return "# A real log's odometry drifts along its path whatever its reading rate: a random\n"
           "# walk beside the per-reading noise (doc/beacons.md, \"Odometry noise\"). Raise it\n"
           "# if the tracker refuses good ranges after a stretch without any (a poor odometry).\n"
           "odometry_walk_xy = 0.05\n"
           "odometry_walk_phi = 0.05\n"
           "odometry_walk_phi_per_m = 0.02\n"
           "# Keys you may want to change (doc/ini.md): range_sigma, the ranges' noise (m);\n"
           "# gate_probability and huber_k, how gross errors are refused or weighed less;\n"
           "# start = x y phi_deg, if you know where the robot starts (else the tracker finds\n"
           "# it from the ranges: doc/beacons.md, \"Start-up\").\n";
}

namespace {

ImportSummary convertAll(const Format& format, const ImportRequest& request,
                         const std::string& rawlogPath) {
    const auto& inputs = request.inputs;
    ImportOutput output(rawlogPath);
    try {
        format.convert(request, output);
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {  // the format's library (rosbag::BagException...)
        throw Error(inputs[0] + ": " + oneLine(e.what()));
    }
    return output.commit();
}

nlohmann::json toJson(const ImportSummary& s) {
    nlohmann::json j{{"rawlog", s.rawlog}, {"groundTruth", s.groundTruth},  {"files", s.files},
                     {"notes", s.notes},   {"warnings", s.warnings},        {"t0", s.t0},
                     {"t1", s.t1},         {"observations", s.observations}};
    for (const auto& [key, c] : s.streams)
        j["streams"].push_back({key.first, key.second, c.count, c.t0, c.t1});
    return j;
}

ImportSummary fromJson(const nlohmann::json& j) {
    ImportSummary s;
    s.rawlog = j["rawlog"];
    s.groundTruth = j["groundTruth"].get<std::map<std::string, size_t>>();
    s.files = j["files"].get<std::vector<std::string>>();
    s.notes = j["notes"].get<std::vector<std::string>>();
    s.warnings = j.value("warnings", std::vector<std::string>{});
    s.t0 = j["t0"], s.t1 = j["t1"], s.observations = j["observations"];
    for (const auto& r : j["streams"])
        s.streams[{r[0].get<std::string>(), r[1].get<std::string>()}] = {r[2], r[3], r[4]};
    return s;
}

/** convertAll in a child process: its summary or its error comes back through a pipe (its
 *  console goes nowhere); a crash is one line, and the temporary files it left are removed. */
ImportSummary convertIsolated(const Format& format, const ImportRequest& request,
                              const std::string& rawlogPath) {
    const auto& inputs = request.inputs;
    int fds[2];
    if (pipe(fds) != 0) throw Error("cannot make a pipe to convert " + inputs[0]);
    std::cout.flush(), std::cerr.flush();
    const pid_t pid = fork();
    if (pid < 0) throw Error("cannot fork to convert " + inputs[0]);
    if (pid == 0) {
        close(fds[0]);
        // the reader's libraries print their own console text (ROS: "Error reading CONNECTION
        // header" before it throws): the child speaks through its reply only, and mrloc's one
        // line says what went wrong
        if (const int null = open("/dev/null", O_WRONLY); null >= 0) {
            dup2(null, STDOUT_FILENO);
            dup2(null, STDERR_FILENO);
            close(null);
        }
        std::string reply;
        try {
            reply = "O" + toJson(convertAll(format, request, rawlogPath)).dump();
        } catch (const std::exception& e) {
            reply = "E" + oneLine(e.what());
        }
        for (size_t done = 0; done < reply.size();) {
            const ssize_t n = write(fds[1], reply.data() + done, reply.size() - done);
            if (n <= 0) break;
            done += size_t(n);
        }
        _exit(0);
    }
    close(fds[1]);
    std::string reply;
    char buf[65536];
    for (ssize_t n; (n = read(fds[0], buf, sizeof buf)) > 0;) reply.append(buf, size_t(n));
    close(fds[0]);
    int status = 0;
    waitpid(pid, &status, 0);
    if (!reply.empty() && reply[0] == 'O')
        return fromJson(common::parseJson(reply.substr(1), "the importer's reply"));
    if (!reply.empty() && reply[0] == 'E') throw Error(reply.substr(1));
    // the reader died: what it left under temporary names goes
    const fs::path out(rawlogPath);
    const std::string stem = out.stem().string() + ".";
    std::error_code ec;
    const fs::path dir = out.parent_path().empty() ? fs::path(".") : out.parent_path();
    for (const auto& e : fs::directory_iterator(dir, ec)) {
        const std::string name = e.path().filename().string();
        if (name.rfind(stem, 0) == 0 && name.size() > 4 &&
            name.compare(name.size() - 4, 4, ".tmp") == 0)
            fs::remove(e.path(), ec);
    }
    throw Error(inputs[0] + ": the " + format.name + " reader crashed on this file" +
                (WIFSIGNALED(status) ? " (signal " + std::to_string(WTERMSIG(status)) + ")"
                                     : std::string()) +
                ": nothing written");
}

}  // namespace

ImportSummary runImport(const Format& format, const std::vector<std::string>& inputs,
                        const std::vector<std::string>& options, const std::string& rawlogPath) {
    if (inputs.size() < format.minInputs || inputs.size() > format.maxInputs)
        throw Error("format '" + format.name + "' reads " + format.inputs + ", not " +
                    std::to_string(inputs.size()) + " input(s)");
    // the options are checked here, so that their errors come before any fork
    const ImportRequest request{inputs, FormatOptions(format.name, format.options, options)};
    if (format.isolated) return convertIsolated(format, request, rawlogPath);
    return convertAll(format, request, rawlogPath);
}

void registerAllFormats(FormatRegistry& r) {
    registerLibrsf(r);
    registerSonarText(r);
    registerMrclam(r);
    registerCarmen(r);
    registerRosbag(r);
}

}  // namespace mrloc::logimport
