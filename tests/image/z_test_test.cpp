// compare --test's statistics (image/z_test.hpp): Z-scores and p-values of chosen
// differences and image means, the Šidák level, what is and is not tested, and its
// calibration: on 200 pairs of independent renders of one scene it rejects at about
// its nominal 1%, its Z-scores are standard normal in the bulk, a 1% bias is
// rejected by the pixels and a 0.3% bias by the image means from the sample counts a
// pilot render predicts, and against stacks of four images (vkrt stack) Student's
// t-scores keep the level that normal scores would lose.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <tuple>
#include <vector>

#include "image/stack.hpp"
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
    // Six pixel channels and three image means in the family.
    EXPECT_NEAR(r.level, 1.0 - std::pow(0.99, 1.0 / 9.0), 1e-15);
    EXPECT_FLOAT_EQ(p.rgb[0], float(std::erfc(2.0 / std::sqrt(2.0))));  // 0.0455
    EXPECT_FLOAT_EQ(p.rgb[4], float(std::erfc(1.0 / std::sqrt(2.0))));  // 0.317
    EXPECT_EQ(p.rgb[1], 1.0f);
    EXPECT_DOUBLE_EQ(r.worst_z, 2.0);
    EXPECT_EQ(r.worst_x, 0u);
    EXPECT_EQ(r.worst_channel, 0u);
    EXPECT_FALSE(r.rejects()) << "0.0455 is above the level, 0.00112";
    // The red mean: (2 + 0) / 2 = 1 over sqrt(1 + 1) / 2, z = 1.414; green
    // (0 - 1) / 2 over the same, z = -0.707; blue 0.
    EXPECT_DOUBLE_EQ(r.means[0].difference, 1.0);
    EXPECT_DOUBLE_EQ(r.means[0].standard_error, std::sqrt(2.0) / 2.0);
    EXPECT_DOUBLE_EQ(r.means[0].z, std::sqrt(2.0));
    EXPECT_DOUBLE_EQ(r.means[0].p, std::erfc(1.0));
    EXPECT_DOUBLE_EQ(r.means[1].z, -std::sqrt(0.5));
    EXPECT_EQ(r.means[2].z, 0.0);
    EXPECT_EQ(r.means_rejected, 0u);
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
// The lamp reflects nothing, so each pixel's radiance is linear in the floor's
// colour, `albedo` times (0.7, 0.6, 0.5).
Scene lit_floor(std::uint32_t seed, std::uint32_t spp = 64, double albedo = 1.0) {
    const auto c = [&](double v) { return std::to_string(v * albedo); };
    Scene s = test::scene_from_text("lit_floor", R"({
      "camera": { "eye": [0, 2, 3], "look_at": [0, 0, 0], "fov": 40, "width": 8, "height": 8 },
      "render": { "mode": "global", "spp": )" + std::to_string(spp) + R"(, "max_bounces": 2, "sampler": "hash",
                  "seed": )" + std::to_string(seed) + R"(, "background": [0, 0, 0] },
      "materials": { "floor": { "diffuse": [)" + c(0.7) + ", " + c(0.6) + ", " + c(0.5) + R"(] },
                     "lamp": { "diffuse": [0, 0, 0], "emission": [4, 4, 4] } },
      "objects": [ { "type": "quad", "corner": [-3, 0, -3], "edge1": [0, 0, 6], "edge2": [6, 0, 0], "material": "floor" },
                   { "type": "quad", "corner": [-1, 3, -1], "edge1": [2, 0, 0], "edge2": [0, 0, 2], "material": "lamp" } ]
    })");
    s.render.squares = true;
    return s;
}

std::pair<Image, Image> render_with_variance(const Scene& scene) {
    const RenderOutcome r = test::render_cpu(scene);
    Image var(r.image.width, r.image.height);
    var.rgb = variance_layer(r.sums).values;
    return {r.image, var};
}
std::pair<Image, Image> render_with_variance(std::uint32_t seed) { return render_with_variance(lit_floor(seed)); }

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

// The critical score of a two-sided normal test at `level`, by bisection on erfc.
double critical_score(double level) {
    double lo = 0.0, hi = 40.0;
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        (std::erfc(mid / std::sqrt(2.0)) > level ? lo : hi) = mid;
    }
    return lo;
}

// Renders 10 pairs, A of a floor brighter by the factor `bias`, B of the plain floor
// (seeds from `first_seed`), at n50 / 4 and at 4 n50 samples (n50 / 4 at least
// `min_spp`), and expects the test, as `rejects` counts a rejection, to reject at
// most 3 pairs at the first count and all 10 at the second. Prints the counts under
// `label`.
void expect_rejections_around(double n50, double bias, std::uint32_t first_seed, std::uint32_t min_spp,
                              bool (*rejects)(const ZTestResult&), const char* label) {
    std::printf("%s: predicted n50 %.0f samples\n", label, n50);
    ASSERT_LT(n50, 16384.0) << "the scene is too noisy for this test's budget";
    const auto rejections = [&](std::uint32_t spp) {
        int rejected = 0;
        for (std::uint32_t i = 0; i < 10; ++i) {
            const auto [a, var_a] = render_with_variance(lit_floor(first_seed + 2u * i, spp, bias));
            const auto [b, var_b] = render_with_variance(lit_floor(first_seed + 2u * i + 1u, spp));
            rejected += rejects(z_test(a, var_a, b, &var_b, 0.01)) ? 1 : 0;
        }
        return rejected;
    };
    const auto quarter = std::max<std::uint32_t>(min_spp, std::uint32_t(n50 / 4.0));
    const auto four = std::uint32_t(std::ceil(n50 * 4.0));
    const int low = rejections(quarter), high = rejections(four);
    std::printf("%s: %d of 10 rejected at %u samples, %d of 10 at %u\n", label, low, quarter, high, four);
    EXPECT_LE(low, 3);
    EXPECT_EQ(high, 10);
}

