// Textured emitters weighed by their own footprint (host/flatten/emission_footprint.cpp,
// kernel/shapes/triangle.glsl triangle_emitter_weight): the texel intervals a footprint
// reaches under each wrap mode; the mean emission over a footprint, exact on small
// textures; only triangles over emitting texels become emitters; and next-event
// estimation over such a mesh stays unbiased: it agrees with BSDF sampling alone on
// a mesh whose texture is black but for two texels, one of them reached by its
// neighbours' triangles only through the bilinear filter.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <glm/glm.hpp>

#include "cpu/cpu_backend.hpp"
#include "flatten/emission_footprint.hpp"
#include "flatten/flat_scene.hpp"
#include "image/image.hpp"
#include "kernel/kernel.hpp"
#include "scene/load_scene.hpp"
#include "test_support.hpp"

namespace vkrt {
namespace {

using Intervals = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

Intervals intervals(std::int64_t lo, std::int64_t hi, std::uint32_t n, Wrap mode) {
    Intervals out;
    for (const TexelInterval& i : wrapped_intervals(lo, hi, n, mode)) out.emplace_back(i.first, i.last);
    return out;
}

TEST(EmissionFootprint, IntervalsFollowTheWrapMode) {
    // Clamp: one interval, the edge texel for everything beyond.
    EXPECT_EQ(intervals(-3, 2, 8, Wrap::Clamp), (Intervals{{0, 2}}));
    EXPECT_EQ(intervals(6, 40, 8, Wrap::Clamp), (Intervals{{6, 7}}));
    EXPECT_EQ(intervals(-9, -2, 8, Wrap::Clamp), (Intervals{{0, 0}}));
    // Repeat: wrapped into one or two pieces; a whole period or more is the axis.
    EXPECT_EQ(intervals(2, 5, 8, Wrap::Repeat), (Intervals{{2, 5}}));
    EXPECT_EQ(intervals(6, 9, 8, Wrap::Repeat), (Intervals{{6, 7}, {0, 1}}));
    EXPECT_EQ(intervals(-2, 1, 8, Wrap::Repeat), (Intervals{{6, 7}, {0, 1}}));
    EXPECT_EQ(intervals(-17, -14, 8, Wrap::Repeat), (Intervals{{7, 7}, {0, 2}}));
    EXPECT_EQ(intervals(3, 10, 8, Wrap::Repeat), (Intervals{{0, 7}}));
    // Mirror: odd periods reflected; 2n or more is the axis.
    EXPECT_EQ(intervals(9, 10, 8, Wrap::Mirror), (Intervals{{5, 6}}));
    EXPECT_EQ(intervals(6, 9, 8, Wrap::Mirror), (Intervals{{6, 7}, {6, 7}}));
    EXPECT_EQ(intervals(-2, 0, 8, Wrap::Mirror), (Intervals{{0, 1}, {0, 0}}));
    EXPECT_EQ(intervals(-20, -6, 8, Wrap::Mirror), (Intervals{{0, 3}, {0, 7}, {5, 7}}));
    EXPECT_EQ(intervals(0, 15, 8, Wrap::Mirror), (Intervals{{0, 7}}));
}

// An 8 x 8 linear texture, black but for texel (3, 3) of 0.75 and texel (6, 1) of
// 0.25 (channels equal; exact in the half floats of the file).
std::filesystem::path sparse_texture(const std::string& name) {
    Image img(8, 8);
    for (int c = 0; c < 3; ++c) {
        img.pixel(3, 3)[c] = 0.75f;
        img.pixel(6, 1)[c] = 0.25f;
    }
    const std::filesystem::path file = test::temp_dir("emission_footprint_" + name) / (name + ".exr");
    write_image(img, file);
    return file;
}

Scene one_textured_material(const std::string& name) {
    return test::scene_from_text(name, R"({
      "camera": { "eye": [0, 0, 3], "look_at": [0, 0, 0] },
      "render": { "mode": "global" },
      "materials": { "lamp": { "emission": [2, 1, 3], "emission_texture": ")" + sparse_texture(name).string() + R"(" } },
      "objects": [ { "type": "quad", "corner": [-1, -1, 0], "edge1": [2, 0, 0], "edge2": [0, 2, 0], "material": "lamp" } ]
    })");
}

TEST(EmissionFootprint, TheMeanIsOverTheTexelsTheFilterReaches) {
    const Scene scene = one_textured_material("mean");
    EmissionFootprints footprints(scene);
    const Material& m = scene.materials.at(0);
    // Emission (2, 1, 3) has mean 2: texel (3, 3) weighs 2 * 0.75 = 1.5, (6, 1) 0.5.
    const auto at = [&](std::vector<glm::dvec2> uv) { return footprints.mean_emission(m, uv, m.uv_transform); };
    // A triangle in texel (0, 6)'s square: texel positions x = 8u - 0.5 from -0.42 to
    // -0.02, whose floors and the texels after them (-1, 0), widened by one each
    // side, repeat as 6, 7, 0, 1; rows 4 to 7 likewise. No lit texel: 0.
    EXPECT_EQ(at({{0.01, 0.76}, {0.06, 0.76}, {0.01, 0.81}}), 0.0);
    // In texel (2, 3)'s square: columns 0 to 3 and rows 1 to 4 reach (3, 3), one of 16.
    const double one_of_16 = 1.5 / 16.0;
    EXPECT_NEAR(at({{0.26, 0.39}, {0.30, 0.39}, {0.26, 0.42}}), one_of_16, 1e-6 * one_of_16);
    // The whole texture: the mean over 64 texels of 1.5 + 0.5, each lit texel
    // rounded up by less than a unit of the table (the brightest, 1.5, / 2^11).
    const double units = 2.0 * 1.5 / 2048.0 / 64.0;
    EXPECT_NEAR(at({{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}}), 2.0 / 64.0, units);
    // Coordinates that are not finite read anywhere: the whole texture too.
    EXPECT_NEAR(at({{NAN, 0.0}, {1.0, 0.0}, {0.0, 1.0}}), 2.0 / 64.0, units);
    // Far beyond [0, 1] with repeat: the same texels as inside.
    EXPECT_NEAR(at({{1000.26, -999.61}, {1000.30, -999.61}, {1000.26, -999.58}}), one_of_16, 1e-6 * one_of_16);
}

TEST(EmissionFootprint, TheMaterialsTransformMovesTheFootprint) {
    Scene scene = one_textured_material("transform");
    Material& m = scene.materials.at(0);
    // A triangle in texel (6, 4)'s square reaches columns 4 to 7 and rows 2 to 5: no
    // lit texel. Offset by (-0.5, 0), it reads around (2, 4), which reaches (3, 3).
    const std::vector<glm::dvec2> uv{{0.76, 0.51}, {0.80, 0.51}, {0.76, 0.55}};
    EXPECT_EQ(EmissionFootprints(scene).mean_emission(m, uv, m.uv_transform), 0.0);
    m.uv_transform = texture_transform(-0.5, 0.0, 0.0, 1.0, 1.0);
    EXPECT_NEAR(EmissionFootprints(scene).mean_emission(m, uv, m.uv_transform), 1.5 / 16.0, 1e-7);
}

// A quad of emission (1, 1, 1) times the texture `file`.
Scene white_lamp(const std::filesystem::path& file) {
    return test::scene_from_text(file.stem().string(), R"({
      "camera": { "eye": [0, 0, 3], "look_at": [0, 0, 0] },
      "materials": { "lamp": { "emission": [1, 1, 1], "emission_texture": ")" + file.string() + R"(" } },
      "objects": [ { "type": "quad", "corner": [-1, -1, 0], "edge1": [2, 0, 0], "edge2": [0, 2, 0], "material": "lamp" } ]
    })");
}

