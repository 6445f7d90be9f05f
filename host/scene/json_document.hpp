#pragma once
// A parsed JSON document as one flat array of values in document order (a "tape"),
// with every key and string in one buffer: a 100,000-object scene costs a handful of
// allocations instead of several per value, and a value's JSON path is recovered
// from its parents only when a message needs it (decision 0024).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace vkrt::json {

// No scene needs deep nesting; the cap keeps a hostile file from costing much.
inline constexpr int kMaxNesting = 64;

// A user-supplied string made safe for a one-line message: control characters
// escaped, long strings shortened, wrapped in single quotes.
std::string quote_user(std::string_view s);

// "materials.red" for plain keys; "materials[\"my glass\"]" when the key would
// make the path ambiguous to read.
std::string path_join(std::string_view parent, std::string_view key);

std::string path_index(std::string_view parent, std::size_t index);

// Throws SceneError "<file>: <path>: <message>" (without the path when it is empty).
[[noreturn]] void fail_at(const std::string& file, std::string_view path, std::string_view message);

enum class Kind : std::uint8_t { Null, Boolean, Integer, Unsigned, Float, String, Array, Object };

class Document {
public:
    using Index = std::uint32_t;
    static constexpr Index kNoParent = ~Index(0);

    // One value. A container's children follow it directly; `end` is one past the
    // last value inside it (for a scalar, its own index + 1), so siblings are
    // reached by jumping from one `end` to the next.
    struct Value {
        Kind kind = Kind::Null;
        Index parent = kNoParent;
        Index key_offset = 0;  // member of an object: the key in strings(); element of an array: its index
        Index key_size = 0;
        Index end = 0;
        Index count = 0;  // containers: number of children
        union {
            bool boolean;
            std::int64_t integer;
            std::uint64_t unsigned_integer;
            double number;
            struct {
                Index offset;
                Index size;
            } text;
        };
        Value() : number(0.0) {}
    };

    const Value& at(Index i) const { return values_[i]; }
    Index root() const { return 0; }
    std::size_t size() const { return values_.size(); }

    std::string_view text(const Value& v) const { return view(v.text.offset, v.text.size); }
    std::string_view key(const Value& v) const { return view(v.key_offset, v.key_size); }
    bool in_object(const Value& v) const { return v.parent != kNoParent && values_[v.parent].kind == Kind::Object; }

    // The first child of a container (or its end when empty), and the sibling after i.
    Index first_child(Index container) const { return container + 1; }
    Index next_sibling(Index i) const { return values_[i].end; }

    // "objects[3].center": the path of value i from the root, built on demand.
    std::string path(Index i) const;

private:
    friend class DocumentBuilder;
    std::string_view view(Index offset, Index size) const { return std::string_view(strings_).substr(offset, size); }

    std::vector<Value> values_;
    std::string strings_;
};

// Parses JSON text with // and /* */ comments allowed. Throws SceneError with
// "<file>:<line>:<col>: invalid JSON: <reason>", or a message naming the JSON path
// of what the document cannot show afterwards: a key given twice (where the last
// would silently win), a number too large for a double, nesting deeper than
// kMaxNesting.
Document parse_document(const std::string& file, const std::string& text);

// nlohmann reports the 1-based count of bytes read; turn it into the line and
// column (in characters, not UTF-8 bytes) that an editor shows.
std::pair<std::size_t, std::size_t> line_column(std::string_view text, std::size_t bytes_read);

// nlohmann's messages carry an exception id, a position (which we give ourselves)
// and an echo of the input that may span lines; keep only the reason.
std::string short_parse_reason(std::string message);

}  // namespace vkrt::json
