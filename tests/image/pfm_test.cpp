// The Portable Float Map, written and read without the OpenImageIO plug-in
// (image/pfm.hpp): every float kept bit for bit, rows bottom-up as the format says
// (checked against OpenImageIO's own reader), either byte order and grey maps read,
// and a broken file refused with a message that names what is wrong.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "image/image.hpp"
#include "image/image_files.hpp"
#include "image/pfm.hpp"
#include "test_support.hpp"

namespace {

using namespace vkrt;

std::filesystem::path temp_dir() {
    static const std::filesystem::path dir = test::temp_dir("pfm_test");
    return dir;
}

// Values a float image holds in practice and at its edges: negatives, -0, a
// subnormal, the largest float and infinity.
Image awkward() {
    Image img(3, 2);
    const float values[] = {0.0f, -0.0f, 0.18f, 1.0f, 2.5e-42f, -7.25f, std::numeric_limits<float>::max(),
                            std::numeric_limits<float>::infinity(), 1e-3f};
    for (std::size_t i = 0; i < img.rgb.size(); ++i) img.rgb[i] = values[i % 9] * (i < 9 ? 1.0f : 0.5f);
    return img;
}

std::vector<std::uint32_t> bits(const Image& img) {
    std::vector<std::uint32_t> out;
    for (float v : img.rgb) out.push_back(std::bit_cast<std::uint32_t>(v));
    return out;
}

void write_bytes(const std::filesystem::path& file, const std::string& bytes) {
    std::ofstream(file, std::ios::binary) << bytes;
}

std::string error_of(const std::filesystem::path& file) {
    try {
        read_image(file);
    } catch (const ImageError& e) {
        return e.what();
    }
    return "no error";
}

TEST(Pfm, KeepsEveryFloatBitForBit) {
    const Image img = awkward();
    const std::filesystem::path file = temp_dir() / "awkward.pfm";
    write_image(img, file);
    const Image back = read_image(file);
    ASSERT_EQ(back.width, 3u);
    ASSERT_EQ(back.height, 2u);
    EXPECT_EQ(bits(back), bits(img));
}

// OpenImageIO reads the file as the same picture: the rows are bottom-up in the
// file and top-down in memory on both sides.
TEST(Pfm, OpenImageIoReadsTheSamePicture) {
    Image img(2, 3);
    for (std::size_t i = 0; i < img.rgb.size(); ++i) img.rgb[i] = float(i) * 0.25f;
    const std::filesystem::path file = temp_dir() / "rows.pfm";
    write_pfm(img, file);
    std::string error;
    const std::unique_ptr<ImageFileReader> in = image_files().open(file.string(), error);
    ASSERT_TRUE(in) << error;
    ASSERT_EQ(in->spec().channels.size(), 3u);
    std::vector<float> values(img.rgb.size());
    ASSERT_TRUE(in->read_floats(values.data())) << in->error();
    EXPECT_EQ(values, img.rgb);
}

TEST(Pfm, ReadsBigEndianAndGreyMaps) {
    // One grey row of two values, big-endian (a positive scale).
    std::string grey = "Pf\n2 1\n1.0\n";
    for (float v : {0.5f, -3.0f}) {
        const std::uint32_t word = std::bit_cast<std::uint32_t>(v);
        for (int shift = 24; shift >= 0; shift -= 8) grey.push_back(char((word >> shift) & 0xffu));
    }
    write_bytes(temp_dir() / "grey.pfm", grey);
    const Image img = read_image(temp_dir() / "grey.pfm");
    EXPECT_EQ(img.rgb, (std::vector<float>{0.5f, 0.5f, 0.5f, -3.0f, -3.0f, -3.0f}));
}

TEST(Pfm, ABrokenFileIsRefusedByName) {
    const std::string body(12, '\0');  // one RGB pixel
    for (const auto& [name, bytes, piece] :
         {std::tuple{"magic.pfm", std::string("P6\n1 1\n255\n") + body, "not a PFM file"},
          std::tuple{"header.pfm", std::string("PF\none one\n-1\n") + body, "needs a width, a height and a scale"},
          std::tuple{"size.pfm", std::string("PF\n0 1\n-1\n") + body, "out of range"},
          std::tuple{"scale.pfm", std::string("PF\n1 1\n0\n") + body, "out of range"},
          std::tuple{"short.pfm", std::string("PF\n2 1\n-1\n") + body, "need 24 bytes after the header, the file has 12"}}) {
        write_bytes(temp_dir() / name, bytes);
        const std::string message = error_of(temp_dir() / name);
        EXPECT_NE(message.find(name), std::string::npos) << message;
        EXPECT_NE(message.find(piece), std::string::npos) << message;
    }
}

}  // namespace