// An 8-bit texture larger than the table's pieces (2100 x 1100 texels, white but
// for a black block of 1000 x 500 at the top left), on a quad of emission (1, 1, 1):
// each white texel counts kUnits exactly, so the whole texture's sum, far past
// 2^32 units, shows whether the pieces add up; the black block sums to 0 exactly.
TEST(EmissionFootprint, LargeEightBitTexturesSumExactlyPieceByPiece) {
    constexpr int w = 2100, h = 1100, bw = 1000, bh = 500;
    Image img(w, h);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const float v = x < bw && y < bh ? 0.0f : 1.0f;
            for (int c = 0; c < 3; ++c) img.pixel(x, y)[c] = v;
        }
    }
    const std::filesystem::path file = test::temp_dir("emission_footprint_large") / "large.png";
    write_image(img, file);
    const Scene scene = white_lamp(file);
    ASSERT_EQ(scene.textures.at(0).format, TexelFormat::Rgba8);
    EmissionFootprints footprints(scene);
    const Material& m = scene.materials.at(0);
    const auto at = [&](std::vector<glm::dvec2> uv) { return footprints.mean_emission(m, uv, m.uv_transform); };
    const double white = double(w) * h - double(bw) * bh;
    EXPECT_DOUBLE_EQ(at({{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}}), white / (double(w) * h));
    // Well inside the black block (texels 100 to 400 across, 100 to 300 down).
    EXPECT_EQ(at({{100.0 / w, 100.0 / h}, {400.0 / w, 100.0 / h}, {100.0 / w, 300.0 / h}}), 0.0);
    // Across its right edge: texel positions 897.5 to 1099.5 reach columns 896 to
    // 1101, 102 of them lit; rows 98 to 301.
    const double reached = 206.0 * 204.0, lit = 102.0 * 204.0;
    EXPECT_DOUBLE_EQ(at({{898.0 / w, 100.0 / h}, {1100.0 / w, 100.0 / h}, {898.0 / w, 300.0 / h}}), lit / reached);
}

