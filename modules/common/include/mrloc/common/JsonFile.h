#pragma once
// The one reader of every JSON file mrloc reads (metrics.json, provenance.json, a batch's
// plan, records and summary, beacons.study.json, an importer child's reply): such a file may
// come from someone else, so it is bounded in size and nesting (nlohmann's dump, copy and
// comparison recurse: a 600 KB nested array overflows the stack), never read through a
// symbolic link, and checked for the types of the keys its reader uses. Every refusal is one
// line naming the file (doc/errors.md, "JSON files").
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace mrloc::common {

struct JsonLimits {
    size_t maxBytes = 64u << 20;  ///< a run's metrics.json is under 1 MB; a batch summary's 10
    size_t maxDepth = 32;         ///< mrloc's own files nest at most 6 levels
};

/** `text` parsed within `limits`; throws mrloc::Error "<where>: ..." in one line. */
nlohmann::json parseJson(const std::string& text, const std::string& where,
                         const JsonLimits& limits = {});

/** The file at `path`: a regular file (not a link, FIFO or folder) within `limits`, parsed.
 *  Throws mrloc::Error naming the file. */
nlohmann::json readJsonFile(const std::string& path, const JsonLimits& limits = {});

/** What a key of a file must hold, when it is there. */
enum class JsonType { Object, Array, String, Number, Boolean };

struct JsonField {
    std::string pointer;  ///< RFC 6901: "/robots", "/headline/figures"
    JsonType type;
};

/** Throws mrloc::Error "<where>: <pointer> is <a type>, expected <type>" for the first field
 *  present with another type (the root must be an object). The readers then use the fields
 *  without type errors. */
void checkJsonShape(const nlohmann::json& j, const std::vector<JsonField>& shape,
                    const std::string& where);

}  // namespace mrloc::common
