// The render passes (HAS_PASSES: kernel/sums.glsl's add_first_hit, render/pixel_sums.hpp's
// pass_means): the first hit's base colour, shading normal and distance, exact
// where the scene makes them so, on both backends and in both modes; split renders
// that add up bit for bit; pixels that spread over slabs; none kept where the
// render does not ask; and `vkrt render --passes`, its layers and its refusals.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "cpu/cpu_backend.hpp"
#include "flatten/flat_scene.hpp"
#include "gpu/vulkan_backend.hpp"
#include "image/image_files.hpp"
#include "render/accumulate.hpp"
#include "render/pixel_sums.hpp"
#include "render/render.hpp"
#include "test_support.hpp"

namespace vkrt {
namespace {

// A quad in the plane z = 0 facing the eye at z = 5, its colour (0.25, 0.5, 0.75),
// under a field of view of 10 degrees: every eye ray of a pixel that sees the quad
// hits it at a distance between 5 and 5 / cos(7.1 degrees) < 5.04, where the normal
// is (0, 0, 1). `offset` moves the quad along x: by 5, its edge runs through the
// centre of a one-pixel image; by 20, the pixel sees only the sky.
std::string facing_quad(const std::string& mode, double offset, std::uint32_t width, std::uint32_t spp,
                        std::uint32_t height = 1) {
    return R"({
      "camera": { "eye": [0, 0, 5], "look_at": [0, 0, 0], "fov": 10, "width": )" +
           std::to_string(width) + R"(, "height": )" + std::to_string(height) + R"( },
      "render": { "mode": ")" + mode + R"(", "spp": )" + std::to_string(spp) + R"(, "sampler": "hash",
                  "background": [0.5, 0.5, 0.5] },
      "materials": { "paint": { "diffuse": [0.25, 0.5, 0.75] } },
      "lights": [ { "type": "point", "position": [0, 3, 4], "color": [1, 1, 1] } ],
      "objects": [ { "type": "quad", "corner": [)" +
           std::to_string(offset - 5.0) + R"(, -5, 0], "edge1": [10, 0, 0], "edge2": [0, 10, 0],
                     "material": "paint" } ]
    })";
}

Scene with_passes(Scene scene) {
    scene.render.passes = true;
    return scene;
}

PassMeans means_of(const RenderResult& r, std::size_t pixel) {
    const kernel::Counters& c = r.counters.at(pixel);
    return pass_means(r.passes.at(pixel), c.rays[kernel::RAYS_EYE], c.tree[kernel::TREE_EYE_HITS]);
}

// Every sample hits the quad: the colour and the normal are sums of exactly
// representable values, so their means are exact; the distance lies between the
// nearest and the farthest ray's. Both backends keep the very same words.
TEST(Passes, ExactOnAFacingQuadInBothModesAndOnBothBackends) {
    for (const std::string mode : {"local", "global"}) {
        SCOPED_TRACE(mode);
        const Scene scene = with_passes(test::scene_from_text("quad_" + mode, facing_quad(mode, 0.0, 1, 16)));
        const RenderOutcome cpu = test::render_cpu(scene);
        ASSERT_EQ(cpu.sums.passes.size(), 1u);
        const PassMeans m = means_of(cpu.sums, 0);
        EXPECT_EQ(m.albedo, glm::dvec3(0.25, 0.5, 0.75));
        EXPECT_EQ(m.normal, glm::dvec3(0.0, 0.0, 1.0));
        EXPECT_GE(m.depth, 5.0);
        EXPECT_LT(m.depth, 5.04);
        const RenderOutcome gpu = test::render_vulkan(scene);
        ASSERT_EQ(gpu.sums.passes.size(), 1u);
        EXPECT_EQ(gpu.sums.passes[0], cpu.sums.passes[0]);
        EXPECT_EQ(gpu.sums.counters[0].tree[kernel::TREE_EYE_HITS], 16u);
    }
}

