// Reading input files: gzip-compressed scenes and meshes read as their plain text,
// recognised by their bytes; damaged gzip data is refused with a message that
// names the file, never read as a shorter scene.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "scene/load_scene.hpp"
#include "scene/read_text.hpp"
#include "scene/scene_error.hpp"
#include "test_support.hpp"

namespace {

namespace fs = std::filesystem;
using vkrt::read_text;
using vkrt::SceneError;

// An NFF scene long enough to span more than two of the reader's 64 KiB buffers
// once decompressed: a view, a light, a material and many spheres.
std::string long_nff() {
    std::string text = "v\nfrom 0 0 -10\nat 0 0 0\nup 0 1 0\nangle 40\nhither 0.1\nresolution 16 16\n"
                       "b 0 0 0\nl 0 10 -10\nf 1 1 1 1 0 1 0 1\n";
    for (int i = 0; i < 10000; ++i) text += "s " + std::to_string(i % 50 - 25) + " " + std::to_string(i / 50 - 50) + " 30 0.4\n";
    return text;
}

std::string bytes_of(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void expect_refused(const fs::path& file, const std::string& piece) {
    try {
        read_text(file, file.string(), "scene");
        ADD_FAILURE() << "no error for " << file;
    } catch (const SceneError& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.rfind(file.string() + ": corrupt gzip data (", 0), 0u) << message;
        EXPECT_NE(message.find(piece), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

TEST(ReadText, GzipReadsAsThePlainTextWhateverTheName) {
    const fs::path dir = vkrt::test::temp_dir("read_text_gzip");
    const std::string text = long_nff();
    ASSERT_GT(text.size(), 2u << 16);
    vkrt::test::write_gzip(dir / "scene.nff.gz", text);
    vkrt::test::write_gzip(dir / "named_plainly.nff", text);
    ASSERT_LT(fs::file_size(dir / "scene.nff.gz"), text.size() / 4) << "not compressed";
    EXPECT_EQ(read_text(dir / "scene.nff.gz", "s", "scene"), text);
    EXPECT_EQ(read_text(dir / "named_plainly.nff", "s", "scene"), text);
    std::ofstream(dir / "plain.nff") << text;
    EXPECT_EQ(read_text(dir / "plain.nff", "s", "scene"), text);
}

TEST(ReadText, ConcatenatedGzipMembersReadAsOneText) {
    const fs::path dir = vkrt::test::temp_dir("read_text_members");
    vkrt::test::write_gzip(dir / "a.gz", "first half\n");
    vkrt::test::write_gzip(dir / "b.gz", "second half\n");
    std::ofstream(dir / "both.gz", std::ios::binary) << bytes_of(dir / "a.gz") << bytes_of(dir / "b.gz");
    EXPECT_EQ(read_text(dir / "both.gz", "both", "scene"), "first half\nsecond half\n");
}

TEST(ReadText, TruncatedGzipIsRefused) {
    const fs::path dir = vkrt::test::temp_dir("read_text_truncated");
    vkrt::test::write_gzip(dir / "whole.nff.gz", long_nff());
    const std::string bytes = bytes_of(dir / "whole.nff.gz");
    std::ofstream(dir / "half.nff.gz", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
    expect_refused(dir / "half.nff.gz", "the file ends inside the compressed stream");
    // Only the 8-byte trailer (CRC and length) missing: the text is whole, the check is not.
    std::ofstream(dir / "no_trailer.nff.gz", std::ios::binary) << bytes.substr(0, bytes.size() - 8);
    expect_refused(dir / "no_trailer.nff.gz", "the file ends inside the compressed stream");
}

TEST(ReadText, DamagedGzipIsRefused) {
    const fs::path dir = vkrt::test::temp_dir("read_text_damaged");
    // The gzip magic, then bytes that are no deflate stream.
    std::ofstream(dir / "garbage.nff.gz", std::ios::binary) << std::string("\x1f\x8b\x08\x00garbage, not deflate");
    expect_refused(dir / "garbage.nff.gz", "");
    // A flipped byte in the compressed data: the CRC (or the stream) catches it.
    vkrt::test::write_gzip(dir / "whole.nff.gz", long_nff());
    std::string bytes = bytes_of(dir / "whole.nff.gz");
    bytes[bytes.size() / 2] = static_cast<char>(bytes[bytes.size() / 2] ^ 0x10);
    std::ofstream(dir / "flipped.nff.gz", std::ios::binary) << bytes;
    expect_refused(dir / "flipped.nff.gz", "");
    // Trailing bytes after the last member are not a gzip member either.
    std::ofstream(dir / "trailing.nff.gz", std::ios::binary) << bytes_of(dir / "whole.nff.gz") << "junk";
    expect_refused(dir / "trailing.nff.gz", "");
}

TEST(ReadText, FormatLooksThroughGz) {
    EXPECT_EQ(vkrt::format_extension("dir/balls.nff.gz"), ".nff");
    EXPECT_EQ(vkrt::format_extension("dir/balls.nff"), ".nff");
    EXPECT_EQ(vkrt::format_extension("room.json.gz"), ".json");
    EXPECT_EQ(vkrt::format_extension("archive.gz"), "");
    EXPECT_EQ(vkrt::scene_stem("dir/balls.nff.gz"), "balls");
    EXPECT_EQ(vkrt::scene_stem("dir/balls.nff"), "balls");
    EXPECT_EQ(vkrt::scene_stem("a.b.json"), "a.b");
}

TEST(ReadText, GzippedScenesLoadAsTheirPlainFiles) {
    const fs::path dir = vkrt::test::temp_dir("read_text_scenes");
    const std::string nff = long_nff();
    std::ofstream(dir / "plain.nff") << nff;
    vkrt::test::write_gzip(dir / "packed.nff.gz", nff);
    const vkrt::Scene plain = vkrt::load_scene(dir / "plain.nff");
    const vkrt::Scene packed = vkrt::load_scene(dir / "packed.nff.gz");
    EXPECT_EQ(packed.spheres.size(), 10000u);
    EXPECT_EQ(packed.spheres.size(), plain.spheres.size());
    EXPECT_EQ(packed.camera.width, plain.camera.width);

    const std::string json = R"({"camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]}, "materials": {"m": {}},
        "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]})";
    vkrt::test::write_gzip(dir / "room.json.gz", json);
    EXPECT_EQ(vkrt::load_scene(dir / "room.json.gz").spheres.size(), 1u);

    vkrt::test::write_gzip(dir / "archive.gz", json);
    try {
        vkrt::load_scene(dir / "archive.gz");
        ADD_FAILURE() << "no error for a .gz that names no scene format";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("unknown scene format"), std::string::npos) << e.what();
    }
}

// The program names its default output after the scene, not after "scene.nff".
TEST(ReadText, RenderOfAGzippedSceneWritesItsStemDotPng) {
    const fs::path dir = vkrt::test::temp_dir("read_text_render");
    vkrt::test::write_gzip(dir / "tiny.nff.gz",
                           "v\nfrom 0 0 -10\nat 0 0 0\nup 0 1 0\nangle 40\nhither 0.1\nresolution 8 8\n"
                           "l 0 10 -10\nf 1 0 0 1 0 1 0 1\ns 0 0 0 1\n");
    const fs::path previous = fs::current_path();
    fs::current_path(dir);
    const vkrt::test::ProgramRun run =
        vkrt::test::run_vkrt("render tiny.nff.gz --backend cpu -q", dir);
    fs::current_path(previous);
    ASSERT_EQ(run.code, 0) << run.stderr_text;
    EXPECT_TRUE(fs::exists(dir / "tiny.png"));
    EXPECT_FALSE(fs::exists(dir / "tiny.nff.png"));
}

}  // namespace
