// compare --test's statistics (image/z_test.hpp): Z-scores and p-values of chosen
// differences, the Šidák level, what is and is not tested, and its calibration: on
// 200 pairs of independent renders of one scene it rejects at about its nominal 1%,
// and its Z-scores are standard normal in the bulk.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>

#include "image/z_test.hpp"
#include "render/pixel_sums.hpp"
#include "render/render.hpp"
#include "scene/load_scene.hpp"
#include "test_support.hpp"
#include "uniform_image.hpp"

namespace vkrt {
namespace {

using test::uniform_image;

TEST(ZTest, ScoresAndPValuesOfChosenDifferences) {
    Image a = uniform_image(2, 1, 1.0f), b = uniform_image(2, 1, 1.0f);
    const Image var_a = uniform_image(2, 1, 0.25f), var_b = uniform_image(2, 1, 0.75f);
    a.rgb[0] = 3.0f;  // z = 2 / sqrt(1) = 2
    b.rgb[4] = 2.0f;  // z = -1
    Image p;
    const ZTestResult r = z_test(a, var_a, b, &var_b, 0.01, &p);
    EXPECT_EQ(r.tests, 6u);
    EXPECT_NEAR(r.level, 1.0 - std::pow(0.99, 1.0 / 6.0), 1e-15);
    EXPECT_FLOAT_EQ(p.rgb[0], float(std::erfc(2.0 / std::sqrt(2.0))));  // 0.0455
    EXPECT_FLOAT_EQ(p.rgb[4], float(std::erfc(1.0 / std::sqrt(2.0))));  // 0.317
    EXPECT_EQ(p.rgb[1], 1.0f);
    EXPECT_DOUBLE_EQ(r.worst_z, 2.0);
    EXPECT_EQ(r.worst_x, 0u);
    EXPECT_EQ(r.worst_channel, 0u);
    EXPECT_FALSE(r.rejects()) << "0.0455 is above the level, 0.00167";
    // B exact: only A's variance, so z = 2 / 0.5 = 4, p = 6.3e-5: rejected.
    const ZTestResult exact = z_test(a, var_a, b, nullptr, 0.01);
    EXPECT_DOUBLE_EQ(exact.worst_z, 4.0);
    EXPECT_EQ(exact.rejected, 1u);
}

TEST(ZTest, UnknownVariancesAreNotTestedAndZeroVariancesExactly) {
    Image a = uniform_image(3, 1, 0.5f), b = uniform_image(3, 1, 0.5f);
    Image var = uniform_image(3, 1, 0.0f);
    for (int c = 0; c < 3; ++c) var.rgb[std::size_t(c)] = std::numeric_limits<float>::infinity();
    a.rgb[0] = 9.0f;  // untested: its variance is unknown
    EXPECT_EQ(z_test(a, var, b, nullptr, 0.01).tests, 6u);
    EXPECT_FALSE(z_test(a, var, b, nullptr, 0.01).rejects()) << "equal values of no variance pass";
    a.rgb[8] = 0.5001f;  // no variance, a difference: certain
    const ZTestResult r = z_test(a, var, b, nullptr, 0.01);
    EXPECT_EQ(r.rejected, 1u);
    EXPECT_EQ(r.min_p, 0.0);
    EXPECT_EQ(r.worst_x, 2u);
}

// A diffuse floor under a large area light, global mode with next-event estimation:
// every sample's radiance varies continuously, so the means of 64 are near normal.
Scene lit_floor(std::uint32_t seed) {
    Scene s = test::scene_from_text("lit_floor", R"({
      "camera": { "eye": [0, 2, 3], "look_at": [0, 0, 0], "fov": 40, "width": 8, "height": 8 },
      "render": { "mode": "global", "spp": 64, "max_bounces": 2, "sampler": "hash", "seed": )" +
                                                     std::to_string(seed) + R"(, "background": [0, 0, 0] },
      "materials": { "floor": { "diffuse": [0.7, 0.6, 0.5] }, "lamp": { "emission": [4, 4, 4] } },
      "objects": [ { "type": "quad", "corner": [-3, 0, -3], "edge1": [0, 0, 6], "edge2": [6, 0, 0], "material": "floor" },
                   { "type": "quad", "corner": [-1, 3, -1], "edge1": [2, 0, 0], "edge2": [0, 0, 2], "material": "lamp" } ]
    })");
    s.render.squares = true;
    return s;
}

std::pair<Image, Image> render_with_variance(std::uint32_t seed) {
    const RenderOutcome r = test::render_cpu(lit_floor(seed));
    Image var(r.image.width, r.image.height);
    var.rgb = variance_layer(r.sums).values;
    return {r.image, var};
}

TEST(ZTest, RejectsIndependentRendersAtItsNominalRate) {
    constexpr int kPairs = 200;
    int rejected = 0;
    std::size_t tests = 0, beyond_196 = 0;
    for (int i = 0; i < kPairs; ++i) {
        const auto [a, var_a] = render_with_variance(2u * std::uint32_t(i) + 1u);
        const auto [b, var_b] = render_with_variance(2u * std::uint32_t(i) + 2u);
        Image p;
        const ZTestResult r = z_test(a, var_a, b, &var_b, 0.01, &p);
        ASSERT_EQ(r.tests, a.rgb.size());
        rejected += r.rejects() ? 1 : 0;
        tests += r.tests;
        for (float v : p.rgb) beyond_196 += v < 0.05f ? 1u : 0u;
    }
    const double rate = double(beyond_196) / double(tests);
    std::printf("%d of %d pairs rejected at alpha 0.01; %.4f of Z-scores beyond 1.96\n", rejected, kPairs, rate);
    // Binomial(200, 0.01): 2 expected; 8 or more has a chance of 5e-4.
    EXPECT_LE(rejected, 7);
    // 5% of standard normal scores lie beyond 1.96 (the channels of a pixel are
    // correlated, which widens the spread of this fraction, not its mean).
    EXPECT_NEAR(rate, 0.05, 0.01);
}

}  // namespace
}  // namespace vkrt
