#include "scene/json_reader.hpp"

#include <algorithm>
#include <cmath>

namespace vkrt::json {

std::string quote_user(std::string_view s) {
    constexpr std::size_t kMaxShown = 60;
    std::string text(s.substr(0, kMaxShown));
    // dump() escapes control characters; `replace` tolerates a UTF-8 sequence
    // that the shortening above cut in half.
    std::string escaped = Json(text).dump(-1, ' ', false, Json::error_handler_t::replace);
    escaped = escaped.substr(1, escaped.size() - 2);
    return fmt::format("'{}{}'", escaped, s.size() > kMaxShown ? "..." : "");
}

std::string path_join(std::string_view parent, std::string_view key) {
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

std::string format_number(const Json& j) {
    if (j.is_number_unsigned()) return fmt::format("{}", j.get<std::uint64_t>());
    if (j.is_number_integer()) return fmt::format("{}", j.get<std::int64_t>());
    return fmt::format("{}", j.get<double>());
}

std::string describe(const Json& j) {
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

void fail_at(const std::string& file, std::string_view path, std::string_view message) {
    if (path.empty()) throw SceneError(fmt::format("{}: {}", file, message));
    throw SceneError(fmt::format("{}: {}: {}", file, path, message));
}

// ---- Node: objects -----------------------------------------------------------

void Node::allow_only(std::initializer_list<std::string_view> keys) const {
    expect_object();
    for (const auto& item : value_->items()) {
        if (std::find(keys.begin(), keys.end(), item.key()) != keys.end()) continue;
        std::string list;
        for (std::string_view k : keys) list += (list.empty() ? "" : ", ") + std::string(k);
        fail(fmt::format("unknown field {} (expected one of: {})", quote_user(item.key()), list));
    }
}

std::optional<Node> Node::find(std::string_view key) const {
    expect_object();
    const auto it = value_->find(key);
    if (it == value_->end()) return std::nullopt;
    return Node(*file_, *it, path_join(path_, key));
}

Node Node::required(std::string_view key) const {
    if (auto node = find(key)) return *node;
    fail_field(key, "required field is missing");
}

std::vector<std::pair<std::string, Node>> Node::members() const {
    expect_object();
    std::vector<std::pair<std::string, Node>> out;
    for (const auto& item : value_->items()) {
        out.emplace_back(item.key(), Node(*file_, item.value(), path_join(path_, item.key())));
    }
    return out;
}

// ---- Node: arrays ------------------------------------------------------------

std::vector<Node> Node::elements() const {
    if (!value_->is_array()) fail_expected("an array");
    return collect();
}

std::vector<Node> Node::elements(std::size_t n, std::string_view expected) const {
    if (!value_->is_array() || value_->size() != n) fail_expected(expected);
    return collect();
}

std::vector<Node> Node::collect() const {
    std::vector<Node> out;
    out.reserve(value_->size());
    for (std::size_t i = 0; i < value_->size(); ++i) {
        out.emplace_back(*file_, (*value_)[i], path_index(path_, i));
    }
    return out;
}

// ---- Node: scalars -----------------------------------------------------------

double Node::number() const {
    if (!value_->is_number()) fail_expected("a number");
    const double v = value_->get<double>();
    if (!std::isfinite(v)) fail(fmt::format("expected a finite number, got {}", v));
    if (std::abs(v) > kMaxMagnitude) {
        fail(fmt::format("expected a number of magnitude at most {}, got {}", kMaxMagnitude,
                         format_number(*value_)));
    }
    return v;
}

double Node::number_at_least(double lo) const {
    const double v = number();
    if (!(v >= lo)) fail(fmt::format("expected a number >= {}, got {}", lo, format_number(*value_)));
    return v;
}

double Node::number_above(double lo) const {
    const double v = number();
    if (!(v > lo)) fail(fmt::format("expected a number > {}, got {}", lo, format_number(*value_)));
    return v;
}

double Node::number_between_exclusive(double lo, double hi) const {
    const double v = number();
    if (!(v > lo && v < hi)) {
        fail(fmt::format("expected a number strictly between {} and {}, got {}", lo, hi,
                         format_number(*value_)));
    }
    return v;
}

std::uint64_t Node::whole(std::uint64_t lo, std::uint64_t hi) const {
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

bool Node::boolean() const {
    if (!value_->is_boolean()) fail_expected("true or false");
    return value_->get<bool>();
}

std::string Node::string() const {
    if (!value_->is_string()) fail_expected("a string");
    return value_->get<std::string>();
}

glm::dvec3 Node::vec3() const {
    const auto e = elements(3, "an array of 3 numbers");
    return {e[0].number(), e[1].number(), e[2].number()};
}

glm::dvec3 Node::color() const {
    const auto e = elements(3, "an array of 3 numbers");
    return {e[0].number_at_least(0.0), e[1].number_at_least(0.0), e[2].number_at_least(0.0)};
}

// ---- DocumentBuilder ---------------------------------------------------------

namespace {

// Builds the document from the parser's events (nlohmann's SAX interface), and
// knows at each event the JSON path of the value being read, so that what the
// document cannot show afterwards is named by its path. Paths are built only for a
// message: building one per value cost more than the parse. (nlohmann's callback
// parser would give the events too, but rescans the parent array at every object's
// end: quadratic in the length of "objects".)
class DocumentBuilder {
public:
    DocumentBuilder(const std::string& file, std::string_view text) : file_(file), text_(text) {}

    Json take() { return std::move(root_); }

    bool null() { return add(Json(nullptr)); }
    bool boolean(bool v) { return add(Json(v)); }
    bool number_integer(Json::number_integer_t v) { return add(Json(v)); }
    bool number_unsigned(Json::number_unsigned_t v) { return add(Json(v)); }
    bool number_float(Json::number_float_t v, const std::string&) { return add(Json(v)); }
    bool string(Json::string_t& v) { return add(Json(std::move(v))); }
    bool binary(Json::binary_t& v) { return add(Json(std::move(v))); }

    bool start_object(std::size_t) { return open(Json::object()); }
    bool start_array(std::size_t) { return open(Json::array()); }
    bool end_object() { return close(); }
    bool end_array() { return close(); }

    bool key(Json::string_t& k) {
        Frame& top = frames_.back();
        if (top.value->contains(k)) {
            fail_at(file_, path(frames_.size() - 1), fmt::format("field {} is given more than once", quote_user(k)));
        }
        top.key = std::move(k);
        return true;
    }

    bool parse_error(std::size_t bytes_read, const std::string&, const nlohmann::detail::exception& e) {
        // id 406: a literal such as 1e999 overflows a double; it names the value.
        if (e.id == 406) {
            std::string token = e.what();
            const auto open = token.find('\'');
            const auto close = token.rfind('\'');
            token = (open != std::string::npos && close > open) ? token.substr(open + 1, close - open - 1) : "?";
            if (token.size() > 40) token = token.substr(0, 37) + "...";
            fail_at(file_, pending_path(), fmt::format("expected a finite number, got {} (too large for a double)", token));
        }
        const auto [line, column] = line_column(text_, bytes_read);
        throw SceneError(fmt::format("{}:{}:{}: invalid JSON: {}", file_, line, column, short_parse_reason(e.what())));
    }

private:
    // An open object or array, and how it was reached from its parent.
    struct Frame {
        Json* value;
        std::string key;             // objects: the key whose value comes next
        std::size_t next_index = 0;  // arrays: the index of the next element
    };

    // Puts a value where the parser is; the slot it returns stays valid while the
    // value's container is open, since nothing is added to that container meanwhile.
    Json* place(Json&& v) {
        if (frames_.empty()) {
            root_ = std::move(v);
            return &root_;
        }
        Frame& top = frames_.back();
        if (top.value->is_object()) return &top.value->emplace(top.key, std::move(v)).first.value();  // the key stays, for paths
        ++top.next_index;
        top.value->push_back(std::move(v));
        return &top.value->back();
    }
    bool add(Json&& v) {
        place(std::move(v));
        return true;
    }
    bool open(Json&& container) {
        if (frames_.size() >= std::size_t(kMaxNesting)) {
            // The path itself is as deep as the nesting: show its start.
            const std::string p = pending_path();
            fail_at(file_, p.size() > 80 ? p.substr(0, 80) + "..." : p,
                    fmt::format("nesting is deeper than {} levels", kMaxNesting));
        }
        frames_.push_back(Frame{place(std::move(container)), {}, 0});
        return true;
    }
    bool close() {
        frames_.pop_back();
        return true;
    }

    // The path of the container frames_[n], or of the value about to be read.
    std::string path(std::size_t n) const {
        std::string p;
        for (std::size_t i = 0; i < n; ++i) {
            const Frame& f = frames_[i];
            p = f.value->is_object() ? path_join(p, f.key) : path_index(p, f.next_index - 1);
        }
        return p;
    }
    std::string pending_path() const {
        if (frames_.empty()) return {};
        const Frame& top = frames_.back();
        const std::string parent = path(frames_.size() - 1);
        return top.value->is_object() ? path_join(parent, top.key) : path_index(parent, top.next_index);
    }

    const std::string& file_;
    std::string_view text_;
    Json root_;
    std::vector<Frame> frames_;
};

}  // namespace

// ---- parsing -----------------------------------------------------------------

std::pair<std::size_t, std::size_t> line_column(std::string_view text, std::size_t bytes_read) {
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

std::string short_parse_reason(std::string message) {
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

Json parse_document(const std::string& file, const std::string& text) {
    DocumentBuilder builder(file, text);
    try {
        Json::sax_parse(text, &builder, nlohmann::detail::input_format_t::json, /*strict=*/true,
                        /*ignore_comments=*/true);
    } catch (const Json::exception& e) {
        throw SceneError(fmt::format("{}: invalid JSON: {}", file, e.what()));
    }
    return builder.take();
}

}  // namespace vkrt::json
