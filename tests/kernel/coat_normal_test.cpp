// A clear coat's own normal (kernel/normal_map.glsl coat_normal, lobes/coat.glsl):
// the material's normal map does not bend the coat, the coat's own map does
// (glTF's clearcoatNormalTexture); the coat is weighed, valued, drawn and given its
// density on that normal; the image of a tilted coat is its GGX value on the tilted
// normal, on both backends; the scene file's fields and their errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <string>

#include <glm/geometric.hpp>

#include "flatten/flat_scene.hpp"
#include "flatten/ggx_albedo.hpp"
#include "image/image.hpp"
#include "image/image_files.hpp"
#include "kernel/kernel.hpp"
#include "mapped_triangle.hpp"
#include "scene/load_scene.hpp"
#include "test_support.hpp"

namespace vkrt {
namespace {

using kernel::Kernel;
using kernel::vec2;
using kernel::vec3;
using Slot = test::MappedTriangle::Slot;

const vec3 kUp(0.0f, 0.0f, 1.0f);
// (0.5, 0, 1) in tangent space: the normal (1, 0, 2) / sqrt 5, toward +u.
const vec3 kTilt(0.5f, 0.0f, 1.0f);
const std::array<vec2, 3> kAlongEdges = {vec2(0.0f, 0.0f), vec2(1.0f, 0.0f), vec2(0.0f, 1.0f)};

TEST(CoatNormalKernel, TheMaterialsMapLeavesTheCoatOnTheSurfacesNormal) {
    test::MappedTriangle base(kTilt, kAlongEdges, Slot::Material);
    const vec3 bent = base.normal(kUp);
    EXPECT_NEAR(bent.x, 1.0f / std::sqrt(5.0f), 1e-6f);
    EXPECT_EQ(base.coat_normal(kUp), kUp);
}

TEST(CoatNormalKernel, TheCoatsOwnMapBendsTheCoatAlone) {
    test::MappedTriangle base(kTilt, kAlongEdges, Slot::Material);
    test::MappedTriangle coat(kTilt, kAlongEdges, Slot::Coat);
    EXPECT_EQ(coat.normal(kUp), kUp);
    EXPECT_EQ(coat.coat_normal(kUp), base.normal(kUp)) << "the same map bends either normal alike, bit for bit";
}

// A kernel that reads the GGX albedo tables (the coat's R_coat), as a flattened
// scene with a metallic-roughness material gives them.
Kernel kernel_with_tables() {
    Kernel k;
    k.table_words = ggx_albedo_table();
    kernel::set_ggx_table_first_word(k.params, 0u);
    return k;
}

// A coat alone over a base that reflects nothing (no diffuse colour, a GGX lobe of
// zero reflectance at every angle), the coat on a tilted normal.
kernel::Material coat_only(float coat_alpha) {
    kernel::Material m{};
    m.ggx_alpha = 0.25f;
    m.ggx_f90 = 0.0f;
    m.coat = 1.0f;
    m.coat_alpha = coat_alpha;
    return m;
}

// Its Fresnel weight at wo's cosine to its own normal; its value, times the cosine
// to the shading normal the caller weighs by, is its GGX value times its own cosine.
TEST(CoatNormalLobes, TheCoatIsWeighedAndValuedOnItsOwnNormal) {
    Kernel k = kernel_with_tables();
    const vec3 nc = glm::normalize(vec3(0.3f, 0.0f, 1.0f));
    const vec3 wo = glm::normalize(vec3(-0.2f, 0.1f, 1.0f));
    const kernel::Material m = coat_only(0.3f);
    const Kernel::Lobes l = k.material_lobes(m, kUp, nc, wo);
    EXPECT_FLOAT_EQ(l.coat.weight, k.fresnel_schlick(vec3(k.COAT_F0), glm::dot(nc, wo)).x);
    EXPECT_EQ(l.coat.normal, nc);
    for (const vec3 wi : {glm::normalize(vec3(0.5f, 0.0f, 1.0f)), glm::normalize(vec3(0.1f, -0.4f, 1.0f)),
                          glm::normalize(vec3(-0.9f, 0.2f, 0.6f))}) {
        const float shaded = k.coat_eval(l.coat, kUp, wo, wi).x * glm::dot(kUp, wi);
        const float own = k.ggx_eval(vec3(k.COAT_F0), 1.0f, 0.3f, nc, wo, wi).x * glm::dot(nc, wi);
        EXPECT_NEAR(shaded, own, 1e-6f * std::max(1.0f, own));
    }
    // On the shading normal itself the value is GGX's as is.
    const Kernel::Lobes flat = k.material_lobes(m, kUp, kUp, wo);
    const vec3 wi = glm::normalize(vec3(0.5f, 0.0f, 1.0f));
    EXPECT_EQ(k.coat_eval(flat.coat, kUp, wo, wi), k.ggx_eval(vec3(k.COAT_F0), 1.0f, 0.3f, kUp, wo, wi));
}

// Drawn on its own normal with the density coat_pdf gives: the estimate of its
// directional albedo from its own draws (a stratified grid, the frame of the shading
// normal handed in) is the albedo of an untilted coat seen at the same cosine.
TEST(CoatNormalLobes, TheCoatIsDrawnWithTheDensityItStates) {
    Kernel k = kernel_with_tables();
    const kernel::Material m = coat_only(0.09f);
    const auto albedo = [&](vec3 n, vec3 nc, vec3 wo) {
        const Kernel::Lobes l = k.material_lobes(m, n, nc, wo);
        const Kernel::Basis frame = k.basis_around(n);
        const int side = 256;
        double sum = 0.0;
        for (int i = 0; i < side; ++i) {
            for (int j = 0; j < side; ++j) {
                const vec3 wi = k.coat_sample(l.coat, frame, wo, 0u, (float(i) + 0.5f) / side, (float(j) + 0.5f) / side);
                const float cos_n = glm::dot(n, wi);
                const float pdf = k.coat_pdf(l.coat, frame, wo, wi, 0u);
                if (cos_n > 0.0f && pdf > 0.0f) sum += double(k.coat_eval(l.coat, n, wo, wi).x) * cos_n / pdf;
            }
        }
        return sum / (side * side);
    };
    const vec3 nc = glm::normalize(vec3(0.3f, 0.0f, 1.0f));
    const vec3 wo = glm::normalize(vec3(0.2f, 0.1f, 1.0f));
    const float c = glm::dot(nc, wo);
    const double tilted = albedo(kUp, nc, wo);
    const double untilted = albedo(kUp, kUp, vec3(std::sqrt(1.0f - c * c), 0.0f, c));
    EXPECT_NEAR(tilted, untilted, 2e-4);
    EXPECT_GT(tilted, 0.03);  // about its 0.04 reflectance
}

// A quad seen head-on from far away (wo within 0.003 of +z across it), lit by a
// directional light from (1, 0, 1) / sqrt 2, its material a rough coat (roughness 1)
// over nothing, in global mode with one bounce: each pixel is the coat's GGX value on
// its normal times that normal's cosine to the light, to the 1e-3 that wo's spread
// moves it.
std::string coat_scene(const std::string& maps) {
    return R"({
      "camera": { "eye": [0, 0, 300], "look_at": [0, 0, 0], "fov": 0.3, "width": 8, "height": 8 },
      "render": { "mode": "global", "spp": 4, "max_bounces": 1, "background": [0, 0, 0] },
      "lights": [ { "type": "directional", "direction": [-1, 0, -1], "intensity": 1 } ],
      "materials": { "m": { "base_color": [0, 0, 0], "metallic": 0, "roughness": 1, "specular_factor": 0,
                            "clearcoat": 1, "clearcoat_roughness": 1)" + maps + R"( } },
      "objects": [ { "type": "quad", "corner": [-1, -1, 0], "edge1": [2, 0, 0], "edge2": [0, 2, 0], "material": "m" } ]
    })";
}

