#pragma once
// A typed, path-aware view of a parsed JSON document, used by the scene loader.
//
// Every value handed out carries its JSON path ("objects[3].radius"), so that any
// complaint about it can name the file, the path, what was expected and what was
// found (docs/architecture.md, principle 5) without the loader repeating that bookkeeping at
// each field. The definitions live in json_reader.cpp; only one-liners stay here.
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "scene/scene_error.hpp"

namespace vkrt::json {

// Ordered, so that materials keep the order of the file: their position is the
// material index that objects refer to, and a stable order makes that predictable.
using Json = nlohmann::ordered_json;

// Beyond this magnitude a coordinate, size or intensity is certainly a typo, and
// it would overflow once squared in the kernel's single-precision arithmetic
// (float tops out near 3.4e38), giving NaN pixels instead of an error.
inline constexpr double kMaxMagnitude = 1e12;

// No scene needs deep nesting; the cap keeps a hostile file from costing much.
inline constexpr int kMaxNesting = 64;

// A user-supplied string made safe for a one-line message: control characters
// escaped, long strings shortened, wrapped in single quotes.
std::string quote_user(std::string_view s);

// "materials.red" for plain keys; "materials[\"my glass\"]" when the key would
// make the path ambiguous to read.
std::string path_join(std::string_view parent, std::string_view key);

inline std::string path_index(std::string_view parent, std::size_t index) {
    return fmt::format("{}[{}]", parent, index);
}

std::string format_number(const Json& j);

// What a value is, for "expected X, got <this>".
std::string describe(const Json& j);

inline std::string format_vec3(const glm::dvec3& v) {
    return fmt::format("[{}, {}, {}]", v.x, v.y, v.z);
}

[[noreturn]] void fail_at(const std::string& file, std::string_view path, std::string_view message);

// One value of the document and where it sits. Cheap to copy: it refers to the
// document and the file name, which outlive it (both belong to the loader call).
class Node {
public:
    Node(const std::string& file, const Json& value, std::string path)
        : file_(&file), value_(&value), path_(std::move(path)) {}

    const std::string& path() const { return path_; }
    const std::string& file() const { return *file_; }
    const Json& raw() const { return *value_; }

    [[noreturn]] void fail(std::string_view message) const { fail_at(*file_, path_, message); }
    // For a field that may be absent (a default that turned out to be unusable).
    [[noreturn]] void fail_field(std::string_view key, std::string_view message) const {
        fail_at(*file_, path_join(path_, key), message);
    }
    [[noreturn]] void fail_expected(std::string_view expected) const {
        fail(fmt::format("expected {}, got {}", expected, describe(*value_)));
    }

    // ---- objects -------------------------------------------------------------
    void expect_object() const {
        if (!value_->is_object()) fail_expected("an object");
    }

    // Rejects any key not listed: a misspelt optional field would otherwise be
    // ignored and its default used without a word.
    void allow_only(std::initializer_list<std::string_view> keys) const;

    std::optional<Node> find(std::string_view key) const;

    Node required(std::string_view key) const;

    // The members of an object, in file order.
    std::vector<std::pair<std::string, Node>> members() const;

    // ---- arrays --------------------------------------------------------------
    std::vector<Node> elements() const;

    // An array of exactly n elements; `expected` reads like "an array of 3 numbers".
    std::vector<Node> elements(std::size_t n, std::string_view expected) const;

    // ---- scalars -------------------------------------------------------------
    double number() const;
    double number_at_least(double lo) const;
    double number_above(double lo) const;
    double number_between_exclusive(double lo, double hi) const;

    // A whole number in [lo, hi]. 400.0 counts as whole; 2.5 does not.
    std::uint64_t whole(std::uint64_t lo, std::uint64_t hi) const;

    bool boolean() const;
    std::string string() const;
    glm::dvec3 vec3() const;

    // A colour or any other non-negative triple.
    glm::dvec3 color() const;

private:
    std::vector<Node> collect() const;

    const std::string* file_;
    const Json* value_;
    std::string path_;
};

// nlohmann reports the 1-based count of bytes read; turn it into the line and
// column (in characters, not UTF-8 bytes) that an editor shows.
std::pair<std::size_t, std::size_t> line_column(std::string_view text, std::size_t bytes_read);

// nlohmann's messages carry an exception id, a position (which we give ourselves)
// and an echo of the input that may span lines; keep only the reason.
std::string short_parse_reason(std::string message);

// Parses JSON text with // and /* */ comments allowed. Throws SceneError with
// "<file>:<line>:<col>: invalid JSON: <reason>", or a message naming the JSON path
// of what the document cannot show afterwards: a key given twice (where the last
// would silently win), a number too large for a double, nesting deeper than
// kMaxNesting.
Json parse_document(const std::string& file, const std::string& text);

}  // namespace vkrt::json
