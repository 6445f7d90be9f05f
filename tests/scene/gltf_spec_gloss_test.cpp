// KHR_materials_pbrSpecularGlossiness as vkrt's metallic-roughness material
// (host/scene/gltf_spec_gloss.cpp, decision 0033): the factors convert to the values
// the record states, the converted material keeps the extension's reflectance at
// normal incidence and diffuse colour, a hand-written file (tests/scenes/gltf/) is
// read so, and the record's measurement: each model's reflectance by angle.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/packing.hpp>

#include "ggx_reference.hpp"
#include "image/image_files.hpp"
#include "scene/gltf_spec_gloss.hpp"
#include "scene/gltf_spec_gloss_textures.hpp"
#include "scene/load_scene.hpp"
#include "scene/texture_image.hpp"
#include "test_support.hpp"

namespace {

using glm::dvec3;
using vkrt::Material;
using vkrt::gltf::SpecularGlossiness;
using vkrt::gltf::to_metallic_roughness;
namespace ggx = vkrt::test::ggx;

// ------------------------------------------------------------------ the conversion

void expect_material(const Material::MetallicRoughness& mr, dvec3 base, double metallic, double roughness) {
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(mr.base_color[k], base[k], 1e-12) << "base colour " << k;
    EXPECT_NEAR(mr.metallic, metallic, 1e-12);
    EXPECT_NEAR(mr.roughness, roughness, 1e-12);
}

// The values of decision 0033's table.
TEST(SpecularGlossiness, FactorsConvertToTheRecordsValues) {
    // A dielectric (F0 below 0.04): the base colour is the diffuse colour, c_diff / 0.96.
    expect_material(to_metallic_roughness({dvec3(0.8, 0.2, 0.1), dvec3(0.04), 0.5}), dvec3(0.8, 0.2, 0.1), 0.0, 0.5);
    // The extension's gold: no diffuse colour, a metal of the specular colour.
    expect_material(to_metallic_roughness({dvec3(0.0), dvec3(1.0, 0.766, 0.336), 0.9}), dvec3(1.0, 0.766, 0.336), 1.0,
                    0.1);
    // The extension's defaults (every factor 1): a white, polished metal.
    expect_material(to_metallic_roughness({}), dvec3(1.0), 1.0, 0.0);
    // Grey, diffuse 0.5 and specular 0.2: c_diff 0.4, F0 0.2; the metallic factor
    // solves 0.04 m^2 + (0.4 / 0.96 + 0.2 - 0.08) m - 0.16 = 0; the base colour
    // blends 0.4 / (0.96 (1 - m)) and (0.2 - 0.04 (1 - m)) / m by m^2.
    expect_material(to_metallic_roughness({dvec3(0.5), dvec3(0.2), 0.5}), dvec3(0.58833829360685708),
                    0.29179067350476734, 0.5);
    expect_material(to_metallic_roughness({dvec3(0.5), dvec3(0.5), 0.5}), dvec3(0.74646194774477459),
                    0.65113202695269012, 0.5);
    // Coloured: the metallic factor is solved on perceived brightness.
    expect_material(to_metallic_roughness({dvec3(0.3, 0.1, 0.05), dvec3(0.6, 0.35, 0.2), 0.3}),
                    dvec3(0.73471483129542658, 0.36868354047535634, 0.20296750393007035), 0.84809387246021073, 0.7);
}

// A texel multiplies each factor by its texture's value (the glossiness by the
// specular-glossiness texture's alpha) before the conversion: the grey material
// of above, from a texel of half the diffuse factor's colour and a specular
// texel of 0.8 under a factor of 0.25.
TEST(SpecularGlossiness, ATexelTimesItsFactorsConverts) {
    const SpecularGlossiness factors{dvec3(1.0), dvec3(0.25), 1.0};
    expect_material(vkrt::gltf::convert_texel(dvec3(0.5), glm::dvec4(0.8, 0.8, 0.8, 0.5), factors),
                    dvec3(0.58833829360685708), 0.29179067350476734, 0.5);
    // Absent textures count as 1: the factors' own conversion.
    const SpecularGlossiness gold{dvec3(0.0), dvec3(1.0, 0.766, 0.336), 0.9};
    const Material::MetallicRoughness a = vkrt::gltf::convert_texel(dvec3(1.0), glm::dvec4(1.0), gold);
    const Material::MetallicRoughness b = to_metallic_roughness(gold);
    EXPECT_EQ(a.base_color, b.base_color);
    EXPECT_EQ(a.metallic, b.metallic);
    EXPECT_EQ(a.roughness, b.roughness);
}

// In glTF's reference model the converted material reflects mix(0.04, base, m) at
// normal incidence and has the diffuse colour 0.96 (1 - m) base: for grey factors,
// the extension's F0 = specular and c_diff = diffuse (1 - max(specular)) exactly.
TEST(SpecularGlossiness, GreyFactorsKeepTheExtensionsReflectanceAndDiffuseColour) {
    for (const double diffuse : {0.0, 0.2, 0.5, 0.9, 1.0}) {
        for (const double specular : {0.04, 0.1, 0.2, 0.5, 0.8}) {
            const Material::MetallicRoughness mr = to_metallic_roughness({dvec3(diffuse), dvec3(specular), 0.5});
            if (mr.base_color.r >= 1.0) continue;  // clamped: brighter than the material can be
            const double f0 = 0.04 + (mr.base_color.r - 0.04) * mr.metallic;
            const double c_diff = 0.96 * (1.0 - mr.metallic) * mr.base_color.r;
            EXPECT_NEAR(f0, specular, 1e-12) << diffuse << ", " << specular;
            EXPECT_NEAR(c_diff, diffuse * (1.0 - specular), 1e-12) << diffuse << ", " << specular;
        }
    }
}

// ------------------------------------------------------------------ the file

std::filesystem::path spec_gloss_file() { return vkrt::test::source_dir() / "tests" / "scenes" / "gltf" / "spec_gloss.gltf"; }

const Material& material_named(const vkrt::Scene& s, const std::string& name) {
    for (const Material& m : s.materials) {
        if (m.name == name) return m;
    }
    ADD_FAILURE() << "no material " << name;
    return s.materials.front();
}

TEST(SpecularGlossiness, AFileIsReadWithTheConvertedMaterials) {
    const vkrt::Scene s = vkrt::load_scene(spec_gloss_file());
    // Factors alone (grey, as above).
    const Material& grey = material_named(s, "grey");
    ASSERT_TRUE(grey.metallic_roughness);
    expect_material(*grey.metallic_roughness, dvec3(0.58833829360685708), 0.29179067350476734, 0.5);
    // The extension takes the place of the material's pbrMetallicRoughness.
    const Material& gold = material_named(s, "gold");
    expect_material(*gold.metallic_roughness, dvec3(1.0, 0.766, 0.336), 1.0, 0.1);
    EXPECT_FALSE(gold.texture) << "pbrMetallicRoughness's texture is not read beside the extension";
    // Its defaults with a diffuse texture: converted into textures, whose values are
    // the defaults' (a specular factor of 1 leaves no diffuse colour), the material's
    // factors then 1.
    const Material& textured = material_named(s, "defaults with a diffuse texture");
    expect_material(*textured.metallic_roughness, dvec3(1.0), 1.0, 1.0);
    ASSERT_TRUE(textured.texture && textured.metallic_roughness_texture);
    const vkrt::TextureImage& base = s.textures.at(*textured.texture);
    const vkrt::TextureImage& mr = s.textures.at(*textured.metallic_roughness_texture);
    EXPECT_EQ(glm::vec3(vkrt::texel_value(base, s.texels.words(), 0)), glm::vec3(1.0f));
    EXPECT_EQ(vkrt::texel_value(mr, s.texels.words(), 0), glm::vec4(0.0f, 0.0f, 1.0f, 1.0f));
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
}

TEST(SpecularGlossiness, BadFactorsAreNamed) {
    std::ifstream in(spec_gloss_file());
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::filesystem::path dir = vkrt::test::temp_dir("spec_gloss_bad");
    const auto refusal = [&](const std::string& from, const std::string& to) {
        std::string edited = text;
        const std::size_t at = edited.find(from);
        EXPECT_NE(at, std::string::npos) << from;
        edited.replace(at, from.size(), to);
        std::ofstream(dir / "bad.gltf") << edited;
        return vkrt::test::load_error_of(dir / "bad.gltf");
    };
    const std::string element = (dir / "bad.gltf").string() + ": materials[0].extensions.KHR_materials_pbrSpecularGlossiness.";
    EXPECT_EQ(refusal(R"("glossinessFactor": 0.5)", R"("glossinessFactor": 1.5)"),
              element + "glossinessFactor: expected 1 number from 0 to 1");
    EXPECT_EQ(refusal(R"("specularFactor": [0.2, 0.2, 0.2])", R"("specularFactor": [0.2, 0.2])"),
              element + "specularFactor: expected 3 numbers from 0 to 1");
    EXPECT_EQ(refusal(R"("diffuseFactor": [0.5, 0.5, 0.5, 1])", R"("diffuseFactor": [0.5, -0.5, 0.5, 1])"),
              element + "diffuseFactor: expected 4 numbers from 0 to 1");
}

// ------------------------------------------------------------------ the textures

using Texels = std::vector<std::uint32_t>;  // 8-bit RGBA, red in the low byte

// An image of a test file: texture i of the file is image i, with its sampler (none:
// glTF's default, repeat).
struct Png {
    std::string name;
    std::uint32_t width = 0, height = 0;
    Texels texels;
    int sampler = -1;
};

// Bytes spread over their whole range, the same every run.
Texels some_texels(std::uint32_t count, std::uint32_t seed) {
    Texels out;
    for (std::uint32_t i = 0; i < count; ++i) {
        seed = seed * 1664525u + 1013904223u;
        out.push_back(seed ^ (seed >> 13));
    }
    return out;
}

// A 4-channel PNG, written through the image plug-in: 8-bit, or with `sixteen_bit`
// each byte b as the 16-bit value 257 b (the same value, b / 255).
void write_png(const std::filesystem::path& file, const Png& png, bool sixteen_bit = false) {
    vkrt::FileSpec spec;
    spec.width = png.width;
    spec.height = png.height;
    spec.channels = {"R", "G", "B", "A"};
    spec.types.assign(4, sixteen_bit ? vkrt::ChannelType::UInt16 : vkrt::ChannelType::UInt8);
    // The values as given: OpenImageIO would otherwise take the colours as
    // premultiplied by alpha and divide them by it.
    spec.ints["oiio:UnassociatedAlpha"] = 1;
    std::vector<std::uint8_t> bytes;
    std::vector<std::uint16_t> shorts;
    for (std::uint32_t w : png.texels) {
        for (int k = 0; k < 4; ++k) {
            bytes.push_back(std::uint8_t(w >> (8 * k)));
            shorts.push_back(std::uint16_t(257u * ((w >> (8 * k)) & 255u)));
        }
    }
    std::string error;
    const void* pixels = sixteen_bit ? static_cast<const void*>(shorts.data()) : bytes.data();
    ASSERT_TRUE(vkrt::image_files().write(file.string(), spec, pixels, error)) << error;
}

// A glTF file of one quad filling view_quad_head_on's view, with TEXCOORD_0 ((0, 0)
// at the top left), of the material `material` (JSON), beside its images; samplers
// 0 and 1 clamp and repeat.
std::filesystem::path quad_file(const std::string& name, const std::string& material, const std::vector<Png>& pngs) {
    const std::filesystem::path dir = vkrt::test::temp_dir("spec_gloss_textures");
    vkrt::test::write_quad_buffer(dir / (name + ".bin"));
    std::string textures, images;
    for (const Png& png : pngs) {
        write_png(dir / (png.name + ".png"), png);
        const std::string sampler = png.sampler >= 0 ? ", \"sampler\": " + std::to_string(png.sampler) : "";
        textures += std::string(textures.empty() ? "" : ", ") + "{\"source\": " + std::to_string(&png - pngs.data()) +
                    sampler + "}";
        images += std::string(images.empty() ? "" : ", ") + "{\"uri\": \"" + png.name + ".png\"}";
    }
    const std::filesystem::path file = dir / (name + ".gltf");
    std::ofstream(file) << R"({
      "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
      "extensionsUsed": ["KHR_materials_pbrSpecularGlossiness", "KHR_texture_transform"],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": 0}]}],
      "materials": [)" + material + R"(],
      "textures": [)" + textures + R"(],
      "samplers": [{"wrapS": 33071, "wrapT": 33071}, {"wrapS": 10497, "wrapT": 10497}],
      "images": [)" + images + R"(],
      )" + vkrt::test::quad_buffer_json(name + ".bin") + R"(
    })";
    return file;
}