std::filesystem::path tilted_map() {
    Image img(2, 2);
    for (std::uint32_t y = 0; y < 2; ++y) {
        for (std::uint32_t x = 0; x < 2; ++x) {
            img.pixel(x, y)[0] = 0.75f;  // (0.75, 0.5, 1) decodes to (0.5, 0, 1)
            img.pixel(x, y)[1] = 0.5f;
            img.pixel(x, y)[2] = 1.0f;
        }
    }
    const std::filesystem::path file = test::temp_dir("coat_normal") / "tilted.exr";
    write_image(img, file);
    return file;
}

float coat_value(vec3 n) {
    Kernel k;
    const vec3 light = glm::normalize(vec3(1.0f, 0.0f, 1.0f));
    return k.ggx_eval(vec3(k.COAT_F0), 1.0f, 1.0f, n, kUp, light).x * glm::dot(n, light);
}

TEST(CoatNormalRender, TheImageShowsTheCoatOnItsOwnNormal) {
    const std::string map = tilted_map().string();
    const vec3 tilted = glm::normalize(vec3(1.0f, 0.0f, 2.0f));
    struct Case {
        const char* name;
        std::string maps;
        float expected;
    };
    const Case cases[] = {
        {"the material's map", R"(, "normal_map": ")" + map + "\"", coat_value(kUp)},
        {"the coat's map", R"(, "clearcoat_normal_map": ")" + map + "\"", coat_value(tilted)},
        {"both", R"(, "normal_map": ")" + map + R"(", "clearcoat_normal_map": ")" + map + "\"", coat_value(tilted)},
    };
    EXPECT_GT(std::abs(coat_value(tilted) / coat_value(kUp) - 1.0f), 0.1f) << "the cases tell the normals apart";
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        const Scene scene = test::scene_from_text("coat_normal", coat_scene(c.maps));
        EXPECT_TRUE(flatten_scene(scene).features.has(Feature::HAS_NORMAL_MAPS));
        const Image cpu = test::render_cpu(scene).image;
        const Image gpu = test::render_vulkan(scene).image;
        for (std::uint32_t y = 1; y < 8; y += 3) {
            for (std::uint32_t x = 1; x < 8; x += 3) {
                EXPECT_NEAR(cpu.pixel(x, y)[0], c.expected, 1e-3f * c.expected) << x << "," << y;
            }
        }
        EXPECT_LE(test::max_abs_difference(cpu, gpu), 1e-6f * c.expected);
    }
}