// A pilot render of the plain floor, 1024 samples with its variance, from which a
// test predicts its sample counts; and the critical score c of the level for its
// pixel channels and image means at alpha 0.01.
struct Pilot {
    static constexpr std::uint32_t kSamples = 1024;
    Image image, variance;
    double c = 0.0;
};
Pilot pilot_render(std::uint32_t seed) {
    Pilot p;
    std::tie(p.image, p.variance) = render_with_variance(lit_floor(seed, Pilot::kSamples));
    p.c = critical_score(-std::expm1(std::log1p(-0.01) / double(p.image.rgb.size() + 3)));
    return p;
}

// A floor 1% brighter (B's albedo times 1.01) shifts each pixel channel's mean by
// 0.01 mu. Against an unbiased B of as many samples, the expected Z-score at n samples
// is 0.01 mu sqrt(n) / (sigma sqrt(1.01^2 + 1)), sigma a sample's standard deviation;
// the test starts to reject where the largest reaches the level's critical score c:
// n50 = (1.01^2 + 1) (c sigma / (0.01 mu))^2, smallest over the channels, predicted
// here from a pilot render (decision 0049). At n50 / 4 the largest expected score is
// c / 2 and the test seldom rejects; at 4 n50 it is 2c and it always does.
TEST(ZTest, RejectsAOnePercentBiasAtThePredictedSampleCount) {
    const Pilot pilot = pilot_render(99);
    double n50 = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < pilot.image.rgb.size(); ++i) {
        const double sigma = std::sqrt(double(pilot.variance.rgb[i]) * Pilot::kSamples);
        const double mu = pilot.image.rgb[i];
        if (mu > 0.0) n50 = std::min(n50, (1.01 * 1.01 + 1.0) * std::pow(pilot.c * sigma / (0.01 * mu), 2.0));
    }
    // By its pixels alone.
    expect_rejections_around(n50, 1.01, 1u, 16u, [](const ZTestResult& t) { return t.rejected > 0; },
                             "1% bias, pixels");
}

// The image means see a bias spread over the whole image long before any pixel
// does. A floor 0.3% brighter shifts channel c's image mean by 0.003 mu_c (mu_c its
// mean over the P pixels); the mean's variance at n samples a side is
// (1.003^2 + 1) sbar_c^2 / (n P), sbar_c^2 the pixels' mean variance of one sample, so
// the test starts to reject at n50 = (1.003^2 + 1) (c sbar_c / (0.003 mu_c))^2 / P,
// the smallest over the channels; at n50 / 4 it seldom does, at 4 n50 always.
TEST(ZTest, ImageMeansRejectAThirdOfAPercentBiasAtThePredictedSampleCount) {
    const Pilot pilot = pilot_render(98);
    const std::size_t m = pilot.image.rgb.size();
    const double pixels = double(m / 3);
    double n50 = std::numeric_limits<double>::infinity();
    for (std::size_t channel = 0; channel < 3; ++channel) {
        double mu = 0.0, sigma2 = 0.0;
        for (std::size_t i = channel; i < m; i += 3) {
            mu += pilot.image.rgb[i] / pixels;
            sigma2 += double(pilot.variance.rgb[i]) * Pilot::kSamples / pixels;
        }
        n50 = std::min(n50, (1.003 * 1.003 + 1.0) * pilot.c * pilot.c * sigma2 / (0.003 * mu * 0.003 * mu) / pixels);
    }
    ASSERT_GT(n50, 64.0) << "too few samples for means near normal";
    expect_rejections_around(n50, 1.003, 301u, 1u, [](const ZTestResult& t) { return t.means_rejected > 0; },
                             "0.3% bias, image means");
}

// B the mean of K = 4 independent renders whose variance is their spread (vkrt
// stack): 3 degrees of freedom. Scored with Student's t of those degrees of freedom
// the test keeps its level over 200 pairs (conservatively: A's own variance, of
// many more, is half of the sum); had the stack's variances been taken as exact, as
// normal scores take them, more pairs would be rejected than a 1% level allows.
TEST(ZTest, AStackOfFourKeepsTheLevelWithStudentsT) {
    constexpr int kPairs = 200;
    constexpr std::uint32_t kImages = 4;
    int rejected = 0, rejected_as_normal = 0;
    for (int i = 0; i < kPairs; ++i) {
        const std::uint32_t seed = 1000u + 10u * std::uint32_t(i);
        const auto [a, var_a] = render_with_variance(lit_floor(seed, 64));
        std::vector<Image> runs;
        for (std::uint32_t k = 0; k < kImages; ++k) runs.push_back(render_with_variance(lit_floor(seed + 1u + k, 16)).first);
        const StackedImage b = stack_images(runs);
        ASSERT_EQ(b.dof, 3.0);
        rejected += z_test(a, PixelVariance{&var_a}, b.mean, PixelVariance{&b.variance, b.dof}, 0.01).rejects() ? 1 : 0;
        rejected_as_normal += z_test(a, var_a, b.mean, &b.variance, 0.01).rejects() ? 1 : 0;
    }
    std::printf("stacks of %u: %d of %d pairs rejected with Student's t, %d with normal scores\n", kImages, rejected,
                kPairs, rejected_as_normal);
    // Binomial(200, 0.01): 2 expected; 8 or more has a chance of 5e-4.
    EXPECT_LE(rejected, 7);
    EXPECT_GT(rejected_as_normal, 7);
}

}  // namespace
}  // namespace vkrt
