// Coverage (kernel/alpha.glsl): glTF's alphaMode on triangles and quads. A mask shows
// what lies behind its cut-out texels, exactly, to camera rays and to shadow rays (a
// cut-out leaf casts the shadow of its shape); a blend converges to the blend of the
// surface and what lies behind it, in what the camera sees and in the light it lets
// through; an emitter that is not opaque lights alike by next-event estimation and by
// the rays that meet it; the host tests coverage only where it can vary.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "flatten/coverage.hpp"
#include "flatten/flat_scene.hpp"
#include "image/png_encode.hpp"
#include "statistics.hpp"
#include "test_support.hpp"

namespace vkrt {
namespace {

// A 2 x 2 RGBA texture, white, whose alpha is `alpha[row][column]` (rows from the top,
// that is from v = 0). A quad's u runs along its first edge, v along its second.
std::filesystem::path checker_texture(const std::string& name, std::array<std::array<std::uint8_t, 2>, 2> alpha) {
    std::vector<std::uint8_t> rgba;
    for (int row = 0; row < 2; ++row) {
        for (int column = 0; column < 2; ++column) rgba.insert(rgba.end(), {255, 255, 255, alpha[row][column]});
    }
    const std::vector<std::uint8_t> png = encode_png_rgba8(2, 2, rgba);
    const std::filesystem::path file = test::temp_dir("alpha_" + name) / (name + ".png");
    std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
    return file;
}

// Cut out where column != row: texels (0, 0) and (1, 1) are opaque.
std::filesystem::path diagonal_texture(const std::string& name) {
    return checker_texture(name, {{{255, 0}, {0, 255}}});
}

double mean_of(const Image& image, std::uint32_t x0, std::uint32_t x1, std::uint32_t y0, std::uint32_t y1) {
    double sum = 0.0;
    for (std::uint32_t y = y0; y < y1; ++y) {
        for (std::uint32_t x = x0; x < x1; ++x) sum += image.pixel(x, y)[0];
    }
    return sum / double((x1 - x0) * (y1 - y0));
}

void expect_backends_agree(const Scene& scene, const RenderOutcome& cpu) {
    const RenderOutcome vulkan = test::render_vulkan(scene);
    EXPECT_LE(test::max_abs_difference(cpu.image, vulkan.image), 1e-6f);
}

// A quad that emits 1 and fills the view (test::view_quad_head_on), of material
// `material`, over a background of 0.2.
Scene emitting_quad(const std::string& name, const std::string& material, std::uint32_t spp) {
    Scene scene = test::scene_from_text(name, R"({
      "camera": { "eye": [0, 0, 3], "look_at": [0, 0, 0] },
      "render": { "mode": "global" },
      "materials": { "panel": )" + material + R"( },
      "objects": [ { "type": "quad", "corner": [-1, -1, 0], "edge1": [2, 0, 0], "edge2": [0, 2, 0], "material": "panel" } ]
    })");
    test::view_quad_head_on(scene, 16, spp, 0.2);
    return scene;
}

TEST(AlphaMask, CameraRaysSeeTheBackgroundThroughCutOutTexels) {
    const std::filesystem::path texture = diagonal_texture("camera");
    const Scene scene = emitting_quad("mask_camera", fmt::format(R"({{ "emission": [1, 1, 1], "texture": "{}",
        "alpha_mode": "mask", "alpha_cutoff": 0.5 }})", texture.string()), 4);
    ASSERT_TRUE(flatten_scene(scene).features.has(Feature::HAS_ALPHA));
    const RenderOutcome out = test::render_cpu(scene);
    // The view spans u and v from 0.1 to 0.9; the image's top is v = 1 (the quad's
    // second edge points up), so the image's top left quarter is texel (0, 1): cut out.
    for (std::uint32_t y : {2u, 5u, 10u, 13u}) {
        for (std::uint32_t x : {2u, 5u, 10u, 13u}) {
            const bool top = y < 8, left = x < 8;
            const float expected = top == left ? 0.2f : 1.0f;
            EXPECT_NEAR(out.image.pixel(x, y)[0], expected, 1e-6f) << x << "," << y;
        }
    }
    expect_backends_agree(scene, out);
}

