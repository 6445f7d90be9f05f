#pragma once
// A typed, path-aware view of a parsed JSON document, used by the scene loader.
//
// Every value handed out carries its JSON path ("objects[3].radius"), so that any
// complaint about it can name the file, the path, what was expected and what was
// found (DESIGN.md principle 5) without the loader repeating that bookkeeping at
// each field. Header-only because the loader is its only user.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <set>
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
inline std::string quote_user(std::string_view s) {
    constexpr std::size_t kMaxShown = 60;
    std::string text(s.substr(0, kMaxShown));
    // dump() escapes control characters; `replace` tolerates a UTF-8 sequence
    // that the shortening above cut in half.
    std::string escaped = Json(text).dump(-1, ' ', false, Json::error_handler_t::replace);
    escaped = escaped.substr(1, escaped.size() - 2);
    return fmt::format("'{}{}'", escaped, s.size() > kMaxShown ? "..." : "");
}

// "materials.red" for plain keys; "materials[\"my glass\"]" when the key would
// make the path ambiguous to read.
inline std::string path_join(std::string_view parent, std::string_view key) {
    const bool plain = !key.empty() && std::all_of(key.begin(), key.end(), [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
               c == '_' || c == '-';
    });
    if (plain) {
        return parent.empty() ? std::string(key) : fmt::format("{}.{}", parent, key);
    }
    return fmt::format("{}[{}]", parent,
                       Json(std::string(key)).dump(-1, ' ', false, Json::error_handler_t::replace));
}

inline std::string path_index(std::string_view parent, std::size_t index) {
    return fmt::format("{}[{}]", parent, index);
}

inline std::string format_number(const Json& j) {
    if (j.is_number_unsigned()) return fmt::format("{}", j.get<std::uint64_t>());
    if (j.is_number_integer()) return fmt::format("{}", j.get<std::int64_t>());
    return fmt::format("{}", j.get<double>());
}

// What a value is, for "expected X, got <this>".
inline std::string describe(const Json& j) {
    switch (j.type()) {
        case Json::value_t::null: return "null";
        case Json::value_t::boolean: return fmt::format("a boolean ({})", j.get<bool>());
        case Json::value_t::number_integer:
        case Json::value_t::number_unsigned:
        case Json::value_t::number_float: return fmt::format("a number ({})", format_number(j));
        case Json::value_t::string: return fmt::format("a string ({})", quote_user(j.get_ref<const std::string&>()));
        case Json::value_t::array:
            return j.size() == 1 ? std::string("an array of 1 element")
                                 : fmt::format("an array of {} elements", j.size());
        case Json::value_t::object: return "an object";
        default: return "an unexpected value";
    }
}

inline std::string format_vec3(const glm::dvec3& v) {
    return fmt::format("[{}, {}, {}]", v.x, v.y, v.z);
}