// Whether a warning of the scene holds `text`.
bool warned(const vkrt::Scene& s, const std::string& text) {
    return std::any_of(s.warnings.begin(), s.warnings.end(),
                       [&](const std::string& w) { return w.find(text) != std::string::npos; });
}

// The extension's object with these factors (diffuse alpha 0.5) and textures (JSON
// members, e.g. "\"diffuseTexture\": {\"index\": 0}").
const SpecularGlossiness kFactors{dvec3(0.9, 0.8, 1.0), dvec3(1.0, 0.9, 0.8), 0.7};
constexpr double kAlpha = 0.5;
std::string spec_gloss_material(const std::string& textures) {
    return R"({"extensions": {"KHR_materials_pbrSpecularGlossiness": {"diffuseFactor": [0.9, 0.8, 1, 0.5],
              "specularFactor": [1, 0.9, 0.8], "glossinessFactor": 0.7)" +
           (textures.empty() ? "" : ", " + textures) + "}}}";
}

// A source texel as the kernel reads it: red, green and blue sRGB-decoded by the
// table, alpha b / 255.
glm::dvec4 linear_texel(std::uint32_t w) {
    const std::array<float, 256>& table = vkrt::srgb_byte_table();
    return {table[w & 255], table[(w >> 8) & 255], table[(w >> 16) & 255], float(w >> 24) * (1.0f / 255.0f)};
}

