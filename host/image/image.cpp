#include "image/image.hpp"

#include <algorithm>
#include <cmath>

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>
#include <fmt/std.h>

namespace vkrt {

namespace {

std::string lower_extension(const std::filesystem::path& file) {
    std::string ext = file.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

}  // namespace

bool is_float_format(const std::filesystem::path& file) {
    const std::string ext = lower_extension(file);
    return ext == ".exr" || ext == ".hdr";
}

bool can_write_image_format(const std::filesystem::path& file) {
    return !file.extension().empty() && OIIO::ImageOutput::create(file.string()) != nullptr;
}

float linear_to_srgb(float linear) {
    const float c = std::clamp(linear, 0.0f, 1.0f);
    if (c >= 1.0f) {
        return 1.0f;  // in float the formula gives a hair under 1 there
    }
    return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

std::vector<std::uint8_t> to_srgb8(const Image& image) {
    std::vector<std::uint8_t> bytes(image.rgb.size());
    for (std::size_t i = 0; i < bytes.size(); ++i) {
        bytes[i] = static_cast<std::uint8_t>(std::lround(linear_to_srgb(image.rgb[i]) * 255.0f));
    }
    return bytes;
}

void write_image(const Image& image, const std::filesystem::path& file) {
    const std::string name = file.string();
    auto out = OIIO::ImageOutput::create(name);
    if (!out) {
        throw ImageError(fmt::format("{}: cannot write this image format ({})", name, OIIO::geterror()));
    }
    const bool linear = is_float_format(file);
    OIIO::ImageSpec spec(int(image.width), int(image.height), 3, linear ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", linear ? "Linear" : "sRGB");
    if (!out->open(name, spec)) {
        throw ImageError(fmt::format("{}: cannot open for writing: {}", name, out->geterror()));
    }
    bool ok = false;
    if (linear && lower_extension(file) == ".hdr") {
        // RGBE shares one exponent across a pixel and has no sign: a negative channel
        // would corrupt its neighbours, so it is stored as 0.
        std::vector<float> positive(image.rgb);
        for (float& v : positive) v = std::max(v, 0.0f);
        ok = out->write_image(OIIO::TypeDesc::FLOAT, positive.data());
    } else if (linear) {
        ok = out->write_image(OIIO::TypeDesc::FLOAT, image.rgb.data());
    } else {
        // Encode here rather than trusting a format's colour-space handling: the
        // stored bytes are then the same for every 8-bit format.
        ok = out->write_image(OIIO::TypeDesc::UINT8, to_srgb8(image).data());
    }
    if (!ok || !out->close()) {
        throw ImageError(fmt::format("{}: writing failed: {}", name, out->geterror()));
    }
}

Image read_image(const std::filesystem::path& file) {
    const std::string name = file.string();
    if (!std::filesystem::exists(file)) {
        throw ImageError(fmt::format("{}: no such file", name));
    }
    auto in = OIIO::ImageInput::open(name);
    if (!in) {
        throw ImageError(fmt::format("{}: cannot read image ({})", name, OIIO::geterror()));
    }
    const OIIO::ImageSpec& spec = in->spec();
    const int channels = spec.nchannels;
    std::vector<float> all(std::size_t(spec.width) * spec.height * channels);
    if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, all.data())) {
        throw ImageError(fmt::format("{}: reading failed: {}", name, in->geterror()));
    }
    Image image(std::uint32_t(spec.width), std::uint32_t(spec.height));
    for (std::size_t p = 0; p < std::size_t(spec.width) * spec.height; ++p) {
        for (int c = 0; c < 3; ++c) {
            // Grey (with or without alpha) fills all three; alpha is never colour.
            image.rgb[p * 3 + c] = all[p * channels + (channels >= 3 ? c : 0)];
        }
    }
    return image;
}

}  // namespace vkrt