// A leaf at height 1 over a floor, lit by a directional light that travels along
// (1, -1, 0): the leaf's texel (u, v) throws its shadow 1 along x. The camera looks
// straight down at the floor beyond the leaf's edge (x from 1 to 2), where the leaf's
// right half (x from 0 to 1) throws its shadow: its cut-out texel (1, 0) at z < 0, its
// opaque texel (1, 1) at z > 0.
Scene leaf_over_floor(const std::string& name, const std::string& leaf_material, bool leaf) {
    const std::string leaf_object =
        R"(, { "type": "quad", "corner": [-1, 1, -1], "edge1": [2, 0, 0], "edge2": [0, 0, 2], "material": "leaf" })";
    return test::scene_from_text(name, R"({
      "camera": { "eye": [1.5, 6, 0], "look_at": [1.5, 0, 0], "up": [0, 0, -1], "fov": 10, "width": 16, "height": 16 },
      "render": { "mode": "local", "background": [0, 0, 0], "jitter": false },
      "materials": { "floor": { "diffuse": [0.8, 0.8, 0.8] }, "leaf": )" + leaf_material + R"( },
      "lights": [ { "type": "directional", "direction": [1, -1, 0], "intensity": 2 } ],
      "objects": [ { "type": "quad", "corner": [-3, 0, -3], "edge1": [0, 0, 6], "edge2": [6, 0, 0], "material": "floor" })" +
                                          (leaf ? leaf_object : std::string()) + "]}");
}

TEST(AlphaMask, ShadowRaysPassThroughCutOutTexels) {
    const std::filesystem::path texture = diagonal_texture("shadow");
    const std::string material =
        fmt::format(R"({{ "diffuse": [0.5, 0.5, 0.5], "texture": "{}", "alpha_mode": "mask" }})", texture.string());
    const Scene bare = leaf_over_floor("mask_bare", material, false);
    const Scene scene = leaf_over_floor("mask_leaf", material, true);
    const RenderOutcome lit = test::render_cpu(bare);
    const RenderOutcome out = test::render_cpu(scene);
    // The image's top is z < 0 (up is -z): lit there, in the leaf's shadow below.
    for (std::uint32_t y : {1u, 4u, 6u, 9u, 11u, 14u}) {
        for (std::uint32_t x = 2; x < 14; ++x) {
            const float expected = y < 8 ? lit.image.pixel(x, y)[0] : 0.0f;
            EXPECT_EQ(out.image.pixel(x, y)[0], expected) << x << "," << y;
        }
    }
    EXPECT_GT(lit.image.pixel(8, 4)[0], 0.1f);
    expect_backends_agree(scene, out);
}

// Without the texture, an opaque leaf: the same floor is in shadow at every z.
TEST(AlphaMask, AnOpaqueLeafShadowsEverything) {
    const Scene scene = leaf_over_floor("opaque_leaf", R"({ "diffuse": [0.5, 0.5, 0.5] })", true);
    const RenderOutcome out = test::render_cpu(scene);
    for (std::uint32_t y : {1u, 14u}) EXPECT_EQ(out.image.pixel(8, y)[0], 0.0f);
}