[[noreturn]] inline void fail_at(const std::string& file, std::string_view path, std::string_view message) {
    if (path.empty()) throw SceneError(fmt::format("{}: {}", file, message));
    throw SceneError(fmt::format("{}: {}: {}", file, path, message));
}

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
    void allow_only(std::initializer_list<std::string_view> keys) const {
        expect_object();
        for (const auto& item : value_->items()) {
            if (std::find(keys.begin(), keys.end(), item.key()) != keys.end()) continue;
            std::string list;
            for (std::string_view k : keys) list += (list.empty() ? "" : ", ") + std::string(k);
            fail(fmt::format("unknown field {} (expected one of: {})", quote_user(item.key()), list));
        }
    }

    std::optional<Node> find(std::string_view key) const {
        expect_object();
        const auto it = value_->find(key);
        if (it == value_->end()) return std::nullopt;
        return Node(*file_, *it, path_join(path_, key));
    }

    Node required(std::string_view key) const {
        if (auto node = find(key)) return *node;
        fail_field(key, "required field is missing");
    }

    // The members of an object, in file order.
    std::vector<std::pair<std::string, Node>> members() const {
        expect_object();
        std::vector<std::pair<std::string, Node>> out;
        for (const auto& item : value_->items()) {
            out.emplace_back(item.key(), Node(*file_, item.value(), path_join(path_, item.key())));
        }
        return out;
    }

    // ---- arrays --------------------------------------------------------------
    std::vector<Node> elements() const {
        if (!value_->is_array()) fail_expected("an array");
        return collect();
    }

    // An array of exactly n elements; `expected` reads like "an array of 3 numbers".
    std::vector<Node> elements(std::size_t n, std::string_view expected) const {
        if (!value_->is_array() || value_->size() != n) fail_expected(expected);
        return collect();
    }

    // ---- scalars -------------------------------------------------------------
    double number() const {
        if (!value_->is_number()) fail_expected("a number");
        const double v = value_->get<double>();
        if (!std::isfinite(v)) fail(fmt::format("expected a finite number, got {}", v));
        if (std::abs(v) > kMaxMagnitude) {
            fail(fmt::format("expected a number of magnitude at most {}, got {}", kMaxMagnitude,
                             format_number(*value_)));
        }
        return v;
    }

    double number_at_least(double lo) const {
        const double v = number();
        if (!(v >= lo)) fail(fmt::format("expected a number >= {}, got {}", lo, format_number(*value_)));
        return v;
    }

    double number_above(double lo) const {
        const double v = number();
        if (!(v > lo)) fail(fmt::format("expected a number > {}, got {}", lo, format_number(*value_)));
        return v;
    }

    double number_between_exclusive(double lo, double hi) const {
        const double v = number();
        if (!(v > lo && v < hi)) {
            fail(fmt::format("expected a number strictly between {} and {}, got {}", lo, hi,
                             format_number(*value_)));
        }
        return v;
    }

    // A whole number in [lo, hi]. 400.0 counts as whole; 2.5 does not.
    std::uint64_t whole(std::uint64_t lo, std::uint64_t hi) const {
        if (!value_->is_number()) fail_expected("a whole number");
        const std::string range = fmt::format("expected a whole number in [{}, {}], got {}", lo, hi,
                                              format_number(*value_));
        if (value_->is_number_unsigned()) {
            const auto v = value_->get<std::uint64_t>();
            if (v < lo || v > hi) fail(range);
            return v;
        }
        if (value_->is_number_integer()) {
            const auto v = value_->get<std::int64_t>();
            if (v < 0 || static_cast<std::uint64_t>(v) < lo || static_cast<std::uint64_t>(v) > hi) fail(range);
            return static_cast<std::uint64_t>(v);
        }
        const double v = value_->get<double>();
        if (!std::isfinite(v)) fail(fmt::format("expected a finite number, got {}", v));
        if (std::floor(v) != v) fail(fmt::format("expected a whole number, got {}", format_number(*value_)));
        if (v < static_cast<double>(lo) || v > static_cast<double>(hi)) fail(range);
        return static_cast<std::uint64_t>(v);
    }

    bool boolean() const {
        if (!value_->is_boolean()) fail_expected("true or false");
        return value_->get<bool>();
    }

    std::string string() const {
        if (!value_->is_string()) fail_expected("a string");
        return value_->get<std::string>();
    }

    glm::dvec3 vec3() const {
        const auto e = elements(3, "an array of 3 numbers");
        return {e[0].number(), e[1].number(), e[2].number()};
    }

    // A colour or any other non-negative triple.
    glm::dvec3 color() const {
        const auto e = elements(3, "an array of 3 numbers");
        return {e[0].number_at_least(0.0), e[1].number_at_least(0.0), e[2].number_at_least(0.0)};
    }

private:
    std::vector<Node> collect() const {
        std::vector<Node> out;
        out.reserve(value_->size());
        for (std::size_t i = 0; i < value_->size(); ++i) {
            out.emplace_back(*file_, (*value_)[i], path_index(path_, i));
        }
        return out;
    }

    const std::string* file_;
    const Json* value_;
    std::string path_;
};

// Follows the parser's events so that problems the DOM cannot show afterwards
// (a key given twice, where the last one would silently win; a number too large
// for a double, which nlohmann reports without a position) can still be named by
// their JSON path.
class PathTracker {
public:
    explicit PathTracker(const std::string& file) : file_(file) {}

    // The path of the value the parser is about to produce.
    std::string pending_path() const {
        if (frames_.empty()) return {};
        const Frame& top = frames_.back();
        return top.is_object ? path_join(top.path, top.key) : path_index(top.path, top.next_index);
    }

