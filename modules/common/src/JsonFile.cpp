#include <fcntl.h>
#include <mrloc/common/AtomicFile.h>
#include <mrloc/common/Error.h>
#include <mrloc/common/JsonFile.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace mrloc::common {

namespace {

const char* typeName(const nlohmann::json& v) {
    if (v.is_object()) return "an object";
    if (v.is_array()) return "an array";
    if (v.is_string()) return "a string";
    if (v.is_boolean()) return "true or false";
    if (v.is_number()) return "a number";
    return "null";
}

const char* typeName(JsonType t) {
    switch (t) {
        case JsonType::Object: return "an object";
        case JsonType::Array: return "an array";
        case JsonType::String: return "a string";
        case JsonType::Number: return "a number";
        case JsonType::Boolean: return "true or false";
    }
    return "?";
}

bool holds(const nlohmann::json& v, JsonType t) {
    switch (t) {
        case JsonType::Object: return v.is_object();
        case JsonType::Array: return v.is_array();
        case JsonType::String: return v.is_string();
        case JsonType::Number: return v.is_number();
        case JsonType::Boolean: return v.is_boolean();
    }
    return false;
}

}  // namespace

nlohmann::json parseJson(const std::string& text, const std::string& where,
                         const JsonLimits& limits) {
    if (text.size() > limits.maxBytes)
        throw Error(where + ": " + std::to_string(text.size()) + " bytes of JSON, more than the " +
                    std::to_string(limits.maxBytes) + " allowed");
    // The callback sees each value's depth as it is parsed: a file nested deeper than any
    // mrloc writes is refused before its tree exists (the parser itself is not recursive).
    const auto depthCheck = [&](int depth, nlohmann::json::parse_event_t, nlohmann::json&) {
        if (size_t(depth) >= limits.maxDepth)
            throw Error(where + ": JSON nested more than " + std::to_string(limits.maxDepth) +
                        " levels deep");
        return true;
    };
    try {
        return nlohmann::json::parse(text, depthCheck);
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error(where + ": not valid JSON: " + oneLine(e.what()));
    }
}

nlohmann::json readJsonFile(const std::string& path, const JsonLimits& limits) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        if (errno == ELOOP)
            throw Error(path + ": a symbolic link (mrloc reads no JSON file through a link)");
        if (errno == ENOENT) throw Error(pathInWords(path) + ": no such file");
        throw Error(path + ": cannot open: " + std::strerror(errno));
    }
    struct stat st {};
    std::string text;
    const auto fail = [&](const std::string& why) {
        ::close(fd);
        throw Error(path + ": " + why);
    };
    if (::fstat(fd, &st) != 0) fail(std::strerror(errno));
    if (S_ISDIR(st.st_mode)) fail("a folder, not a JSON file");
    if (!S_ISREG(st.st_mode)) fail("not a regular file (a FIFO or a device?)");
    if (size_t(st.st_size) > limits.maxBytes)
        fail(std::to_string(st.st_size) + " bytes, more than the " +
             std::to_string(limits.maxBytes) + " a JSON file may hold here");
    text.resize(size_t(st.st_size));
    size_t got = 0;
    while (got < text.size()) {
        const ssize_t n = ::read(fd, text.data() + got, text.size() - got);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) fail(std::string("cannot read: ") + std::strerror(errno));
        if (n == 0) break;  // shrank while read: parse what is there
        got += size_t(n);
    }
    ::close(fd);
    text.resize(got);
    return parseJson(text, path, limits);
}

void checkJsonShape(const nlohmann::json& j, const std::vector<JsonField>& shape,
                    const std::string& where) {
    if (!j.is_object()) throw Error(where + ": " + typeName(j) + ", expected a JSON object");
    for (const auto& f : shape) {
        // a missing key on the way is not an error: the field is absent
        const nlohmann::json* node = &j;
        bool present = true;
        std::string rest = f.pointer;
        while (present && !rest.empty()) {
            const auto next = rest.find('/', 1);
            const std::string key = rest.substr(1, next == std::string::npos ? next : next - 1);
            rest = next == std::string::npos ? "" : rest.substr(next);
            if (!node->is_object() || !node->contains(key)) {
                present = false;
                break;
            }
            node = &(*node)[key];
            if (!rest.empty() && !node->is_object())
                throw Error(where + ": " + f.pointer.substr(0, f.pointer.size() - rest.size()) +
                            " is " + typeName(*node) + ", expected an object");
        }
        if (present && !holds(*node, f.type))
            throw Error(where + ": " + f.pointer + " is " + typeName(*node) + ", expected " +
                        typeName(f.type));
    }
}

}  // namespace mrloc::common