TEST(CoatNormalScene, FieldsWithoutWhatTheyNeedAreRefused) {
    const std::string map = tilted_map().string();
    const auto scene = [&](const std::string& material) {
        return R"({ "camera": { "eye": [0, 0, 3], "look_at": [0, 0, 0] }, "materials": { "m": )" + material + R"( },
          "objects": [ { "type": "quad", "corner": [-1, -1, 0], "edge1": [2, 0, 0], "edge2": [0, 2, 0], "material": "m" } ] })";
    };
    test::expect_error_message(
        test::scene_error_of("coat_map_alone", scene(R"({ "base_color": [1, 1, 1], "clearcoat_normal_map": ")" + map + "\" }")),
        "", {"clearcoat_normal_map", "a clear coat normal map needs \"clearcoat\""});
    test::expect_error_message(
        test::scene_error_of("coat_scale_alone", scene(R"({ "base_color": [1, 1, 1], "clearcoat": 1, "clearcoat_normal_scale": 2 })")),
        "", {"clearcoat_normal_scale", "a normal scale needs a \"clearcoat_normal_map\""});
    const Scene scaled = test::scene_from_text(
        "coat_scale", scene(R"({ "base_color": [1, 1, 1], "clearcoat": 1, "clearcoat_normal_map": ")" + map +
                            R"(", "clearcoat_normal_scale": 0.5 })"));
    ASSERT_TRUE(scaled.materials[0].clearcoat_normal_map.has_value());
    EXPECT_EQ(scaled.textures[*scaled.materials[0].clearcoat_normal_map].normal_scale, 0.5);
}

}  // namespace
}  // namespace vkrt