// The quad's edge through the pixel's centre: the colour and the normal are the
// quad's times the share of samples that hit it, the distance the hits' alone.
// The sky alone: black, a zero normal, an infinite distance.
TEST(Passes, MissesAddNothingAndTheDistanceAveragesTheHits) {
    const Scene edge = with_passes(test::scene_from_text("quad_edge", facing_quad("global", 5.0, 1, 64)));
    const RenderOutcome r = test::render_cpu(edge);
    const std::uint32_t hits = r.sums.counters[0].tree[kernel::TREE_EYE_HITS];
    ASSERT_GT(hits, 16u);
    ASSERT_LT(hits, 48u);
    const double share = double(hits) / 64.0;
    const PassMeans m = means_of(r.sums, 0);
    EXPECT_DOUBLE_EQ(m.albedo.r, 0.25 * share);
    EXPECT_DOUBLE_EQ(m.albedo.b, 0.75 * share);
    EXPECT_DOUBLE_EQ(m.normal.z, share);
    EXPECT_EQ(m.normal.x, 0.0);
    EXPECT_GE(m.depth, 5.0);
    EXPECT_LT(m.depth, 5.04);

    const RenderOutcome sky = test::render_cpu(with_passes(test::scene_from_text("quad_sky", facing_quad("global", 20.0, 1, 8))));
    const PassMeans none = means_of(sky.sums, 0);
    EXPECT_EQ(none.albedo, glm::dvec3(0.0));
    EXPECT_EQ(none.normal, glm::dvec3(0.0));
    EXPECT_EQ(none.depth, std::numeric_limits<double>::infinity());
}

// Not asked for, no passes are kept, and the radiance is the same.
TEST(Passes, NoneKeptUnlessAsked) {
    const Scene plain = test::scene_from_text("quad_plain", facing_quad("global", 0.0, 1, 8));
    const RenderOutcome without = test::render_cpu(plain);
    EXPECT_TRUE(without.sums.passes.empty());
    EXPECT_TRUE(test::render_vulkan(plain).sums.passes.empty());
    const RenderOutcome with = test::render_cpu(with_passes(plain));
    EXPECT_EQ(with.sums.sums.at(0), without.sums.sums.at(0));
}

// Textures, normal maps, emission: a Blender-exported file, whose passes add up
// over a split of its samples bit for bit on either backend, and agree between the
// backends to float rounding.
TEST(Passes, TexturedFileSplitsAndAgreesAcrossBackends) {
    const Scene scene =
        with_passes(test::load_at_size(test::source_dir() / "scenes" / "gltf" / "corpus" / "sign.glb", 80, 60));
    const FlatScene flat = flatten_scene(scene);
    ASSERT_TRUE(flat.features.has(Feature::HAS_TEXTURES));
    std::vector<RenderResult> wholes;
    for (const std::shared_ptr<Backend>& backend :
         {std::shared_ptr<Backend>(make_cpu_backend()), std::shared_ptr<Backend>(make_vulkan_backend(VulkanOptions{"", true}))}) {
        SCOPED_TRACE(backend->name());
        const RenderResult whole = backend->render(flat, SampleRange{0, 6});
        RenderResult split;
        accumulate(split, backend->render(flat, SampleRange{0, 2}));
        accumulate(split, backend->render(flat, SampleRange{2, 4}));
        ASSERT_EQ(whole.passes.size(), flat.pixel_count());
        for (std::size_t p = 0; p < whole.passes.size(); ++p) ASSERT_EQ(split.passes[p], whole.passes[p]) << "pixel " << p;
        wholes.push_back(whole);
    }
    std::size_t hit = 0, varied = 0;
    for (std::size_t p = 0; p < flat.pixel_count(); ++p) {
        const PassMeans c = means_of(wholes[0], p), v = means_of(wholes[1], p);
        ASSERT_EQ(wholes[1].counters[p].tree[kernel::TREE_EYE_HITS], wholes[0].counters[p].tree[kernel::TREE_EYE_HITS]);
        for (glm::length_t k = 0; k < 3; ++k) {
            ASSERT_NEAR(v.albedo[k], c.albedo[k], 1e-5) << "pixel " << p;
            ASSERT_NEAR(v.normal[k], c.normal[k], 1e-5) << "pixel " << p;
        }
        if (std::isfinite(c.depth)) {
            ++hit;
            ASSERT_NEAR(v.depth, c.depth, 1e-5 * c.depth) << "pixel " << p;
        }
        if (std::abs(c.albedo.r - c.albedo.g) > 0.05) ++varied;
    }
    // The bricks' texture shows in the albedo: red and green differ on its pixels.
    EXPECT_GT(hit, 1000u);
    EXPECT_GT(varied, 100u);
}