// A dim 8-bit emission texture (linear values near 0.003 and 0.0015) keeps its
// weights' precision: the table's unit follows the brightest byte present, not the
// brightest a byte could hold, so rounding each texel up costs under 1/2048 of it.
TEST(EmissionFootprint, DimEightBitTexturesKeepTheirPrecision) {
    Image img(4, 4);
    for (int y = 0; y < 4; ++y) {
        for (int x = 0; x < 4; ++x) {
            for (int c = 0; c < 3; ++c) img.pixel(x, y)[c] = x == 0 && y == 0 ? 0.0015f : 0.003f;
        }
    }
    const std::filesystem::path file = test::temp_dir("emission_footprint_dim") / "dim.png";
    write_image(img, file);
    const Scene scene = white_lamp(file);
    const TextureImage& t = scene.textures.at(0);
    ASSERT_EQ(t.format, TexelFormat::Rgba8);
    double expected = 0.0;
    for (std::size_t i = 0; i < t.texel_count(); ++i) {
        const glm::vec4 c = texel_value(t, scene.texels.words(), i);
        expected += (double(c.r) + double(c.g) + double(c.b)) / 3.0 / double(t.texel_count());
    }
    ASSERT_GT(expected, 0.001);
    ASSERT_LT(expected, 0.01);
    const double mean = EmissionFootprints(scene).mean_emission(scene.materials.at(0), {{{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}}},
                                                           scene.materials.at(0).uv_transform);
    EXPECT_GE(mean, expected);
    EXPECT_LT(mean, expected * (1.0 + 1.0 / 1024.0));
}