// A source image sampled bilinearly at the centre of texel (x, y) of a result of
// width x height texels, as the kernel samples it there (clamped or repeated).
glm::dvec4 at_centre(const Png& png, bool clamp, std::uint32_t x, std::uint32_t y, std::uint32_t width,
                     std::uint32_t height) {
    const auto axis = [&](std::uint32_t k, std::uint32_t n, std::uint32_t m) {
        const double p = (k + 0.5) * n / m - 0.5, whole = std::floor(p);
        const auto wrap = [&](int i) { return clamp ? std::clamp(i, 0, int(n) - 1) : (i + int(n)) % int(n); };
        return std::tuple{wrap(int(whole)), wrap(int(whole) + 1), p - whole};
    };
    const auto [x0, x1, fx] = axis(x, png.width, width);
    const auto [y0, y1, fy] = axis(y, png.height, height);
    const auto t = [&](int i, int j) { return linear_texel(png.texels[std::size_t(j) * png.width + i]); };
    return glm::mix(glm::mix(t(x0, y0), t(x1, y0), fx), glm::mix(t(x0, y1), t(x1, y1), fx), fy);
}

// sRGB's encoding of a linear value.
double srgb_encoded(double linear) {
    linear = std::clamp(linear, 0.0, 1.0);
    return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

// The bound of quantizing a converted value to 8 bits (nearest_byte,
// nearest_srgb_byte: half a step), with room for float's rounding of the kernel's
// reading of the byte (and of sRGB's encoding here).
constexpr double kByteBound = 0.5 / 255.0 + 1e-6;

// The material's converted textures hold convert_texel of the sources `diffuse` and
// `specular` gives at each texel, within kByteBound: the base colour in sRGB's
// encoding, alpha, roughness and metallic as they are. Returns the largest error.
double expect_converted(const vkrt::Scene& s, std::uint32_t width, std::uint32_t height,
                        const std::function<glm::dvec4(std::uint32_t, std::uint32_t)>& diffuse,
                        const std::function<glm::dvec4(std::uint32_t, std::uint32_t)>& specular) {
    const Material& m = s.materials.at(0);
    expect_material(*m.metallic_roughness, dvec3(1.0), 1.0, 1.0);
    if (!m.texture || !m.metallic_roughness_texture) {
        ADD_FAILURE() << "no converted textures";
        return 0.0;
    }
    const vkrt::TextureImage& base = s.textures.at(*m.texture);
    const vkrt::TextureImage& mr = s.textures.at(*m.metallic_roughness_texture);
    EXPECT_EQ(base.width, width);
    EXPECT_EQ(base.height, height);
    EXPECT_EQ(mr.width, width);
    EXPECT_EQ(mr.height, height);
    EXPECT_TRUE(base.format == vkrt::TexelFormat::Rgba8 && base.srgb);
    EXPECT_TRUE(mr.format == vkrt::TexelFormat::Rgba8 && !mr.srgb);
    if (base.width != width || base.height != height || mr.width != width || mr.height != height) return 0.0;
    double worst = 0.0;
    for (std::uint32_t y = 0; y < height; ++y) {
        for (std::uint32_t x = 0; x < width; ++x) {
            const glm::dvec4 d = diffuse(x, y);
            const Material::MetallicRoughness want = vkrt::gltf::convert_texel(dvec3(d), specular(x, y), kFactors);
            const glm::dvec4 b(vkrt::texel_value(base, s.texels.words(), y * width + x));
            const glm::dvec4 t(vkrt::texel_value(mr, s.texels.words(), y * width + x));
            const double errors[6] = {std::abs(srgb_encoded(b.r) - srgb_encoded(want.base_color.r)),
                                      std::abs(srgb_encoded(b.g) - srgb_encoded(want.base_color.g)),
                                      std::abs(srgb_encoded(b.b) - srgb_encoded(want.base_color.b)),
                                      std::abs(b.a - d.a * kAlpha), std::abs(t.g - want.roughness),
                                      std::abs(t.b - want.metallic)};
            for (int k = 0; k < 6; ++k) {
                EXPECT_LE(errors[k], kByteBound) << "texel " << x << ", " << y << ", value " << k;
                worst = std::max(worst, errors[k]);
            }
        }
    }
    return worst;
}

const Png kDiffuse{"diffuse", 4, 4, some_texels(16, 1)};
const Png kSpecular{"specular", 4, 4, some_texels(16, 2)};

// The quantization's bound, over every linear value a double step of 1e-5 apart:
// the byte nearest in sRGB's encoding is off by half a step there (0.0045 at most
// once decoded), the linear byte by half a step.
TEST(SpecularGlossinessTextures, QuantizingToEightBitsIsOffByHalfAStep) {
    double worst_encoded = 0.0, worst_linear = 0.0, worst_plain = 0.0;
    for (int i = 0; i <= 100000; ++i) {
        const double v = i / 100000.0;
        const std::uint8_t b = vkrt::gltf::nearest_srgb_byte(v);
        worst_encoded = std::max(worst_encoded, std::abs(b / 255.0 - srgb_encoded(v)));
        worst_linear = std::max(worst_linear, std::abs(vkrt::srgb_to_linear(b / 255.0) - v));
        worst_plain = std::max(worst_plain, std::abs(vkrt::gltf::nearest_byte(v) / 255.0 - v));
    }
    std::printf("8-bit error: sRGB %.6f encoded, %.6f linear; linear bytes %.6f (half a step: %.6f)\n", worst_encoded,
                worst_linear, worst_plain, 0.5 / 255.0);
    EXPECT_LE(worst_encoded, 0.5 / 255.0 + 1e-12);
    EXPECT_LE(worst_linear, 0.5 / 255.0 * 2.4 / 1.055 + 1e-12);
    EXPECT_LE(worst_plain, 0.5 / 255.0 + 1e-12);
    EXPECT_EQ(vkrt::gltf::nearest_srgb_byte(-1.0), 0);
    EXPECT_EQ(vkrt::gltf::nearest_srgb_byte(2.0), 255);
}

// Two textures of one size: each texel converted with the factors; only the two
// converted textures stay in the scene's texels, not their sources.
TEST(SpecularGlossinessTextures, TexelsConvertOneForOne) {
    const vkrt::Scene s = vkrt::load_scene(quad_file(
        "same_size",
        spec_gloss_material(R"("diffuseTexture": {"index": 0}, "specularGlossinessTexture": {"index": 1})"),
        {kDiffuse, kSpecular}));
    // The diffuse factor's alpha, 0.5, rides in the converted texture's alpha; the
    // material is opaque, which ignores it as glTF says, without a warning.
    EXPECT_TRUE(s.warnings.empty());
    const auto texel = [](const Png& png) {
        return [&png](std::uint32_t x, std::uint32_t y) { return linear_texel(png.texels[y * png.width + x]); };
    };
    const double worst = expect_converted(s, 4, 4, texel(kDiffuse), texel(kSpecular));
    std::printf("largest error of the converted texels: %.6f (bound %.6f)\n", worst, kByteBound);
    EXPECT_EQ(s.textures.size(), 2u);
    EXPECT_EQ(s.texels.size(), 2u * 16u);
}

// One texture alone: the other side from its factor, at the texture's size.
TEST(SpecularGlossinessTextures, OneTextureAloneTakesTheOtherFromItsFactor) {
    const auto texel = [](const Png& png) {
        return [&png](std::uint32_t x, std::uint32_t y) { return linear_texel(png.texels[y * png.width + x]); };
    };
    const auto one = [](std::uint32_t, std::uint32_t) { return glm::dvec4(1.0); };
    const Png small_specular{"small_specular", 2, 3, some_texels(6, 3)};
    const vkrt::Scene d = vkrt::load_scene(quad_file(
        "diffuse_only", spec_gloss_material(R"("diffuseTexture": {"index": 0})"), {kDiffuse}));
    expect_converted(d, 4, 4, texel(kDiffuse), one);
    const vkrt::Scene sg = vkrt::load_scene(quad_file(
        "specular_only", spec_gloss_material(R"("specularGlossinessTexture": {"index": 0})"), {small_specular}));
    expect_converted(sg, 2, 3, one, texel(small_specular));
}

// A 16-bit diffuse texture, which vkrt keeps as half floats where it is a plain
// texture, converts as an 8-bit one does: from its values sRGB-decoded to linear
// (then rounded to half floats), into 8-bit converted textures.
TEST(SpecularGlossinessTextures, SixteenBitTexturesConvertToo) {
    const std::filesystem::path file = quad_file(
        "sixteen_bit", spec_gloss_material(R"("diffuseTexture": {"index": 0}, "specularGlossinessTexture": {"index": 1})"),
        {kDiffuse, kSpecular});
    write_png(file.parent_path() / "diffuse.png", kDiffuse, true);
    {
        std::ifstream png(file.parent_path() / "diffuse.png", std::ios::binary);
        char header[25] = {};
        png.read(header, sizeof header);
        ASSERT_EQ(header[24], 16) << "IHDR's bit depth";
    }
    const vkrt::Scene s = vkrt::load_scene(file);
    const auto half = [](double v) { return double(glm::unpackHalf2x16(glm::packHalf2x16(glm::vec2(float(v)))).x); };
    expect_converted(
        s, 4, 4,
        [&](std::uint32_t x, std::uint32_t y) {
            const std::uint32_t w = kDiffuse.texels[y * 4 + x];
            const auto channel = [&](int k) { return double((w >> (8 * k)) & 255u) / 255.0; };
            return glm::dvec4(half(vkrt::srgb_to_linear(channel(0))), half(vkrt::srgb_to_linear(channel(1))),
                              half(vkrt::srgb_to_linear(channel(2))), half(channel(3)));
        },
        [](std::uint32_t x, std::uint32_t y) { return linear_texel(kSpecular.texels[y * 4 + x]); });
    EXPECT_EQ(s.texels.size(), 2u * 16u) << "no half-float texels left behind";
}

// A diffuse texture 4 x 2, clamped, and a specular-glossiness texture 2 x 4,
// repeated: converted at 4 x 4, each sampled bilinearly with its own wrap modes;
// the converted textures clamp, as the diffuse one, and the other's wrap modes are
// named as not kept.
TEST(SpecularGlossinessTextures, TexturesOfDifferentSizesConvertAtTheLarger) {
    Png diffuse{"wide", 4, 2, some_texels(8, 4), 0};
    Png specular{"tall", 2, 4, some_texels(8, 5), 1};
    const vkrt::Scene s = vkrt::load_scene(quad_file(
        "sizes", spec_gloss_material(R"("diffuseTexture": {"index": 0}, "specularGlossinessTexture": {"index": 1})"),
        {diffuse, specular}));
    const double worst = expect_converted(
        s, 4, 4, [&](std::uint32_t x, std::uint32_t y) { return at_centre(diffuse, true, x, y, 4, 4); },
        [&](std::uint32_t x, std::uint32_t y) { return at_centre(specular, false, x, y, 4, 4); });
    std::printf("largest error of the resampled, converted texels: %.6f\n", worst);
    const Material& m = s.materials.at(0);
    ASSERT_TRUE(m.texture && m.metallic_roughness_texture);
    EXPECT_EQ(s.textures.at(*m.texture).wrap_s, vkrt::Wrap::Clamp);
    EXPECT_EQ(s.textures.at(*m.metallic_roughness_texture).wrap_t, vkrt::Wrap::Clamp);
    EXPECT_EQ(s.warnings.size(), 1u);
    EXPECT_TRUE(warned(s, "KHR_materials_pbrSpecularGlossiness textures with different wrap modes, both converted "
                          "with the diffuse texture's (1): ignored"));
}

// Converted texel by texel, the two textures must share one mapping: a
// specular-glossiness texture whose transform differs from the diffuse texture's is
// left out, and its factors alone converted. An image a plain texture uses as well is read from the scene's
// texels, not decoded again.
TEST(SpecularGlossinessTextures, ADifferentTransformLeavesTheLaterTextureOut) {
    const std::string material = spec_gloss_material(
        R"("diffuseTexture": {"index": 0}, "specularGlossinessTexture": {"index": 1,
           "extensions": {"KHR_texture_transform": {"offset": [0.5, 0]}}})");
    const std::string plain = R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}})";
    const vkrt::Scene s = vkrt::load_scene(quad_file("transforms", material + ", " + plain, {kDiffuse, kSpecular}));
    expect_converted(
        s, 4, 4, [](std::uint32_t x, std::uint32_t y) { return linear_texel(kDiffuse.texels[y * 4 + x]); },
        [](std::uint32_t, std::uint32_t) { return glm::dvec4(1.0); });
    EXPECT_EQ(s.warnings.size(), 1u);
    EXPECT_TRUE(warned(s, "KHR_materials_pbrSpecularGlossiness textures on different texture coordinates (TEXCOORD_n or "
                          "KHR_texture_transform), converted without the specular-glossiness texture (1): ignored"));
    EXPECT_EQ(s.texels.size(), 16u + 2u * 16u) << "the diffuse image once, and the two converted textures";
}