// Under the specification's minimum limits the pixel buffer holds 16 rows of 200
// pixels with passes (65,536 texels of PIXEL_TEXELS + PASS_TEXELS = 17 a pixel; 32
// rows without), so a 200 x 48 image takes three slabs; its passes are the
// reference's bit for bit.
TEST(Passes, SlabsOfLongerPixels) {
    const Scene scene = with_passes(test::scene_from_text("quad_slabs", facing_quad("global", 2.0, 200, 2, 48)));
    VulkanOptions minimum;
    minimum.profile = "minimum";
    const RenderOutcome slabs = test::render_vulkan_with(scene, minimum);
    EXPECT_EQ(slabs.stats.slabs, 3u) << slabs.stats.data_paths;
    const RenderOutcome cpu = test::render_cpu(scene);
    ASSERT_EQ(slabs.sums.passes.size(), cpu.sums.passes.size());
    for (std::size_t p = 0; p < cpu.sums.passes.size(); ++p) {
        ASSERT_EQ(slabs.sums.passes[p], cpu.sums.passes[p]) << "pixel " << p;
    }
}

TEST(Passes, RenderWritesTheLayersCompositorsRead) {
    const std::filesystem::path dir = test::temp_dir("passes_cli");
    const std::string scene_file = (dir / "quad.json").string();
    {
        std::ofstream(scene_file) << facing_quad("global", 0.0, 2, 8);
    }
    const std::string out = (dir / "quad.exr").string();
    const test::ProgramRun run = test::run_vkrt("render " + test::shell_quote(scene_file) +
                                                    " --backend cpu --passes depth,albedo,normal --variance -q -o " +
                                                    test::shell_quote(out),
                                                dir);
    ASSERT_EQ(run.code, 0) << run.stderr_text;
    std::string error;
    const std::unique_ptr<ImageFileReader> in = image_files().open(out, error);
    ASSERT_TRUE(in) << error;
    std::vector<std::string> channels = in->spec().channels;
    std::sort(channels.begin(), channels.end());
    const std::vector<std::string> expected = {"B",   "G",   "N.X",        "N.Y",        "N.Z",        "R",
                                               "Z",   "albedo.B", "albedo.G", "albedo.R", "variance.B", "variance.G",
                                               "variance.R"};
    EXPECT_EQ(channels, expected);
    const std::size_t n = in->spec().channels.size();
    std::vector<float> values(n * 2);
    ASSERT_TRUE(in->read_floats(values.data()));
    const auto value = [&](const std::string& name) {
        const auto& c = in->spec().channels;
        return values[std::size_t(std::find(c.begin(), c.end(), name) - c.begin())];
    };
    EXPECT_EQ(value("albedo.G"), 0.5f);
    EXPECT_EQ(value("N.Z"), 1.0f);
    EXPECT_EQ(value("N.X"), 0.0f);
    // Two pixels side by side: rays up to 10 degrees off the axis.
    EXPECT_GE(value("Z"), 5.0f);
    EXPECT_LT(value("Z"), 5.08f);
}

TEST(Passes, RenderRefusesWhatCannotCarryThem) {
    const std::filesystem::path dir = test::temp_dir("passes_refusals");
    const std::string scene = (dir / "quad.json").string();
    {
        std::ofstream(scene) << facing_quad("global", 0.0, 1, 4);
    }
    const std::string render = "render " + test::shell_quote(scene) + " --backend cpu ";
    test::expect_one_error(test::run_vkrt(render + "--passes albedo -o " + test::shell_quote((dir / "q.png").string()), dir),
                           {"q.png", "--passes writes its layers into an OpenEXR file"});
    test::expect_one_error(test::run_vkrt(render + "--passes albedo --samples 0:2 -o " +
                                              test::shell_quote((dir / "part.exr").string()),
                                          dir),
                           {"part.exr", "a partial file (--samples) carries none"});
    test::expect_one_error(test::run_vkrt(render + "--passes albedo,colour -o " + test::shell_quote((dir / "q.exr").string()), dir),
                           {"--passes", "expected albedo, normal or depth", "'colour'"});
    test::expect_one_error(test::run_vkrt(render + "--passes depth,depth -o " + test::shell_quote((dir / "q.exr").string()), dir),
                           {"--passes", "'depth' is named twice"});
    const std::string nff = (dir / "ball.nff").string();
    {
        std::ofstream(nff) << "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 30\nhither 0.01\nresolution 8 8\n"
                              "b 0.1 0.1 0.1\nl 0 5 5\nf 1 0 0 1 0 0 0 0\ns 0 0 0 1\n";
    }
    test::expect_one_error(test::run_vkrt("render " + test::shell_quote(nff) + " --backend cpu --passes depth -o " +
                                              test::shell_quote((dir / "ball.exr").string()),
                                          dir),
                           {"--passes", "pixel corner"});
}

}  // namespace
}  // namespace vkrt