// Each sample sees the panel (1) with probability 0.3, else the background (0.2): the
// image converges to 0.3 + 0.7 * 0.2 = 0.44. 16 x 16 pixels of 64 samples: a
// standard error of 0.8 sqrt(0.21 / 16384) = 0.0029 on the image's mean.
TEST(AlphaBlend, ConvergesToTheBlendOfSurfaceAndBackground) {
    const Scene scene = emitting_quad("blend_camera", R"({ "emission": [1, 1, 1], "alpha_mode": "blend", "alpha": 0.3 })", 64);
    const RenderOutcome out = test::render_cpu(scene);
    const double mean = mean_of(out.image, 0, 16, 0, 16);
    const double se = 0.8 * std::sqrt(0.21 / (16.0 * 16.0 * 64.0));
    const test::ZTestResult z = test::z_test(mean, se, 0.44);
    EXPECT_GT(z.p_value, 1e-4) << z << ", mean " << mean;
    // Every sample is one or the other: each pixel lies between them, and no pixel is
    // all one (0.3^64 and 0.7^64 are far below 1 in 256).
    for (std::uint32_t y = 0; y < 16; ++y) {
        for (std::uint32_t x = 0; x < 16; ++x) {
            EXPECT_GT(out.image.pixel(x, y)[0], 0.2f);
            EXPECT_LT(out.image.pixel(x, y)[0], 1.0f);
        }
    }
    expect_backends_agree(scene, out);
}

// A leaf of opacity 0.25: each shadow ray gets through with probability 0.75, so the
// floor converges to 0.75 of its light. 256 samples a pixel (aa 16), 12 x 12 pixels.
TEST(AlphaBlend, LetsThroughTheTransmittedFractionOfTheLight) {
    const std::string material = R"({ "diffuse": [0.5, 0.5, 0.5], "alpha_mode": "blend", "alpha": 0.25 })";
    Scene bare = leaf_over_floor("blend_bare", material, false);
    Scene scene = leaf_over_floor("blend_leaf", material, true);
    for (Scene* s : {&bare, &scene}) s->render.aa = 16;
    const double lit = mean_of(test::render_cpu(bare).image, 2, 14, 2, 14);
    const RenderOutcome out = test::render_cpu(scene);
    const double mean = mean_of(out.image, 2, 14, 2, 14);
    const double se = lit * std::sqrt(0.25 * 0.75 / (144.0 * 256.0));
    const test::ZTestResult z = test::z_test(mean, se, 0.75 * lit);
    EXPECT_GT(z.p_value, 1e-4) << z << ", mean " << mean << " of " << lit;
    expect_backends_agree(scene, out);
}

// A masked emitter (half its texels cut out) and a half-transparent one above a floor:
// next-event estimation weighs each point it draws by its coverage, and rays that
// meet the emitters see them with that probability. The floor's mean over 8 seeds by
// next-event estimation (with MIS) and by BSDF sampling alone agree within their
// noise, and both are well below the opaque emitters' (the camera, above them, sees
// more of the floor through them: not half).
TEST(AlphaEmitter, NextEventEstimationAgreesWithTheRaysThatMeetIt) {
    const std::filesystem::path texture = diagonal_texture("emitter");
    const auto floor_mean = [&](bool nee, const std::string& coverage, std::uint32_t seed) {
        Scene scene = test::scene_from_text("emitter", fmt::format(R"({{
          "camera": {{ "eye": [0, 6, 0], "look_at": [0, 0, 0], "up": [0, 0, -1], "fov": 40, "width": 24, "height": 24 }},
          "render": {{ "mode": "global", "spp": 64, "background": [0, 0, 0], "nee": {} }},
          "materials": {{ "floor": {{ "diffuse": [0.8, 0.8, 0.8] }},
                          "mask": {{ "emission": [4, 4, 4], "texture": "{}" {} }},
                          "veil": {{ "emission": [4, 4, 4] {} }} }},
          "objects": [ {{ "type": "quad", "corner": [-3, 0, -3], "edge1": [0, 0, 6], "edge2": [6, 0, 0], "material": "floor" }},
                       {{ "type": "quad", "corner": [-1.5, 0.6, -0.5], "edge1": [1, 0, 0], "edge2": [0, 0, 1], "material": "mask" }},
                       {{ "type": "quad", "corner": [0.5, 0.6, -0.5], "edge1": [1, 0, 0], "edge2": [0, 0, 1], "material": "veil" }} ]
        }})", nee ? "true" : "false", texture.string(), coverage.empty() ? "" : R"(, "alpha_mode": "mask")",
                                                      coverage.empty() ? "" : R"(, "alpha_mode": "blend", "alpha": 0.5)"));
        scene.render.seed = seed;
        return mean_of(test::render_cpu(scene).image, 0, 24, 0, 24);
    };
    const auto over_seeds = [&](bool nee, const std::string& coverage) {
        std::vector<double> means;
        for (std::uint32_t seed = 1; seed <= 8; ++seed) means.push_back(floor_mean(nee, coverage, seed));
        double m = 0.0, v = 0.0;
        for (double x : means) m += x / 8.0;
        for (double x : means) v += (x - m) * (x - m) / 7.0;
        return std::array<double, 2>{m, std::sqrt(v / 8.0)};
    };
    const auto [nee, nee_se] = over_seeds(true, "tested");
    const auto [bsdf, bsdf_se] = over_seeds(false, "tested");
    const test::ZTestResult z = test::z_test(nee - bsdf, std::hypot(nee_se, bsdf_se), 0.0);
    EXPECT_GT(z.p_value, 1e-4) << z << ": by next-event estimation " << nee << " +- " << nee_se
                               << ", by BSDF sampling " << bsdf << " +- " << bsdf_se;
    const double opaque = over_seeds(true, "")[0];
    EXPECT_LT(nee, 0.8 * opaque) << "opaque emitters give " << opaque;
    EXPECT_GT(nee, 0.3 * opaque) << "opaque emitters give " << opaque;
}

