#include "scene/json_document.hpp"

#include <algorithm>
#include <memory>
#include <unordered_set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "scene/scene_error.hpp"

namespace vkrt::json {

using Sax = nlohmann::json;

// ---- names for messages ------------------------------------------------------

std::string quote_user(std::string_view s) {
    constexpr std::size_t kMaxShown = 60;
    std::string text(s.substr(0, kMaxShown));
    // dump() escapes control characters; `replace` tolerates a UTF-8 sequence
    // that the shortening above cut in half.
    std::string escaped = Sax(text).dump(-1, ' ', false, Sax::error_handler_t::replace);
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
                       Sax(std::string(key)).dump(-1, ' ', false, Sax::error_handler_t::replace));
}

std::string path_index(std::string_view parent, std::size_t index) { return fmt::format("{}[{}]", parent, index); }

void fail_at(const std::string& file, std::string_view path, std::string_view message) {
    if (path.empty()) throw SceneError(fmt::format("{}: {}", file, message));
    throw SceneError(fmt::format("{}: {}: {}", file, path, message));
}

std::string Document::path(Index i) const {
    std::vector<Index> chain;
    for (Index at = i; values_[at].parent != kNoParent; at = values_[at].parent) chain.push_back(at);
    std::string p;
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
        const Value& v = values_[*it];
        p = in_object(v) ? path_join(p, key(v)) : path_index(p, v.key_offset);
    }
    return p;
}

// ---- building ----------------------------------------------------------------

// Appends the parser's events (nlohmann's SAX interface) to a Document. Checks
// what the document cannot show afterwards, naming the value by its path.
// (nlohmann's callback parser would give the events too, but rescans the parent
// array at every object's end: quadratic in the length of "objects".)
class DocumentBuilder {
public:
    using Index = Document::Index;

    DocumentBuilder(const std::string& file, std::string_view text) : file_(file), text_(text) {
        // Every value takes at least two characters ("0,"), so up to the cap this
        // never grows: growing by doubling would copy and touch twice the memory.
        // Pages reserved but not reached are never touched.
        constexpr std::size_t kMaxReserved = std::size_t(1) << 24;  // 512 MiB of address space
        doc_.values_.reserve(std::min(text.size() / 2 + 1, kMaxReserved));
        doc_.strings_.reserve(text.size());
    }

    Document take() { return std::move(doc_); }

    bool null() { return add(Kind::Null); }
    bool boolean(bool v) {
        value(add_value(Kind::Boolean)).boolean = v;
        return true;
    }
    bool number_integer(Sax::number_integer_t v) {
        value(add_value(Kind::Integer)).integer = v;
        return true;
    }
    bool number_unsigned(Sax::number_unsigned_t v) {
        value(add_value(Kind::Unsigned)).unsigned_integer = v;
        return true;
    }
    bool number_float(Sax::number_float_t v, const std::string&) {
        value(add_value(Kind::Float)).number = v;
        return true;
    }
    bool string(Sax::string_t& s) {
        const auto [offset, size] = store(s);
        auto& text = value(add_value(Kind::String)).text;
        text.offset = offset;
        text.size = size;
        return true;
    }
    bool binary(Sax::binary_t&) { return add(Kind::Null); }  // never produced by the JSON parser

    bool start_object(std::size_t) { return open(Kind::Object); }
    bool start_array(std::size_t) { return open(Kind::Array); }
    bool end_object() { return close(); }
    bool end_array() { return close(); }

    bool key(Sax::string_t& k) {
        Frame& top = frames_.back();
        if (given_before(top, k)) {
            fail_at(file_, doc_.path(top.container), fmt::format("field {} is given more than once", quote_user(k)));
        }
        std::tie(key_offset_, key_size_) = store(k);
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
    // An open object or array. Large objects look their keys up in a set; small
    // ones compare against their few members.
    struct Frame {
        Index container;
        std::unique_ptr<std::unordered_set<std::string>> keys;
    };
    static constexpr Index kKeysInSet = 16;

    Document::Value& value(Index i) { return doc_.values_[i]; }

    std::pair<Index, Index> store(const std::string& s) {
        if (doc_.strings_.size() + s.size() >= Document::kNoParent) fail_at(file_, "", "document too large (over 4 GiB of text)");
        const auto offset = static_cast<Index>(doc_.strings_.size());
        doc_.strings_ += s;
        return {offset, static_cast<Index>(s.size())};
    }

    bool given_before(Frame& top, const std::string& k) {
        const Document::Value& object = value(top.container);
        if (top.keys) return !top.keys->insert(k).second;
        for (Index i = doc_.first_child(top.container); i < doc_.values_.size(); i = doc_.next_sibling(i)) {
            if (doc_.key(value(i)) == k) return true;
        }
        if (object.count + 1 >= kKeysInSet) {
            top.keys = std::make_unique<std::unordered_set<std::string>>();
            for (Index i = doc_.first_child(top.container); i < doc_.values_.size(); i = doc_.next_sibling(i)) {
                top.keys->emplace(doc_.key(value(i)));
            }
            top.keys->insert(k);
        }
        return false;
    }

    // Appends a value where the parser is and returns its index.
    Index add_value(Kind kind) {
        if (doc_.values_.size() >= Document::kNoParent - 1) fail_at(file_, "", "document too large (over 4 billion values)");
        const auto i = static_cast<Index>(doc_.values_.size());
        Document::Value v;
        v.kind = kind;
        v.end = i + 1;
        if (!frames_.empty()) {
            const Index parent = frames_.back().container;
            Document::Value& p = value(parent);
            v.parent = parent;
            if (p.kind == Kind::Object) {
                v.key_offset = key_offset_;
                v.key_size = key_size_;
            } else {
                v.key_offset = p.count;
            }
            ++p.count;
        }
        doc_.values_.push_back(v);
        return i;
    }
    bool add(Kind kind) {
        add_value(kind);
        return true;
    }
    bool open(Kind kind) {
        if (frames_.size() >= std::size_t(kMaxNesting)) {
            // The path itself is as deep as the nesting: show its start.
            const std::string p = pending_path();
            fail_at(file_, p.size() > 80 ? p.substr(0, 80) + "..." : p,
                    fmt::format("nesting is deeper than {} levels", kMaxNesting));
        }
        frames_.push_back(Frame{add_value(kind), nullptr});
        return true;
    }
    bool close() {
        value(frames_.back().container).end = static_cast<Index>(doc_.values_.size());
        frames_.pop_back();
        return true;
    }

    // The path of the value about to be read.
    std::string pending_path() const {
        if (frames_.empty()) return {};
        const Index top = frames_.back().container;
        const Document::Value& parent = doc_.values_[top];
        const std::string at = doc_.path(top);
        return parent.kind == Kind::Object ? path_join(at, doc_.view(key_offset_, key_size_)) : path_index(at, parent.count);
    }

    const std::string& file_;
    std::string_view text_;
    Document doc_;
    std::vector<Frame> frames_;
    Index key_offset_ = 0;
    Index key_size_ = 0;
};

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

Document parse_document(const std::string& file, const std::string& text) {
    DocumentBuilder builder(file, text);
    try {
        Sax::sax_parse(text, &builder, nlohmann::detail::input_format_t::json, /*strict=*/true,
                       /*ignore_comments=*/true);
    } catch (const Sax::exception& e) {
        throw SceneError(fmt::format("{}: invalid JSON: {}", file, e.what()));
    }
    return builder.take();
}

}  // namespace vkrt::json
