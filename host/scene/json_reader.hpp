#pragma once
// A typed, path-aware view of a parsed JSON document, used by the scene loader.
//
// Every value handed out knows its JSON path ("objects[3].radius"), so that any
// complaint about it can name the file, the path, what was expected and what was
// found (docs/architecture.md, principle 5) without the loader repeating that bookkeeping at
// each field. The definitions live in json_reader.cpp; only one-liners stay here.
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <glm/vec3.hpp>

#include "scene/json_document.hpp"
#include "scene/scene_error.hpp"

namespace vkrt::json {

// Beyond this magnitude a coordinate, size or intensity is certainly a typo, and
// it would overflow once squared in the kernel's single-precision arithmetic
// (float tops out near 3.4e38), giving NaN pixels instead of an error.
inline constexpr double kMaxMagnitude = 1e12;

inline std::string format_vec3(const glm::dvec3& v) {
    return fmt::format("[{}, {}, {}]", v.x, v.y, v.z);
}

// One value of the document and where it sits. Cheap to copy: it refers to the
// document and the file name, which outlive it (both belong to the loader call).
class Node {
public:
    Node(const std::string& file, const Document& doc, Document::Index index = 0)
        : file_(&file), doc_(&doc), index_(index) {}

    // Built on demand: a path per value would cost more than the parse.
    std::string path() const { return doc_->path(index_); }
    const std::string& file() const { return *file_; }

    Kind kind() const { return value().kind; }
    bool is_number() const { return kind() == Kind::Integer || kind() == Kind::Unsigned || kind() == Kind::Float; }
    bool is_string() const { return kind() == Kind::String; }
    bool is_object() const { return kind() == Kind::Object; }

    [[noreturn]] void fail(std::string_view message) const { fail_at(*file_, path(), message); }
    // For a field that may be absent (a default that turned out to be unusable).
    [[noreturn]] void fail_field(std::string_view key, std::string_view message) const {
        fail_at(*file_, path_join(path(), key), message);
    }
    [[noreturn]] void fail_expected(std::string_view expected) const {
        fail(fmt::format("expected {}, got {}", expected, describe()));
    }

    // What the value is, for "expected X, got <this>".
    std::string describe() const;

    // ---- objects -------------------------------------------------------------
    void expect_object() const {
        if (!is_object()) fail_expected("an object");
    }

    // Rejects any key not listed: a misspelt optional field would otherwise be
    // ignored and its default used without a word.
    void allow_only(std::initializer_list<std::string_view> keys) const;
    void allow_only(std::span<const std::string_view> keys) const;

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
    double number_between(double lo, double hi) const;  // inclusive
    double number_between_exclusive(double lo, double hi) const;

    // A whole number in [lo, hi]. 400.0 counts as whole; 2.5 does not.
    std::uint64_t whole(std::uint64_t lo, std::uint64_t hi) const;

    bool boolean() const;
    std::string string() const;
    // A non-empty string naming a file, relative to the scene file's directory
    // (an absolute name stands as it is).
    std::filesystem::path file_path() const;
    glm::dvec3 vec3() const;

    // A colour or any other non-negative triple.
    glm::dvec3 color() const;
    glm::dvec3 unit_color() const;  // each component in [0, 1]

private:
    const Document::Value& value() const { return doc_->at(index_); }
    Node child(Document::Index i) const { return Node(*file_, *doc_, i); }
    std::string format_number() const;
    // Three numbers, each read and checked by `read(Node)`.
    template <typename Read>
    glm::dvec3 triple(Read read) const;

    const std::string* file_;
    const Document* doc_;
    Document::Index index_;
};

}  // namespace vkrt::json
