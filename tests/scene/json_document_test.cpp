// The parsed JSON document (host/scene/json_document.cpp): the tape of values in
// document order with parents, keys, ends and counts; paths built back from it;
// comments; the refusals the tape could not show afterwards (a key given twice, a
// number beyond a double, nesting too deep) and syntax errors at an editor's line
// and column; and the helpers that make user text safe for a one-line message.
#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "scene/json_document.hpp"
#include "scene/scene_error.hpp"

namespace {

using namespace vkrt::json;
using Index = Document::Index;

Document parse(const std::string& text) { return parse_document("t.json", text); }

// The message parsing `text` is refused with.
std::string refusal_of(const std::string& text) {
    try {
        parse(text);
    } catch (const vkrt::SceneError& e) {
        return e.what();
    }
    ADD_FAILURE() << text << " was accepted";
    return {};
}

TEST(JsonDocument, ValuesFollowInDocumentOrder) {
    const Document d = parse(R"({"a": 1, "b": [true, null, "x"], "c": {"d": -2, "e": 1.5}, "f": 18446744073709551615})");
    ASSERT_EQ(d.size(), 10u);
    // index:               0       1         2      3        4     5       6       7        8      9
    const std::vector<Kind> kinds{Kind::Object,  Kind::Unsigned, Kind::Array, Kind::Boolean, Kind::Null,
                                  Kind::String,  Kind::Object,   Kind::Integer, Kind::Float, Kind::Unsigned};
    const std::vector<Index> parents{Document::kNoParent, 0, 0, 2, 2, 2, 0, 6, 6, 0};
    const std::vector<Index> ends{10, 2, 6, 4, 5, 6, 9, 8, 9, 10};
    for (Index i = 0; i < d.size(); ++i) {
        SCOPED_TRACE(testing::Message() << "value " << i);
        EXPECT_EQ(d.at(i).kind, kinds[i]);
        EXPECT_EQ(d.at(i).parent, parents[i]);
        EXPECT_EQ(d.at(i).end, ends[i]);
    }
    EXPECT_EQ(d.at(0).count, 4u);
    EXPECT_EQ(d.at(2).count, 3u);
    EXPECT_EQ(d.at(6).count, 2u);

    EXPECT_EQ(d.at(1).unsigned_integer, 1u);
    EXPECT_TRUE(d.at(3).boolean);
    EXPECT_EQ(d.text(d.at(5)), "x");
    EXPECT_EQ(d.at(7).integer, -2);
    EXPECT_EQ(d.at(8).number, 1.5);
    EXPECT_EQ(d.at(9).unsigned_integer, std::numeric_limits<std::uint64_t>::max());

    // Members carry their key, elements their index.
    EXPECT_EQ(d.key(d.at(6)), "c");
    EXPECT_TRUE(d.in_object(d.at(6)));
    EXPECT_FALSE(d.in_object(d.at(5)));
    EXPECT_EQ(d.at(5).key_offset, 2u);
    EXPECT_FALSE(d.in_object(d.at(0)));

    // Siblings by jumping from end to end: the root's members are 1, 2, 6 and 9.
    std::vector<std::string> keys;
    for (Index i = d.first_child(d.root()); i < d.at(d.root()).end; i = d.next_sibling(i)) {
        keys.emplace_back(d.key(d.at(i)));
    }
    EXPECT_EQ(keys, (std::vector<std::string>{"a", "b", "c", "f"}));
    EXPECT_EQ(d.first_child(2), 3u);

    EXPECT_EQ(d.path(0), "");
    EXPECT_EQ(d.path(5), "b[2]");
    EXPECT_EQ(d.path(8), "c.e");
}

TEST(JsonDocument, EmptyContainersAndCommentsAreFine) {
    const Document d = parse("// a scene\n{/* nothing yet */ \"objects\": [], \"materials\": {}}");
    ASSERT_EQ(d.size(), 3u);
    EXPECT_EQ(d.at(1).count, 0u);
    EXPECT_EQ(d.first_child(1), d.at(1).end) << "an empty container's first child is its end";
    EXPECT_EQ(d.at(2).kind, Kind::Object);
}

TEST(JsonDocument, PathsQuoteKeysThatWouldReadAmbiguously) {
    const Document d = parse(R"({"my glass": {"ior.x": [0, {"k": 1}]}})");
    EXPECT_EQ(d.path(5), R"(["my glass"]["ior.x"][1].k)");
}

TEST(JsonDocument, AKeyGivenTwiceIsRefusedWhereItIs) {
    EXPECT_EQ(refusal_of(R"({"a": 1, "a": 2})"), "t.json: field 'a' is given more than once");
    EXPECT_EQ(refusal_of(R"({"m": [{"k": 1, "k": 2}]})"), "t.json: m[0]: field 'k' is given more than once");
    // Objects of many members look their keys up another way: the same answer.
    std::string many = "{";
    for (int i = 0; i < 40; ++i) many += "\"k" + std::to_string(i) + "\": 0, ";
    EXPECT_EQ(refusal_of(many + "\"k3\": 1}"), "t.json: field 'k3' is given more than once");
    EXPECT_NO_THROW(parse(many + "\"k40\": 1}"));
}

TEST(JsonDocument, ANumberBeyondADoubleIsNamedByItsPath) {
    EXPECT_EQ(refusal_of(R"({"r": [1, 1e999]})"), "t.json: r[1]: expected a finite number, got 1e999 (too large for a double)");
}

TEST(JsonDocument, NestingStopsAtItsCap) {
    const auto nested = [](int depth) { return std::string(std::size_t(depth), '[') + std::string(std::size_t(depth), ']'); };
    EXPECT_EQ(parse(nested(kMaxNesting)).size(), std::size_t(kMaxNesting));
    // The path of the value too deep is as long as the nesting: its first 80
    // characters are shown.
    std::string path;
    for (int i = 0; i < kMaxNesting; ++i) path += "[0]";
    EXPECT_EQ(refusal_of(nested(kMaxNesting + 1)),
              "t.json: " + path.substr(0, 80) + "...: nesting is deeper than 64 levels");
}

TEST(JsonDocument, SyntaxErrorsGiveTheLineAndColumn) {
    const std::string message = refusal_of("{\n  \"a\": 1,\n  \"b\": tru\n}");
    EXPECT_EQ(message.rfind("t.json:3:", 0), 0u) << message;
    EXPECT_NE(message.find(": invalid JSON: invalid literal"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
}

TEST(LineColumn, CountsLinesAndCharactersNotBytes) {
    const std::string text = "ab\nc\xC3\xA9\nx";  // "ab", "cé", "x": é is two bytes
    using LC = std::pair<std::size_t, std::size_t>;
    EXPECT_EQ(line_column(text, 0), LC(1, 1));
    EXPECT_EQ(line_column(text, 1), LC(1, 1));  // the first byte read is the first character
    EXPECT_EQ(line_column(text, 2), LC(1, 2));
    EXPECT_EQ(line_column(text, 4), LC(2, 1));
    EXPECT_EQ(line_column(text, 7), LC(2, 3));  // the newline after "cé"
    EXPECT_EQ(line_column(text, 8), LC(3, 1));
    EXPECT_EQ(line_column(text, 100), LC(3, 2)) << "past the end: the end";
}

TEST(ShortParseReason, KeepsOnlyTheReason) {
    EXPECT_EQ(short_parse_reason("[json.exception.parse_error.101] parse error at line 3, column 10: syntax error "
                                 "while parsing value - invalid literal; last read: 'tru<U+000A>'"),
              "invalid literal");
    EXPECT_EQ(short_parse_reason("[json.exception.parse_error.101] parse error at line 1, column 9: syntax error "
                                 "while parsing object - unexpected number literal; last read: '1 2'; expected '}'"),
              "unexpected number literal; expected '}'");
    EXPECT_EQ(short_parse_reason("something else entirely"), "something else entirely");
}

TEST(QuoteUser, ControlCharactersEscapedAndLongTextShortened) {
    EXPECT_EQ(quote_user("red"), "'red'");
    EXPECT_EQ(quote_user("a\nb\tc"), R"('a\nb\tc')");
    EXPECT_EQ(quote_user(std::string(60, 'x')), "'" + std::string(60, 'x') + "'");
    EXPECT_EQ(quote_user(std::string(61, 'x')), "'" + std::string(60, 'x') + "...'");
    // A UTF-8 sequence cut in half by the shortening does not spoil the message.
    const std::string cut = quote_user(std::string(59, 'x') + "\xC3\xA9");
    EXPECT_EQ(cut.substr(0, 60), "'" + std::string(59, 'x'));
    EXPECT_EQ(cut.substr(cut.size() - 4), "...'");
}

TEST(Paths, PlainKeysDottedOthersQuoted) {
    EXPECT_EQ(path_join("", "materials"), "materials");
    EXPECT_EQ(path_join("materials", "red_2-b"), "materials.red_2-b");
    EXPECT_EQ(path_join("materials", "my glass"), R"(materials["my glass"])");
    EXPECT_EQ(path_join("materials", "a.b"), R"(materials["a.b"])");
    EXPECT_EQ(path_join("m", ""), R"(m[""])");
    EXPECT_EQ(path_join("", "x y"), R"(["x y"])");
    EXPECT_EQ(path_index("objects", 3), "objects[3]");
    EXPECT_EQ(path_index("", 0), "[0]");
}

TEST(FailAt, NamesTheFileAndThePath) {
    EXPECT_THROW(fail_at("f.json", "a.b", "wrong"), vkrt::SceneError);
    try {
        fail_at("f.json", "a.b", "wrong");
    } catch (const vkrt::SceneError& e) {
        EXPECT_STREQ(e.what(), "f.json: a.b: wrong");
    }
    try {
        fail_at("f.json", "", "wrong");
    } catch (const vkrt::SceneError& e) {
        EXPECT_STREQ(e.what(), "f.json: wrong");
    }
}

}  // namespace