TEST(SpecularGlossinessTextures, BadTextureInfosAreNamed) {
    const auto error = [](const std::string& name, const std::string& textures) {
        const std::filesystem::path file = quad_file(name, spec_gloss_material(textures), {kDiffuse});
        return std::pair{vkrt::test::load_error_of(file), file.string()};
    };
    const std::string element = ": materials[0].extensions.KHR_materials_pbrSpecularGlossiness.";
    auto [a, file_a] = error("bad_index", R"("diffuseTexture": {"index": 1.5})");
    EXPECT_EQ(a, file_a + element + "diffuseTexture.index: expected a texture index (an integer from 0)");
    auto [b, file_b] = error("bad_info", R"("specularGlossinessTexture": 3)");
    EXPECT_EQ(b, file_b + element + "specularGlossinessTexture: expected a textureInfo object");
    auto [c, file_c] = error("absent_texture", R"("diffuseTexture": {"index": 4})");
    EXPECT_EQ(c, file_c + element + "diffuseTexture.index: texture 4 does not exist (the file has 1)");
}

// The converted material is an ordinary metallic-roughness one: a quad of it renders
// as the quad whose metallic-roughness material has the converted textures as its
// own (written to PNG files), bit for bit on both backends.
TEST(SpecularGlossinessTextures, RenderAsTheirMetallicRoughnessConversion) {
    const Png diffuse{"render_diffuse", 4, 2, some_texels(8, 6), 0};
    const Png specular{"render_specular", 2, 4, some_texels(8, 7), 1};
    vkrt::Scene a = vkrt::load_scene(quad_file(
        "render_spec_gloss",
        spec_gloss_material(R"("diffuseTexture": {"index": 0}, "specularGlossinessTexture": {"index": 1})"),
        {diffuse, specular}));
    const Material& m = a.materials.at(0);
    ASSERT_TRUE(m.texture && m.metallic_roughness_texture);
    const auto converted = [&](std::uint32_t index, const char* name) {
        const vkrt::TextureImage& t = a.textures.at(index);
        const auto words = a.texels.words().subspan(t.first_word, t.word_count());
        return Png{name, t.width, t.height, Texels(words.begin(), words.end()), 0};
    };
    const Png base = converted(*m.texture, "render_base"), mr = converted(*m.metallic_roughness_texture, "render_mr");
    vkrt::Scene b = vkrt::load_scene(quad_file(
        "render_metallic_roughness",
        R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicRoughnessTexture": {"index": 1}}})",
        {base, mr}));
    ASSERT_EQ(b.texels.size(), a.texels.size());
    EXPECT_TRUE(std::equal(a.texels.words().begin(), a.texels.words().end(), b.texels.words().begin()));
    for (vkrt::Scene* s : {&a, &b}) vkrt::test::view_quad_head_on(*s, 24, 4, 1.0);
    const vkrt::RenderOutcome cpu_a = vkrt::test::render_cpu(a), cpu_b = vkrt::test::render_cpu(b);
    EXPECT_EQ(vkrt::test::max_abs_difference(cpu_a.image, cpu_b.image), 0.0f) << "cpu";
    const vkrt::RenderOutcome gpu_a = vkrt::test::render_vulkan(a), gpu_b = vkrt::test::render_vulkan(b);
    EXPECT_EQ(vkrt::test::max_abs_difference(gpu_a.image, gpu_b.image), 0.0f) << "vulkan";
    // The texture shows: not one colour over the quad.
    float lo = 1e9f, hi = -1e9f;
    for (float v : cpu_a.image.rgb) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
    EXPECT_GT(hi - lo, 0.05f);
}

