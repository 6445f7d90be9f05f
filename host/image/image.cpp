#include "image/image.hpp"

#include <algorithm>
#include <cmath>

#include <fstream>

#include <fmt/format.h>
#include <fmt/std.h>

#include "image/image_files.hpp"
#include "image/pfm.hpp"
#include "image/png_encode.hpp"

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
    return ext == ".exr" || ext == ".hdr" || ext == ".pfm";
}

bool can_write_image_format(const std::filesystem::path& file) {
    // Written here, without the plug-in.
    if (lower_extension(file) == ".png" || lower_extension(file) == ".pfm") return true;
    return !file.extension().empty() && image_files().can_write(file.string());
}

float linear_to_srgb(float linear) {
    const float c = std::clamp(linear, 0.0f, 1.0f);
    if (c >= 1.0f) {
        return 1.0f;  // in float the formula gives a hair under 1 there
    }
    return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

std::vector<std::uint8_t> to_srgb8(const Image& image, const Display& display) {
    std::vector<std::uint8_t> bytes(image.rgb.size());
    for (std::size_t i = 0; i < bytes.size(); ++i) {
        bytes[i] = static_cast<std::uint8_t>(std::lround(linear_to_srgb(display_value(image.rgb[i], display)) * 255.0f));
    }
    return bytes;
}

void write_image(const Image& image, const std::filesystem::path& file, const Display& display) {
    const std::string name = file.string();
    if (lower_extension(file) == ".png") {
        // The most common output needs no image library (image/image_files.hpp).
        const std::vector<std::uint8_t> png = encode_png(image, display);
        std::ofstream out(file, std::ios::binary);
        out.write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
        if (!out) throw ImageError(fmt::format("{}: writing failed", name));
        return;
    }
    if (lower_extension(file) == ".pfm") {
        write_pfm(image, file);
        return;
    }
    const bool linear = is_float_format(file);
    FileSpec spec;
    spec.width = image.width;
    spec.height = image.height;
    spec.channels = {"R", "G", "B"};
    spec.types.assign(3, linear ? ChannelType::Float : ChannelType::UInt8);
    spec.strings["oiio:ColorSpace"] = linear ? "Linear" : "sRGB";
    std::string error;
    bool ok = false;
    if (linear && lower_extension(file) == ".hdr") {
        // RGBE shares one exponent across a pixel and has no sign: a negative channel
        // would corrupt its neighbours, so it is stored as 0.
        std::vector<float> positive(image.rgb);
        for (float& v : positive) v = std::max(v, 0.0f);
        ok = image_files().write(name, spec, positive.data(), error);
    } else if (linear) {
        ok = image_files().write(name, spec, image.rgb.data(), error);
    } else {
        // Encode here rather than trusting a format's colour-space handling: the
        // stored bytes are then the same for every 8-bit format.
        ok = image_files().write(name, spec, to_srgb8(image, display).data(), error);
    }
    if (!ok) throw ImageError(fmt::format("{}: {}", name, error));
}

void write_layered_exr(const Image& image, const std::vector<ImageLayer>& layers, const std::filesystem::path& file,
                       const std::map<std::string, std::string>& attributes) {
    const std::string name = file.string();
    if (lower_extension(file) != ".exr") throw ImageError(fmt::format("{}: layers need an OpenEXR file (.exr)", name));
    FileSpec spec;
    spec.width = image.width;
    spec.height = image.height;
    spec.channels = {"R", "G", "B"};
    for (const ImageLayer& layer : layers) {
        for (const std::string& c : layer.channels) spec.channels.push_back(layer.name.empty() ? c : layer.name + "." + c);
    }
    spec.types.assign(spec.channels.size(), ChannelType::Float);
    spec.strings["oiio:ColorSpace"] = "Linear";
    for (const auto& [key, value] : attributes) spec.strings[key] = value;
    const std::size_t pixels = std::size_t(image.width) * image.height;
    const std::size_t stride = spec.channels.size();
    std::vector<float> values(pixels * stride);
    for (std::size_t p = 0; p < pixels; ++p) {
        float* out = &values[p * stride];
        for (int c = 0; c < 3; ++c) *out++ = image.rgb[p * 3 + std::size_t(c)];
        for (const ImageLayer& layer : layers) {
            const std::size_t n = layer.channels.size();
            if (layer.values.size() != pixels * n) {
                throw ImageError(fmt::format("{}: layer {} holds {} values for {} pixels of {} channels", name,
                                             layer.name, layer.values.size(), pixels, n));
            }
            for (std::size_t c = 0; c < n; ++c) *out++ = layer.values[p * n + c];
        }
    }
    std::string error;
    if (!image_files().write(name, spec, values.data(), error)) throw ImageError(fmt::format("{}: {}", name, error));
}

std::optional<Image> read_layer(const std::filesystem::path& file, const std::string& name) {
    const std::string path = file.string();
    std::string error;
    const std::unique_ptr<ImageFileReader> in = image_files().open(path, error);
    if (!in) throw ImageError(fmt::format("{}: cannot read image ({})", path, error));
    const FileSpec& spec = in->spec();
    std::size_t at[3];
    for (int c = 0; c < 3; ++c) {
        const std::string channel = name + "." + "RGB"[c];
        const auto it = std::find(spec.channels.begin(), spec.channels.end(), channel);
        if (it == spec.channels.end()) return std::nullopt;
        at[c] = std::size_t(it - spec.channels.begin());
    }
    const std::size_t channels = spec.channels.size();
    std::vector<float> all(std::size_t(spec.width) * spec.height * channels);
    if (!in->read_floats(all.data())) throw ImageError(fmt::format("{}: reading failed: {}", path, in->error()));
    Image layer(spec.width, spec.height);
    for (std::size_t p = 0; p < std::size_t(spec.width) * spec.height; ++p) {
        for (int c = 0; c < 3; ++c) layer.rgb[p * 3 + std::size_t(c)] = all[p * channels + at[c]];
    }
    return layer;
}

Image read_image(const std::filesystem::path& file) {
    const std::string name = file.string();
    if (!std::filesystem::exists(file)) {
        throw ImageError(fmt::format("{}: no such file", name));
    }
    if (lower_extension(file) == ".pfm") return read_pfm(file);
    std::string error;
    const std::unique_ptr<ImageFileReader> in = image_files().open(name, error);
    if (!in) {
        throw ImageError(fmt::format("{}: cannot read image ({})", name, error));
    }
    const FileSpec& spec = in->spec();
    const std::size_t channels = spec.channels.size();
    std::vector<float> all(std::size_t(spec.width) * spec.height * channels);
    if (!in->read_floats(all.data())) {
        throw ImageError(fmt::format("{}: reading failed: {}", name, in->error()));
    }
    Image image(spec.width, spec.height);
    for (std::size_t p = 0; p < std::size_t(spec.width) * spec.height; ++p) {
        for (int c = 0; c < 3; ++c) {
            // Grey (with or without alpha) fills all three; alpha is never colour.
            image.rgb[p * 3 + c] = all[p * channels + (channels >= 3 ? c : 0)];
        }
    }
    return image;
}

}  // namespace vkrt