// Coverage is tested only where it can vary or cut: a blend of alpha 1 without a
// texture, or with a texture whose every texel is opaque, is opaque; so is a mask
// whose alpha reaches its cutoff. A mask below its cutoff hides the surface.
TEST(AlphaFeature, OnlyWhereCoverageCanCut) {
    const std::filesystem::path opaque = checker_texture("opaque", {{{255, 255}, {255, 255}}});
    const std::filesystem::path cut = diagonal_texture("feature");
    const auto tested = [](const std::string& material) {
        const Scene scene = emitting_quad("feature", material, 1);
        return flatten_scene(scene).features.has(Feature::HAS_ALPHA);
    };
    EXPECT_FALSE(tested(R"({ "diffuse": [1, 1, 1] })"));
    EXPECT_FALSE(tested(R"({ "diffuse": [1, 1, 1], "alpha_mode": "blend" })"));
    EXPECT_FALSE(tested(fmt::format(R"({{ "diffuse": [1, 1, 1], "alpha_mode": "blend", "texture": "{}" }})", opaque.string())));
    EXPECT_FALSE(tested(R"({ "diffuse": [1, 1, 1], "alpha_mode": "mask", "alpha": 0.6 })"));
    EXPECT_TRUE(tested(R"({ "diffuse": [1, 1, 1], "alpha_mode": "mask", "alpha": 0.4 })"));
    EXPECT_TRUE(tested(R"({ "diffuse": [1, 1, 1], "alpha_mode": "blend", "alpha": 0.99 })"));
    EXPECT_TRUE(tested(fmt::format(R"({{ "diffuse": [1, 1, 1], "alpha_mode": "mask", "texture": "{}" }})", cut.string())));
    EXPECT_FALSE(tested(fmt::format(R"({{ "diffuse": [1, 1, 1], "texture": "{}" }})", cut.string())));

    // A mask below its cutoff: nothing of the panel is seen.
    const Scene hidden = emitting_quad("hidden", R"({ "emission": [1, 1, 1], "alpha_mode": "mask", "alpha": 0.4 })", 1);
    const RenderOutcome out = test::render_cpu(hidden);
    EXPECT_NEAR(out.image.pixel(8, 8)[0], 0.2f, 1e-6f);
}

}  // namespace
}  // namespace vkrt