// ------------------------------------------------------------------ the measurement

// The directional albedo of a BRDF seen from cos_o: the integral of f cos_i over the
// hemisphere, taken over the half vector (dw_i = 4 (wo.h) dw_h), 400 x 400 points.
double albedo(const std::function<double(dvec3, dvec3)>& f, double cos_o) {
    const dvec3 wo(std::sqrt(1.0 - cos_o * cos_o), 0.0, cos_o);
    const int n = 400;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        const double z = (i + 0.5) / n, r = std::sqrt(1.0 - z * z);
        for (int j = 0; j < n; ++j) {
            const double phi = 2.0 * ggx::kPi * (j + 0.5) / n;
            const dvec3 h(r * std::cos(phi), r * std::sin(phi), z);
            const double oh = glm::dot(wo, h);
            const dvec3 wi = 2.0 * oh * h - wo;
            if (!(oh > 0.0 && wi.z > 0.0)) continue;
            sum += f(wo, wi) * wi.z * 4.0 * oh * (1.0 / n) * (2.0 * ggx::kPi / n);
        }
    }
    return sum;
}

// GGX's D G2 / (4 cos_o cos_i), of alpha, for unit wo and wi above the surface.
double microfacet(dvec3 wo, dvec3 wi, double alpha) {
    const dvec3 h = glm::normalize(wo + wi);
    return ggx::d(h.z, alpha) * ggx::g2(wo.z, wi.z, alpha) / (4.0 * wo.z * wi.z);
}

