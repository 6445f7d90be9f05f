#include "scene/texture_image.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include <fmt/format.h>

#include "image/image.hpp"
#include "image/image_files.hpp"
#include "scene/scene.hpp"
#include "scene/scene_error.hpp"

namespace vkrt {

double srgb_to_linear(double encoded) {
    // IEC 61966-2-1: linear below the knee, a 2.4 power above it.
    return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

glm::dvec4 texture_mean(const TextureImage& texture) {
    glm::dvec4 sum(0.0);
    for (const glm::vec4& c : texture.texels) sum += glm::dvec4(c);
    return texture.texels.empty() ? sum : sum / double(texture.texels.size());
}

void decode_normal_map(TextureImage& texture, double scale) {
    for (glm::vec4& c : texture.texels) {
        c = glm::vec4(float((2.0 * c.r - 1.0) * scale), float((2.0 * c.g - 1.0) * scale), float(2.0 * c.b - 1.0), c.a);
    }
}

void add_texture(Scene& scene, TextureImage texture, const std::string& element) {
    std::uint64_t texels = texture.texels.size();
    for (const TextureImage& t : scene.textures) texels += t.texels.size();
    if (texels > kMaxTextureTexels) {
        throw SceneError(fmt::format("{}: texture {}: the scene's textures would hold {} texels, more than the {} vkrt takes",
                                     element, texture.name, texels, kMaxTextureTexels));
    }
    scene.textures.push_back(std::move(texture));
}

std::array<double, 6> texture_transform(double offset_u, double offset_v, double rotation, double scale_u,
                                        double scale_v) {
    const double c = std::cos(rotation), s = std::sin(rotation);
    return {scale_u * c, scale_v * s, offset_u, -scale_u * s, scale_v * c, offset_v};
}

namespace {

TextureImage read_texture(ImageFileReader& in, Encoding encoding, const std::string& name, const std::string& element) {
    const FileSpec& spec = in.spec();
    const auto fail = [&](const std::string& what) {
        throw SceneError(fmt::format("{}: texture {}: {}", element, name, what));
    };
    const std::size_t channels = spec.channels.size();
    if (spec.width == 0 || spec.height == 0 || channels == 0) fail("the image is empty");
    if (spec.width > kMaxTextureSide || spec.height > kMaxTextureSide) {
        fail(fmt::format("{} x {} texels is larger than the {} x {} vkrt takes", spec.width, spec.height, kMaxTextureSide,
                         kMaxTextureSide));
    }
    std::vector<float> values(std::size_t(spec.width) * spec.height * channels);
    if (!in.read_floats(values.data())) fail(fmt::format("cannot read its pixels: {}", one_line(in.error())));
    const bool floats = spec.types.front() == ChannelType::Float || spec.types.front() == ChannelType::Half;
    const bool decode = encoding == Encoding::SrgbUnlessFloat && !floats;
    TextureImage t;
    t.name = name;
    t.width = spec.width;
    t.height = spec.height;
    t.texels.resize(std::size_t(spec.width) * spec.height);
    for (std::size_t i = 0; i < t.texels.size(); ++i) {
        const float* v = &values[i * channels];
        for (std::size_t c = 0; c < channels; ++c) {
            if (!std::isfinite(v[c])) fail("a texel is not a finite number");
        }
        // Grey, grey and alpha, RGB or RGBA; channels past the fourth are ignored.
        const float r = v[0];
        const float g = channels >= 3 ? v[1] : r;
        const float b = channels >= 3 ? v[2] : r;
        const float a = channels == 2 ? v[1] : channels >= 4 ? v[3] : 1.0f;
        const auto linear = [&](float c) { return decode ? float(srgb_to_linear(std::clamp(c, 0.0f, 1.0f))) : c; };
        t.texels[i] = glm::vec4(linear(r), linear(g), linear(b), a);
    }
    return t;
}

}  // namespace

TextureImage load_texture_file(const std::filesystem::path& file, Encoding encoding, const std::string& element) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) {
        throw SceneError(fmt::format("{}: texture {}: no such file", element, file.string()));
    }
    std::string error;
    std::unique_ptr<ImageFileReader> in;
    try {
        in = image_files().open(file.string(), error);
    } catch (const ImageError& e) {
        throw SceneError(fmt::format("{}: texture {}: {}", element, file.string(), one_line(e.what())));
    }
    if (!in) throw SceneError(fmt::format("{}: texture {}: cannot read it as an image: {}", element, file.string(), one_line(error)));
    return read_texture(*in, encoding, file.string(), element);
}

TextureImage load_texture_memory(const unsigned char* data, std::size_t size, const std::string& format,
                                 Encoding encoding, const std::string& element) {
    std::string error;
    std::unique_ptr<ImageFileReader> in;
    try {
        in = image_files().open_memory(data, size, format, error);
    } catch (const ImageError& e) {
        throw SceneError(fmt::format("{}: {}", element, one_line(e.what())));
    }
    if (!in) throw SceneError(fmt::format("{}: cannot read the image it holds: {}", element, one_line(error)));
    return read_texture(*in, encoding, element, element);
}

}  // namespace vkrt