// An emitter of 16 x 16 cells, two triangles each, at z = 1 facing down, over
// [-4, 4]^2, with texture coordinates over [0, 1]^2: each cell covers a quarter of
// a texel, and the filter reaches a lit texel from the cells within about a texel.
std::filesystem::path cell_mesh(const std::filesystem::path& dir) {
    std::string obj;
    for (int j = 0; j <= 16; ++j) {
        for (int i = 0; i <= 16; ++i) {
            obj += fmt::format("v {} {} 1\nvt {} {}\n", i / 2.0 - 4.0, j / 2.0 - 4.0, i / 16.0, 1.0 - j / 16.0);
        }
    }
    for (int j = 0; j < 16; ++j) {
        for (int i = 0; i < 16; ++i) {
            const int a = j * 17 + i + 1, b = a + 1, c = a + 17, d = c + 1;
            // Clockwise seen from above: the front faces look down, at the patch.
            obj += fmt::format("f {0}/{0} {2}/{2} {1}/{1}\nf {1}/{1} {2}/{2} {3}/{3}\n", a, b, c, d);
        }
    }
    const std::filesystem::path file = dir / "cells.obj";
    std::ofstream(file) << obj;
    return file;
}

// Per channel, the mean over the image and its standard error, from the reference
// kernel's samples.
std::pair<glm::dvec3, glm::dvec3> channel_means(const Scene& scene) {
    const FlatScene flat = flatten_scene(scene);
    kernel::Kernel k = make_kernel(flat);
    glm::dvec3 sum(0.0), variance(0.0);
    const double n = flat.samples_per_pixel;
    const double pixels = double(scene.camera.width) * scene.camera.height;
    for (std::uint32_t y = 0; y < scene.camera.height; ++y) {
        for (std::uint32_t x = 0; x < scene.camera.width; ++x) {
            glm::dvec3 s(0.0), s2(0.0);
            for (std::uint32_t i = 0; i < flat.samples_per_pixel; ++i) {
                const glm::dvec3 r(k.render_sample(x, y, i).radiance);
                s += r;
                s2 += r * r;
            }
            const glm::dvec3 mean = s / n;
            sum += mean;
            variance += glm::max(glm::dvec3(0.0), s2 / n - mean * mean) / (n - 1.0);
        }
    }
    return {sum / pixels, glm::sqrt(variance) / pixels};
}

TEST(EmissionFootprintRender, OnlyLitFootprintsAreLightsAndNeeStaysUnbiased) {
    const std::filesystem::path dir = test::temp_dir("emission_footprint_mesh");
    const std::filesystem::path texture = sparse_texture("mesh");
    Scene scene = test::scene_from_text("footprint_mesh", R"({
      "camera": { "eye": [0, 0, 0.5], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 8, "width": 8, "height": 8 },
      "render": { "mode": "global", "spp": 1024, "max_bounces": 1, "background": [0, 0, 0] },
      "materials": { "lamp": { "emission": [1, 1, 1], "emission_texture": ")" + texture.string() + R"(" },
                     "patch": { "diffuse": [0.5, 0.5, 0.5] } },
      "objects": [ { "type": "mesh", "file": ")" + cell_mesh(dir).string() + R"(", "material": "lamp" },
                   { "type": "quad", "corner": [-0.05, -0.05, 0], "edge1": [0.1, 0, 0], "edge2": [0, 0.1, 0], "material": "patch" } ]
    })");
    ASSERT_EQ(scene.triangles.size(), 512u + 1u);
    const FlatScene flat = flatten_scene(scene);
    // Each lit texel is reached from 9 x 9 cells around it (texel (6, 1)'s wrapping
    // around the edges), 15 of them shared: 147 cells, 294 of the mesh's 512 triangles.
    EXPECT_EQ(flat.emitters.size(), 294u);
    scene.render.nee = true;
    const auto [nee, nee_se] = channel_means(scene);
    scene.render.nee = false;
    const auto [bsdf, bsdf_se] = channel_means(scene);
    for (int c = 0; c < 3; ++c) {
        const double se = std::sqrt(nee_se[c] * nee_se[c] + bsdf_se[c] * bsdf_se[c]);
        std::printf("channel %d: nee %.6f +- %.6f, bsdf %.6f +- %.6f\n", c, nee[c], nee_se[c], bsdf[c], bsdf_se[c]);
        EXPECT_GT(nee[c], 0.0);
        EXPECT_LT(std::abs(nee[c] - bsdf[c]), 4.0 * se) << "channel " << c;
    }
}

}  // namespace
}  // namespace vkrt