double schlick(double f0, dvec3 wo, dvec3 wi) {
    return f0 + (1.0 - f0) * ggx::pow5(1.0 - glm::dot(wo, glm::normalize(wo + wi)));
}

// The extension's own material, one channel: its BRDF inputs in glTF's reference
// BRDF (specification, appendix B), c_diff / pi weighed by 1 - F beside the GGX lobe.
double extension_brdf(double diffuse, double specular, double max_specular, double glossiness, dvec3 wo, dvec3 wi) {
    const double alpha = std::max((1.0 - glossiness) * (1.0 - glossiness), 1e-3);
    const double f = schlick(specular, wo, wi);
    return (1.0 - f) * diffuse * (1.0 - max_specular) / ggx::kPi + f * microfacet(wo, wi, alpha);
}

// Blender's importer: a Diffuse BSDF of the diffuse colour added to a Glossy BSDF
// (GGX, no Fresnel term) of the specular colour, both of roughness 1 - glossiness.
// The diffuse lobe is taken as Lambert's here; Cycles' is Oren-Nayar's.
double blender_brdf(double diffuse, double specular, double glossiness, dvec3 wo, dvec3 wi) {
    const double alpha = std::max((1.0 - glossiness) * (1.0 - glossiness), 1e-3);
    return diffuse / ggx::kPi + specular * microfacet(wo, wi, alpha);
}

