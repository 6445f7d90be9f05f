// The variance of each pixel's mean (render/pixel_sums.hpp, variance_of_mean), from
// the sums of squares the kernel keeps (kernel/sums.glsl), against a closed form and
// against the empirical variance over independent seeds; the same sums on both
// backends, and none kept where the render does not ask (HAS_SQUARES); and `vkrt
// render --variance`, its layer and its refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "image/image_files.hpp"
#include "render/pixel_sums.hpp"
#include "render/render.hpp"
#include "scene/load_scene.hpp"
#include "test_support.hpp"

namespace vkrt {
namespace {

// A one-pixel image whose every sample sees either the white sky (radiance 1) or a
// black quad (0): the quad's edge runs through the pixel's centre, so a jittered
// sample sees the sky with probability 1/2, independently under the hash sampler.
// Each sample is Bernoulli(1/2): the mean of n has variance 1/(4n).
std::string edge_pixel(std::uint32_t seed, std::uint32_t spp) {
    return R"({
      "camera": { "eye": [0, 0, 1], "look_at": [0, 0, 0], "fov": 20, "width": 1, "height": 1 },
      "render": { "mode": "global", "spp": )" + std::to_string(spp) + R"(, "max_bounces": 0, "sampler": "hash",
                  "seed": )" + std::to_string(seed) + R"(, "background": [1, 1, 1] },
      "materials": { "black": { "diffuse": [0, 0, 0] } },
      "objects": [ { "type": "quad", "corner": [0, -5, 0], "edge1": [5, 0, 0], "edge2": [0, 10, 0], "material": "black" } ]
    })";
}

// The scene of edge_pixel, its squares kept.
Scene with_squares(Scene scene) {
    scene.render.squares = true;
    return scene;
}

TEST(Variance, MatchesTheClosedFormAndTheEmpiricalVarianceOverSeeds) {
    constexpr std::uint32_t kSpp = 16;
    constexpr int kSeeds = 100;
    const double expected = 0.25 / kSpp;
    std::vector<double> means, reported;
    for (int seed = 1; seed <= kSeeds; ++seed) {
        const RenderOutcome r =
            test::render_cpu(with_squares(test::scene_from_text("edge", edge_pixel(std::uint32_t(seed), kSpp))));
        ASSERT_EQ(r.sums.sums.size(), 1u);
        means.push_back(radiance_sum(r.sums.sums[0]).g / kSpp);
        reported.push_back(variance_of_mean(r.sums.sums[0]).g);
    }
    const auto mean_of = [](const std::vector<double>& v) {
        double s = 0.0;
        for (double x : v) s += x;
        return s / double(v.size());
    };
    const auto spread_of = [&](const std::vector<double>& v) {
        const double m = mean_of(v);
        double s = 0.0;
        for (double x : v) s += (x - m) * (x - m);
        return s / double(v.size() - 1);
    };
    // The mean reported variance, within four of its standard errors of 1/(4n).
    const double reported_mean = mean_of(reported);
    const double reported_error = std::sqrt(spread_of(reported) / kSeeds);
    EXPECT_NEAR(reported_mean, expected, 4.0 * reported_error);
    EXPECT_LT(reported_error, 0.1 * expected);
    // The empirical variance of the 100 means: its relative standard error is about
    // sqrt(2 / 99) = 0.14 (a Bernoulli mean of 16 is near normal); within 3 of them.
    const double empirical = spread_of(means);
    std::printf("1/(4n) %.6f, mean reported %.6f (s.e. %.6f), empirical %.6f\n", expected, reported_mean,
                reported_error, empirical);
    EXPECT_NEAR(empirical, expected, 3.0 * 0.142 * expected);
    EXPECT_NEAR(empirical, reported_mean, 3.0 * 0.142 * expected);
}

// Radiance 0 and 1 only: the squares' sums are the very same words on both
// backends, and a pixel that saw only one of the two has variance 0.
TEST(Variance, BothBackendsKeepTheSameSquares) {
    const Scene scene = with_squares(test::scene_from_text("edge_both", edge_pixel(7, 32)));
    const RenderOutcome cpu = test::render_cpu(scene);
    const RenderOutcome gpu = test::render_vulkan(scene);
    EXPECT_EQ(gpu.sums.sums.at(0), cpu.sums.sums.at(0));
    EXPECT_GT(variance_of_mean(cpu.sums.sums[0]).r, 0.0);
    // Not asked for, the squares are neither summed nor stored; the sums stay the same.
    Scene plain = scene;
    plain.render.squares = false;
    for (const RenderOutcome& r : {test::render_cpu(plain), test::render_vulkan(plain)}) {
        const kernel::PixelSum& s = r.sums.sums.at(0);
        EXPECT_EQ(s.red_squares, glm::uvec4(0u));
        EXPECT_EQ(s.blue_squares, glm::uvec4(0u));
        EXPECT_EQ(s.green, cpu.sums.sums[0].green);
    }
    Scene sky = scene;
    sky.triangles.clear();
    EXPECT_EQ(variance_of_mean(test::render_cpu(sky).sums.sums.at(0)), glm::dvec3(0.0));
}

// The layer `vkrt render --variance` writes: variance.R, .G, .B beside R, G, B, the
// values variance_of_mean gives.
TEST(Variance, RenderWritesTheVarianceLayer) {
    const std::filesystem::path dir = test::temp_dir("variance_cli");
    const Scene scene = with_squares(test::scene_from_text("edge_cli", edge_pixel(3, 64)));
    const std::string scene_file = (dir / "edge.json").string();
    {
        std::ofstream(scene_file) << edge_pixel(3, 64);
    }
    const test::ProgramRun run =
        test::run_vkrt("render " + test::shell_quote(scene_file) + " --backend cpu --variance -q -o " +
                           test::shell_quote((dir / "edge.exr").string()),
                       dir);
    ASSERT_EQ(run.code, 0) << run.stderr_text;
    std::string error;
    const std::unique_ptr<ImageFileReader> in = image_files().open((dir / "edge.exr").string(), error);
    ASSERT_TRUE(in) << error;
    const std::vector<std::string> channels = {"R", "G", "B", "variance.R", "variance.G", "variance.B"};
    EXPECT_EQ(in->spec().channels, channels);
    std::vector<float> values(channels.size());
    ASSERT_TRUE(in->read_floats(values.data()));
    const RenderOutcome same = test::render_cpu(scene);
    EXPECT_EQ(values[4], float(variance_of_mean(same.sums.sums.at(0)).g));
    EXPECT_GT(values[4], 0.0f);
}

TEST(Variance, RenderRefusesWhatHasNoVarianceLayer) {
    const std::filesystem::path dir = test::temp_dir("variance_refusals");
    const std::string scene = (dir / "edge.json").string();
    {
        std::ofstream(scene) << edge_pixel(3, 4);
    }
    test::expect_one_error(test::run_vkrt("render " + test::shell_quote(scene) + " --variance -o " + test::shell_quote((dir / "edge.png").string()), dir),
                           {"edge.png", "--variance writes its layer into an OpenEXR file"});
    test::expect_one_error(
        test::run_vkrt("render " + test::shell_quote(scene) + " --variance --samples 0:2 -o " +
                       test::shell_quote((dir / "part.exr").string()),
                       dir),
        {"part.exr", "a partial file (--samples) carries the sums of squares"});
}

}  // namespace
}  // namespace vkrt
