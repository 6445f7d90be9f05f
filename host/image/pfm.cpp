#include "image/pfm.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "image/image_files.hpp"

namespace vkrt {

namespace {

static_assert(std::endian::native == std::endian::little, "PFM files are written little-endian from memory");

// The header's next whitespace-separated token, from `at` on.
std::string token(const std::string& bytes, std::size_t& at) {
    while (at < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[at]))) ++at;
    const std::size_t start = at;
    while (at < bytes.size() && !std::isspace(static_cast<unsigned char>(bytes[at]))) ++at;
    return bytes.substr(start, at - start);
}

}  // namespace

void write_pfm(const Image& image, const std::filesystem::path& file) {
    std::ofstream out(file, std::ios::binary);
    out << fmt::format("PF\n{} {}\n-1.0\n", image.width, image.height);
    for (std::uint32_t row = image.height; row-- > 0;) {
        out.write(reinterpret_cast<const char*>(image.pixel(0, row)), std::streamsize(sizeof(float) * 3 * image.width));
    }
    if (!out) throw ImageError(fmt::format("{}: writing failed", file.string()));
}

Image read_pfm(const std::filesystem::path& file) {
    const std::string name = file.string();
    std::ifstream in(file, std::ios::binary);
    if (!in) throw ImageError(fmt::format("{}: cannot open it", name));
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::size_t at = 0;
    const std::string magic = token(bytes, at);
    if (magic != "PF" && magic != "Pf") {
        throw ImageError(fmt::format("{}: not a PFM file (it starts with neither PF nor Pf)", name));
    }
    const int channels = magic == "PF" ? 3 : 1;
    std::uint64_t width = 0, height = 0;
    double scale = 0.0;
    try {
        width = std::stoull(token(bytes, at));
        height = std::stoull(token(bytes, at));
        scale = std::stod(token(bytes, at));
    } catch (const std::exception&) {
        throw ImageError(fmt::format("{}: its header needs a width, a height and a scale", name));
    }
    if (width == 0 || height == 0 || width > (1u << 16) || height > (1u << 16) || scale == 0.0 || !std::isfinite(scale)) {
        throw ImageError(fmt::format("{}: a size of {} x {} (1 to 65536 each) or a scale of {} (nonzero) is out of range",
                                     name, width, height, scale));
    }
    ++at;  // the single whitespace character that ends the header
    const std::size_t values = std::size_t(width * height) * channels;
    if (bytes.size() < at || bytes.size() - at != values * sizeof(float)) {
        throw ImageError(fmt::format("{}: {} x {} x {} floats need {} bytes after the header, the file has {}", name,
                                     width, height, channels, values * sizeof(float),
                                     bytes.size() < at ? 0 : bytes.size() - at));
    }
    const bool swap = scale > 0.0;  // big-endian
    Image image(static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height));
    for (std::size_t i = 0; i < values; ++i) {
        std::uint32_t word = 0;
        std::memcpy(&word, bytes.data() + at + i * sizeof(float), sizeof word);
        if (swap) word = (word >> 24) | ((word >> 8) & 0xff00u) | ((word << 8) & 0xff0000u) | (word << 24);
        const float v = std::bit_cast<float>(word);
        const std::size_t pixel = i / channels;
        const std::size_t x = pixel % width, y = height - 1 - pixel / width;
        float* out = image.pixel(std::uint32_t(x), std::uint32_t(y));
        if (channels == 3) {
            out[i % 3] = v;
        } else {
            out[0] = out[1] = out[2] = v;
        }
    }
    return image;
}

}  // namespace vkrt
