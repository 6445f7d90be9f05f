#include "scene/json_reader.hpp"

#include <algorithm>
#include <cmath>

namespace vkrt::json {

std::string Node::format_number() const {
    const Document::Value& v = value();
    if (v.kind == Kind::Unsigned) return fmt::format("{}", v.unsigned_integer);
    if (v.kind == Kind::Integer) return fmt::format("{}", v.integer);
    return fmt::format("{}", v.number);
}

std::string Node::describe() const {
    const Document::Value& v = value();
    switch (v.kind) {
        case Kind::Null: return "null";
        case Kind::Boolean: return fmt::format("a boolean ({})", v.boolean);
        case Kind::Integer:
        case Kind::Unsigned:
        case Kind::Float: return fmt::format("a number ({})", format_number());
        case Kind::String: return fmt::format("a string ({})", quote_user(doc_->text(v)));
        case Kind::Array:
            return v.count == 1 ? std::string("an array of 1 element") : fmt::format("an array of {} elements", v.count);
        case Kind::Object: return "an object";
    }
    return "an unexpected value";
}

// ---- Node: objects -----------------------------------------------------------

void Node::allow_only(std::initializer_list<std::string_view> keys) const {
    allow_only(std::span<const std::string_view>(keys.begin(), keys.size()));
}

void Node::allow_only(std::span<const std::string_view> keys) const {
    expect_object();
    for (Document::Index i = doc_->first_child(index_); i < value().end; i = doc_->next_sibling(i)) {
        const std::string_view key = doc_->key(doc_->at(i));
        if (std::find(keys.begin(), keys.end(), key) != keys.end()) continue;
        std::string list;
        for (std::string_view k : keys) list += (list.empty() ? "" : ", ") + std::string(k);
        fail(fmt::format("unknown field {} (expected one of: {})", quote_user(key), list));
    }
}

std::optional<Node> Node::find(std::string_view key) const {
    expect_object();
    for (Document::Index i = doc_->first_child(index_); i < value().end; i = doc_->next_sibling(i)) {
        if (doc_->key(doc_->at(i)) == key) return child(i);
    }
    return std::nullopt;
}

Node Node::required(std::string_view key) const {
    if (auto node = find(key)) return *node;
    fail_field(key, "required field is missing");
}

std::vector<std::pair<std::string, Node>> Node::members() const {
    expect_object();
    std::vector<std::pair<std::string, Node>> out;
    out.reserve(value().count);
    for (Document::Index i = doc_->first_child(index_); i < value().end; i = doc_->next_sibling(i)) {
        out.emplace_back(std::string(doc_->key(doc_->at(i))), child(i));
    }
    return out;
}

// ---- Node: arrays ------------------------------------------------------------

std::vector<Node> Node::elements() const {
    if (kind() != Kind::Array) fail_expected("an array");
    std::vector<Node> out;
    out.reserve(value().count);
    for (Document::Index i = doc_->first_child(index_); i < value().end; i = doc_->next_sibling(i)) {
        out.push_back(child(i));
    }
    return out;
}

std::vector<Node> Node::elements(std::size_t n, std::string_view expected) const {
    if (kind() != Kind::Array || value().count != n) fail_expected(expected);
    return elements();
}

// ---- Node: scalars -----------------------------------------------------------

double Node::number() const {
    const Document::Value& v = value();
    double d = 0.0;
    switch (v.kind) {
        case Kind::Integer: d = static_cast<double>(v.integer); break;
        case Kind::Unsigned: d = static_cast<double>(v.unsigned_integer); break;
        case Kind::Float: d = v.number; break;
        default: fail_expected("a number");
    }
    if (!std::isfinite(d)) fail(fmt::format("expected a finite number, got {}", d));
    if (std::abs(d) > kMaxMagnitude) {
        fail(fmt::format("expected a number of magnitude at most {}, got {}", kMaxMagnitude, format_number()));
    }
    return d;
}

double Node::number_at_least(double lo) const {
    const double v = number();
    if (!(v >= lo)) fail(fmt::format("expected a number >= {}, got {}", lo, format_number()));
    return v;
}

double Node::number_above(double lo) const {
    const double v = number();
    if (!(v > lo)) fail(fmt::format("expected a number > {}, got {}", lo, format_number()));
    return v;
}

double Node::number_between(double lo, double hi) const {
    const double v = number();
    if (!(v >= lo && v <= hi)) fail(fmt::format("expected a number between {} and {}, got {}", lo, hi, format_number()));
    return v;
}

double Node::number_between_exclusive(double lo, double hi) const {
    const double v = number();
    if (!(v > lo && v < hi)) {
        fail(fmt::format("expected a number strictly between {} and {}, got {}", lo, hi, format_number()));
    }
    return v;
}

std::uint64_t Node::whole(std::uint64_t lo, std::uint64_t hi) const {
    if (!is_number()) fail_expected("a whole number");
    const auto out_of_range = [&] {
        fail(fmt::format("expected a whole number in [{}, {}], got {}", lo, hi, format_number()));
    };
    const Document::Value& v = value();
    if (v.kind == Kind::Unsigned) {
        if (v.unsigned_integer < lo || v.unsigned_integer > hi) out_of_range();
        return v.unsigned_integer;
    }
    if (v.kind == Kind::Integer) {
        const auto u = static_cast<std::uint64_t>(v.integer);
        if (v.integer < 0 || u < lo || u > hi) out_of_range();
        return u;
    }
    const double d = v.number;
    if (!std::isfinite(d)) fail(fmt::format("expected a finite number, got {}", d));
    if (std::floor(d) != d) fail(fmt::format("expected a whole number, got {}", format_number()));
    if (d < static_cast<double>(lo) || d > static_cast<double>(hi)) out_of_range();
    return static_cast<std::uint64_t>(d);
}

bool Node::boolean() const {
    if (kind() != Kind::Boolean) fail_expected("true or false");
    return value().boolean;
}

std::string Node::string() const {
    if (!is_string()) fail_expected("a string");
    return std::string(doc_->text(value()));
}

template <typename Read>
glm::dvec3 Node::triple(Read read) const {
    if (kind() != Kind::Array || value().count != 3) fail_expected("an array of 3 numbers");
    glm::dvec3 out;
    Document::Index i = doc_->first_child(index_);
    for (int a = 0; a < 3; ++a, i = doc_->next_sibling(i)) out[a] = read(child(i));
    return out;
}

glm::dvec3 Node::vec3() const {
    return triple([](const Node& n) { return n.number(); });
}

std::filesystem::path Node::file_path() const {
    const std::string name = string();
    if (name.empty()) fail("expected a file name, got an empty string");
    return std::filesystem::path(file()).parent_path() / name;
}

glm::dvec3 Node::color() const {
    return triple([](const Node& n) { return n.number_at_least(0.0); });
}

glm::dvec3 Node::unit_color() const {
    return triple([](const Node& n) { return n.number_between(0.0, 1.0); });
}

}  // namespace vkrt::json
