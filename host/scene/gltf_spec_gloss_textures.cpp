#include "scene/gltf_spec_gloss_textures.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <fmt/format.h>
#include <glm/common.hpp>
#include <tiny_gltf.h>

#include "scene/scene_error.hpp"

namespace vkrt::gltf {
namespace {

// Where the centre of each of m result texels falls on an axis of n source texels:
// the two texels around it, wrapped, and the second's weight, as texture_bilinear
// (kernel/texture.glsl) finds them for that texture coordinate.
struct Tap {
    std::uint32_t a = 0, b = 0;
    double f = 0.0;
};

std::uint32_t wrap_index(std::int64_t i, std::uint32_t n, Wrap mode) {
    const std::int64_t size = n;
    if (mode == Wrap::Clamp) return std::uint32_t(std::clamp<std::int64_t>(i, 0, size - 1));
    if (mode == Wrap::Mirror) {
        const std::int64_t m = (i + 2 * size) % (2 * size);
        return std::uint32_t(m < size ? m : 2 * size - 1 - m);
    }
    return std::uint32_t((i + size) % size);
}

std::vector<Tap> taps(std::uint32_t n, std::uint32_t m, Wrap mode) {
    std::vector<Tap> out(m);
    for (std::uint32_t k = 0; k < m; ++k) {
        if (n == m) {
            out[k] = {k, k, 0.0};
            continue;
        }
        // The centre, (k + 1/2) / m, is (k + 1/2) n / m - 1/2 in source texels: the
        // integer (2k + 1) n - m over 2m, split exactly into whole and fraction.
        const std::int64_t num = (2 * std::int64_t(k) + 1) * n - m, den = 2 * std::int64_t(m);
        const std::int64_t whole = num >= 0 ? num / den : -((-num + den - 1) / den);
        out[k] = {wrap_index(whole, n, mode), wrap_index(whole + 1, n, mode), double(num - whole * den) / double(den)};
    }
    return out;
}

// The extension's values are from 0 to 1; a float file may hold others.
double unit(double v) { return v > 0.0 ? std::min(v, 1.0) : 0.0; }

// Linear RGBA of a source texture at a result texel (both taps given).
glm::dvec4 sample(const SourceTexture& s, const Tap& x, const Tap& y) {
    const auto at = [&](std::uint32_t i, std::uint32_t j) {
        return glm::dvec4(texel_value(s.texture, s.words, std::size_t(j) * s.texture.width + i));
    };
    const auto row = [&](std::uint32_t j) { return x.f == 0.0 ? at(x.a, j) : glm::mix(at(x.a, j), at(x.b, j), x.f); };
    const glm::dvec4 c = y.f == 0.0 ? row(y.a) : glm::mix(row(y.a), row(y.b), y.f);
    return {unit(c.r), unit(c.g), unit(c.b), unit(c.a)};
}

[[noreturn]] void fail(const std::string& file, const std::string& element, const std::string& what) {
    throw SceneError(fmt::format("{}: {}: {}", file, element, what));
}

}  // namespace

std::uint8_t nearest_byte(double v) { return std::uint8_t(std::lround(unit(v) * 255.0)); }

std::uint8_t nearest_srgb_byte(double v) {
    // The byte is how many of the linear values halfway (in the encoding) between one
    // byte and the next lie at or below v. A search over them is most of a texture's
    // conversion, so it starts from the byte of v's bucket of 4096 (buckets are
    // narrower than the gaps between halfway values, 0.0003 at the least): at most one
    // step on from there.
    constexpr std::size_t kBuckets = 4096;
    struct Tables {
        std::array<double, 256> halfway{};  // the last above every value
        std::array<std::uint8_t, kBuckets> bucket{};
    };
    static const Tables tables = [] {
        Tables t;
        for (std::size_t b = 0; b < 255; ++b) t.halfway[b] = srgb_to_linear((double(b) + 0.5) / 255.0);
        t.halfway[255] = 2.0;
        for (std::size_t i = 0; i < kBuckets; ++i) {
            const double start = double(i) / double(kBuckets);
            t.bucket[i] = std::uint8_t(std::upper_bound(t.halfway.begin(), t.halfway.end(), start) - t.halfway.begin());
        }
        return t;
    }();
    const double u = unit(v);
    std::size_t b = tables.bucket[std::min(std::size_t(u * kBuckets), kBuckets - 1)];
    while (u >= tables.halfway[b]) ++b;
    return std::uint8_t(b);
}

ConvertedTextures convert_textures(const SourceTexture* diffuse, const SourceTexture* specular_glossiness,
                                   const SpecularGlossiness& factors, double alpha) {
    std::uint32_t width = 0, height = 0;
    for (const SourceTexture* s : {diffuse, specular_glossiness}) {
        if (!s) continue;
        width = std::max(width, s->texture.width);
        height = std::max(height, s->texture.height);
    }
    const auto taps_of = [&](const SourceTexture* s, bool x) {
        if (!s) return std::vector<Tap>();
        return x ? taps(s->texture.width, width, s->texture.wrap_s) : taps(s->texture.height, height, s->texture.wrap_t);
    };
    const std::vector<Tap> dx = taps_of(diffuse, true), dy = taps_of(diffuse, false);
    const std::vector<Tap> sx = taps_of(specular_glossiness, true), sy = taps_of(specular_glossiness, false);
    ConvertedTextures out;
    for (DecodedImage* image : {&out.base_color, &out.metallic_roughness}) {
        image->width = width;
        image->height = height;
        image->format = TexelFormat::Rgba8;
        image->words.resize(std::size_t(width) * height);
    }
    out.base_color.srgb = true;
    parallel_for(height, [&](std::size_t y) {
        for (std::uint32_t x = 0; x < width; ++x) {
            const glm::dvec4 d = diffuse ? sample(*diffuse, dx[x], dy[y]) : glm::dvec4(1.0);
            const glm::dvec4 s = specular_glossiness ? sample(*specular_glossiness, sx[x], sy[y]) : glm::dvec4(1.0);
            const Material::MetallicRoughness mr = convert_texel(glm::dvec3(d), s, factors);
            const std::size_t i = y * width + x;
            out.base_color.words[i] = std::uint32_t(nearest_srgb_byte(mr.base_color.r)) |
                                      std::uint32_t(nearest_srgb_byte(mr.base_color.g)) << 8 |
                                      std::uint32_t(nearest_srgb_byte(mr.base_color.b)) << 16 |
                                      std::uint32_t(nearest_byte(d.a * alpha)) << 24;
            out.metallic_roughness.words[i] = std::uint32_t(nearest_byte(mr.roughness)) << 8 |
                                              std::uint32_t(nearest_byte(mr.metallic)) << 16 | 255u << 24;
        }
    });
    return out;
}

std::optional<tinygltf::TextureInfo> read_texture_info(const tinygltf::Value& extension, const char* key,
                                                       const std::string& element, const std::string& file) {
    if (!extension.Has(key)) return std::nullopt;
    const tinygltf::Value& v = extension.Get(key);
    const std::string at = element + "." + key;
    if (!v.IsObject()) fail(file, at, "expected a textureInfo object");
    tinygltf::TextureInfo info;
    const tinygltf::Value& index = v.Get("index");
    if (!index.IsInt() || index.GetNumberAsInt() < 0) fail(file, at + ".index", "expected a texture index (an integer from 0)");
    info.index = index.GetNumberAsInt();
    if (v.Has("texCoord")) {
        const tinygltf::Value& t = v.Get("texCoord");
        if (!t.IsInt() || t.GetNumberAsInt() < 0) fail(file, at + ".texCoord", "expected an integer from 0");
        info.texCoord = t.GetNumberAsInt();
    }
    if (v.Has("extensions")) {
        const tinygltf::Value& e = v.Get("extensions");
        if (!e.IsObject()) fail(file, at + ".extensions", "expected an object");
        for (const std::string& name : e.Keys()) info.extensions[name] = e.Get(name);
    }
    return info;
}

}  // namespace vkrt::gltf