    void on_event(int depth, Json::parse_event_t event, const Json& parsed) {
        using E = Json::parse_event_t;
        switch (event) {
            case E::object_start:
            case E::array_start: {
                std::string path = pending_path();
                if (depth > kMaxNesting) {
                    // The path itself is as deep as the nesting: show its start.
                    const std::string shown = path.size() > 80 ? path.substr(0, 80) + "..." : path;
                    fail_at(file_, shown, fmt::format("nesting is deeper than {} levels", kMaxNesting));
                }
                advance();
                frames_.push_back(Frame{event == E::object_start, std::move(path), {}, 0, {}});
                break;
            }
            case E::key: {
                Frame& top = frames_.back();
                top.key = parsed.get<std::string>();
                if (!top.keys.insert(top.key).second) {
                    fail_at(file_, top.path, fmt::format("field {} is given more than once", quote_user(top.key)));
                }
                break;
            }
            case E::value: advance(); break;
            case E::object_end:
            case E::array_end: frames_.pop_back(); break;
        }
    }

private:
    struct Frame {
        bool is_object;
        std::string path;
        std::string key;             // objects: the key whose value comes next
        std::size_t next_index = 0;  // arrays: the index of the next element
        std::set<std::string, std::less<>> keys;
    };

    void advance() {
        if (!frames_.empty() && !frames_.back().is_object) ++frames_.back().next_index;
    }

    const std::string& file_;
    std::vector<Frame> frames_;
};

// nlohmann reports the 1-based count of bytes read; turn it into the line and
// column (in characters, not UTF-8 bytes) that an editor shows.
inline std::pair<std::size_t, std::size_t> line_column(std::string_view text, std::size_t bytes_read) {
    const std::size_t at = std::min(bytes_read == 0 ? 0 : bytes_read - 1, text.size());
    std::size_t line = 1;
    std::size_t line_start = 0;
    for (std::size_t i = 0; i < at; ++i) {
        if (text[i] == '\n') {
            ++line;
            line_start = i + 1;
        }
    }
    std::size_t column = 1;
    for (std::size_t i = line_start; i < at; ++i) {
        if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) ++column;  // skip continuation bytes
    }
    return {line, column};
}

// nlohmann's messages carry an exception id, a position (which we give ourselves)
// and an echo of the input that may span lines; keep only the reason.
inline std::string short_parse_reason(std::string message) {
    if (const auto pos = message.find("parse error"); pos != std::string::npos) {
        if (const auto colon = message.find(": ", pos); colon != std::string::npos) {
            message.erase(0, colon + 2);
        }
    }
    constexpr std::string_view kWhile = "syntax error while parsing ";
    if (message.rfind(kWhile, 0) == 0) {
        if (const auto dash = message.find(" - "); dash != std::string::npos) message.erase(0, dash + 3);
    }
    constexpr std::string_view kLastRead = "; last read: '";
    if (const auto lr = message.find(kLastRead); lr != std::string::npos) {
        const auto next = message.find("'; ", lr + kLastRead.size());
        message.erase(lr, next == std::string::npos ? std::string::npos : next + 1 - lr);
    }
    return message;
}

// Parses JSON text with // and /* */ comments allowed. Throws SceneError with
// "<file>:<line>:<col>: invalid JSON: <reason>" or a path-named message.
inline Json parse_document(const std::string& file, const std::string& text) {
    PathTracker tracker(file);
    const Json::parser_callback_t callback = [&tracker](int depth, Json::parse_event_t event, Json& parsed) {
        tracker.on_event(depth, event, parsed);
        return true;
    };
    try {
        return Json::parse(text, callback, /*allow_exceptions=*/true, /*ignore_comments=*/true);
    } catch (const Json::parse_error& e) {
        const auto [line, column] = line_column(text, e.byte);
        throw SceneError(fmt::format("{}:{}:{}: invalid JSON: {}", file, line, column, short_parse_reason(e.what())));
    } catch (const Json::out_of_range& e) {
        // id 406: a literal such as 1e999 overflows a double. The parser reports
        // it before producing the value, so the tracker points at that value.
        if (e.id == 406) {
            std::string token = e.what();
            const auto open = token.find('\'');
            const auto close = token.rfind('\'');
            token = (open != std::string::npos && close > open) ? token.substr(open + 1, close - open - 1) : "?";
            if (token.size() > 40) token = token.substr(0, 37) + "...";
            fail_at(file, tracker.pending_path(),
                    fmt::format("expected a finite number, got {} (too large for a double)", token));
        }
        throw SceneError(fmt::format("{}: invalid JSON: {}", file, e.what()));
    } catch (const Json::exception& e) {
        throw SceneError(fmt::format("{}: invalid JSON: {}", file, e.what()));
    }
}

}  // namespace vkrt::json