// The same conversion solved instead for the diffuse colour of vkrt's own lobe,
// (1 - m) base (1 - F0) (decision 0029), in place of glTF's 0.96 (1 - m) base: the
// alternative decision 0033 measured and did not take.
Material::MetallicRoughness solved_for_vkrt(const SpecularGlossiness& sg) {
    const auto perceived = [](dvec3 c) { return std::sqrt(0.299 * c.r * c.r + 0.587 * c.g * c.g + 0.114 * c.b * c.b); };
    const double oms = 1.0 - std::max({sg.specular.r, sg.specular.g, sg.specular.b});
    const double d = perceived(sg.diffuse) * oms, s = perceived(sg.specular), f0 = std::max(s, 0.04);
    double m = 0.0;
    if (s >= 0.04) {
        const double b = d / (1.0 - s) + s - 0.08, c = 0.04 - s;
        m = std::clamp((-b + std::sqrt(std::max(b * b - 0.16 * c, 0.0))) / 0.08, 0.0, 1.0);
    }
    const dvec3 from_diffuse = sg.diffuse * (oms / std::max((1.0 - m) * (1.0 - f0), 1e-6));
    const dvec3 from_specular = (sg.specular - dvec3(0.04 * (1.0 - m))) / std::max(m, 1e-6);
    return {glm::clamp(glm::mix(from_diffuse, from_specular, m * m), 0.0, 1.0), m, 1.0 - sg.glossiness};
}

// Decision 0033's table: the red channel's albedo at three angles under the
// extension's own model, Blender's sum, and vkrt's material by the reference
// conversion and by the alternative. At normal incidence and at 60 degrees vkrt's
// material by the reference conversion stays within 0.035 of the extension's (the
// plastic's 0.031 is vkrt's diffuse lobe, 21/20 of Lambert's there), and never
// further than by the alternative.
TEST(SpecularGlossiness, ReflectanceByAngleOfEachModel) {
    struct Case {
        const char* name;
        SpecularGlossiness sg;
    };
    const Case cases[] = {{"plastic", {dvec3(0.8, 0.2, 0.1), dvec3(0.04), 0.5}},
                          {"gold", {dvec3(0.0), dvec3(1.0, 0.766, 0.336), 0.5}},
                          {"grey", {dvec3(0.5), dvec3(0.2), 0.5}},
                          {"half", {dvec3(0.5), dvec3(0.5), 0.5}},
                          {"copper", {dvec3(0.3, 0.1, 0.05), dvec3(0.6, 0.35, 0.2), 0.5}}};
    std::printf("material  cos_o  extension  Blender  vkrt (reference)  vkrt (solved for vkrt)\n");
    for (const Case& c : cases) {
        const Material::MetallicRoughness ours = to_metallic_roughness(c.sg), other = solved_for_vkrt(c.sg);
        const double max_specular = std::max({c.sg.specular.r, c.sg.specular.g, c.sg.specular.b});
        for (const double cos_o : {1.0, 0.5, 0.1}) {
            const double extension = albedo(
                [&](dvec3 wo, dvec3 wi) {
                    return extension_brdf(c.sg.diffuse.r, c.sg.specular.r, max_specular, c.sg.glossiness, wo, wi);
                },
                cos_o);
            const double blender = albedo(
                [&](dvec3 wo, dvec3 wi) { return blender_brdf(c.sg.diffuse.r, c.sg.specular.r, c.sg.glossiness, wo, wi); },
                cos_o);
            const auto vkrt = [&](const Material::MetallicRoughness& mr) {
                return albedo(
                    [&](dvec3 wo, dvec3 wi) {
                        // Single-scattering, as the extension's own BRDF and Blender's are:
                        // the test judges the conversion, not the lobes' compensation.
                        return ggx::metallic_roughness_single_scattering_bsdf(mr.base_color.r, mr.metallic,
                                                                              mr.roughness, dvec3(0, 0, 1), wo, wi);
                    },
                    cos_o);
            };
            const double a = vkrt(ours), b = vkrt(other);
            std::printf("%-8s  %5.2f  %9.3f  %7.3f  %16.3f  %22.3f\n", c.name, cos_o, extension, blender, a, b);
            if (cos_o >= 0.5) {
                EXPECT_NEAR(a, extension, 0.035) << c.name << " at cos " << cos_o;
                EXPECT_LE(std::abs(a - extension), std::abs(b - extension)) << c.name << " at cos " << cos_o;
            }
        }
    }
}

}  // namespace
