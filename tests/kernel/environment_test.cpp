// The environment image (kernel/environment.glsl, host/flatten/environment_table.cpp,
// host/scene/environment.cpp): where directions land in the image, its rotation and
// up axis, the sampled density against the weights written again here, a constant
// environment's closed form on both backends, halving, and the loaders' messages.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <initializer_list>
#include <iostream>
#include <numbers>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "cpu/cpu_backend.hpp"
#include "flatten/flat_scene.hpp"
#include "image/image.hpp"
#include "kernel/kernel.hpp"
#include "scene/environment.hpp"
#include "statistics.hpp"
#include "test_support.hpp"

namespace vkrt {
namespace {

using kernel::vec3;
constexpr double kPi = std::numbers::pi;

// A linear float image of w x h texels, texel (x, y) colour(x, y), rows from the top.
std::filesystem::path write_environment(const std::string& name, std::uint32_t w, std::uint32_t h,
                                        const std::function<vec3(std::uint32_t, std::uint32_t)>& colour) {
    Image img(w, h);
    for (std::uint32_t y = 0; y < h; ++y) {
        for (std::uint32_t x = 0; x < w; ++x) {
            const vec3 c = colour(x, y);
            std::copy(&c.x, &c.x + 3, img.pixel(x, y));
        }
    }
    const std::filesystem::path file = test::temp_dir("environment") / (name + ".exr");
    write_image(img, file);
    return file;
}

// A scene of `objects` under the environment image `file` with the background's
// further fields `fields` (e.g. "\"rotation\": 90").
Scene scene_under(const std::filesystem::path& file, const std::string& fields = "", const std::string& objects = "[]",
                  const std::string& render = "\"mode\": \"global\"") {
    return test::scene_from_text("environment", R"({
      "camera": { "eye": [0, 0, 3], "look_at": [0, 0, 0], "fov": 10, "width": 16, "height": 16 },
      "render": { )" + render + R"(, "background": { "image": ")" + file.string() + "\"" +
                                                    (fields.empty() ? "" : ", " + fields) + R"( } },
      "materials": { "m": { "diffuse": [0.6, 0.6, 0.6] } },
      "objects": )" + objects + "}");
}

// Texel (x, y) of the 8 x 4 image holds (x, y, 0): a lookup's red and green say
// where in the image, bilinearly, it landed.
std::filesystem::path position_image() {
    return write_environment("positions", 8, 4, [](std::uint32_t x, std::uint32_t y) { return vec3(x, y, 0); });
}

void expect_lands(kernel::Kernel& k, vec3 dir, float x, float y, const std::string& what) {
    const vec3 c = k.environment_radiance(dir);
    EXPECT_NEAR(c.x, x, 1e-4f) << what;
    EXPECT_NEAR(c.y, y, 1e-4f) << what;
}

// The documented mapping: the image's centre looks along +x, a quarter further
// along +z, a quarter back along -z; its top row is up. In an 8 x 4 image, +x
// falls between columns 3 and 4 and rows 1 and 2 (position 3.5, 1.5); -x on the
// seam between the last column and the first, which wrap (7 and 0 average to 3.5).
TEST(EnvironmentMapping, AxesLandWhereTheDocumentationSays) {
    const FlatScene g = flatten_scene(scene_under(position_image()));
    ASSERT_TRUE(g.features.has(Feature::HAS_ENVIRONMENT_MAP));
    kernel::Kernel k = make_kernel(g);
    expect_lands(k, vec3(1, 0, 0), 3.5f, 1.5f, "+x");
    expect_lands(k, vec3(0, 0, 1), 5.5f, 1.5f, "+z");
    expect_lands(k, vec3(0, 0, -1), 1.5f, 1.5f, "-z");
    expect_lands(k, vec3(-1, 0, 0), 3.5f, 1.5f, "-x");
    expect_lands(k, vec3(0, 1, 0), 3.5f, 0.0f, "+y (the top row, latitude clamped)");
    expect_lands(k, vec3(0, -1, 0), 3.5f, 3.0f, "-y (the bottom row)");
    // A texel's centre shows the texel alone: column 6, row 0 is at u = 6.5 / 8, t = 0.5 / 4.
    const double theta = kPi * 0.5 / 4, phi = 2 * kPi * (6.5 / 8 - 0.5);
    expect_lands(k, vec3(std::cos(phi) * std::sin(theta), std::cos(theta), std::sin(phi) * std::sin(theta)), 6.0f,
                 0.0f, "texel (6, 0)");
}

// A rotation turns the image right-handed about its up axis: by 90 degrees, what
// +x saw is seen along -z, and what +z saw along +x. An up of +z puts the top row
// there and what +z saw (the glTF frame's +z, Blender's -y) along -y.
TEST(EnvironmentMapping, RotationAndUpMoveTheImage) {
    // The kernel reads the flattened scene's arrays: they must outlive it.
    const FlatScene turned_scene = flatten_scene(scene_under(position_image(), "\"rotation\": 90"));
    kernel::Kernel turned = make_kernel(turned_scene);
    expect_lands(turned, vec3(0, 0, -1), 3.5f, 1.5f, "rotation 90, -z");
    expect_lands(turned, vec3(1, 0, 0), 5.5f, 1.5f, "rotation 90, +x");
    const FlatScene tilted_scene = flatten_scene(scene_under(position_image(), "\"up\": [0, 0, 2]"));
    kernel::Kernel tilted = make_kernel(tilted_scene);
    expect_lands(tilted, vec3(0, 0, 1), 3.5f, 0.0f, "up +z, +z");
    expect_lands(tilted, vec3(0, -1, 0), 5.5f, 1.5f, "up +z, -y");
    expect_lands(tilted, vec3(1, 0, 0), 3.5f, 1.5f, "up +z, +x");
}

// An image of random values, some texels black, one far brighter than the rest.
std::filesystem::path random_image(std::uint32_t w, std::uint32_t h) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> value(0.0f, 1.0f);
    std::vector<vec3> texels(std::size_t(w) * h);
    for (vec3& t : texels) {
        t = value(rng) < 0.3f ? vec3(0.0f) : vec3(value(rng), value(rng), value(rng));
    }
    texels[std::size_t(2) * w + 5] = vec3(40.0f, 30.0f, 20.0f);
    return write_environment("random", w, h, [&](std::uint32_t x, std::uint32_t y) { return texels[y * w + x]; });
}

// The weight the sampler is documented to give texel (x, y), in double: the mean
// over the texel's square of the bilinear interpolation of luminance (columns
// wrapping, rows clamped), here by the midpoint rule on 16 x 16 points, times the
// sine of its row centre's angle from the pole.
std::vector<double> expected_weights(const LinearImage& image) {
    const std::int64_t w = image.width, h = image.height;
    const auto lum = [&](std::int64_t x, std::int64_t y) {
        const glm::vec4& c = image.texels[std::size_t(std::clamp<std::int64_t>(y, 0, h - 1)) * image.width +
                                          std::size_t((x % w + w) % w)];
        return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
    };
    // The bilinear interpolation at continuous image position (px, py), in texels.
    const auto bilinear = [&](double px, double py) {
        const double fx = px - 0.5, fy = py - 0.5;
        const auto x0 = std::int64_t(std::floor(fx)), y0 = std::int64_t(std::floor(fy));
        const double ax = fx - double(x0), ay = fy - double(y0);
        return (1 - ay) * ((1 - ax) * lum(x0, y0) + ax * lum(x0 + 1, y0)) +
               ay * ((1 - ax) * lum(x0, y0 + 1) + ax * lum(x0 + 1, y0 + 1));
    };
    std::vector<double> out;
    for (std::int64_t y = 0; y < h; ++y) {
        for (std::int64_t x = 0; x < w; ++x) {
            double mean = 0.0;
            for (int j = 0; j < 16; ++j) {
                for (int i = 0; i < 16; ++i) mean += bilinear(x + (i + 0.5) / 16, y + (j + 0.5) / 16) / 256.0;
            }
            out.push_back(mean * std::sin(kPi * (y + 0.5) / h));
        }
    }
    return out;
}

// The texel a world direction falls in, by the mapping in double.
std::size_t texel_of(vec3 d, std::uint32_t w, std::uint32_t h) {
    const double u = 0.5 + std::atan2(double(d.z), double(d.x)) / (2 * kPi);
    const double t = std::acos(std::clamp(double(d.y), -1.0, 1.0)) / kPi;
    const auto x = std::min<std::uint32_t>(std::uint32_t(u * w), w - 1);
    const auto y = std::min<std::uint32_t>(std::uint32_t(t * h), h - 1);
    return std::size_t(y) * w + x;
}

// 400,000 directions drawn by the kernel fall into the texels as the documented
// weights say (a chi-square test over the 16 x 8 texels; black neighbourhoods get
// none), each with the density environment_pdf gives its direction.
TEST(EnvironmentSampling, DirectionsFollowTheDocumentedWeights) {
    const std::uint32_t w = 16, h = 8;
    const Scene scene = scene_under(random_image(w, h));
    const FlatScene g = flatten_scene(scene);
    kernel::Kernel k = make_kernel(g);
    const std::vector<double> weights = expected_weights(scene.environment->image);
    double total = 0.0;
    for (double x : weights) total += x;

    const int n = 400000;
    std::vector<double> counts(weights.size(), 0.0);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    int pdf_mismatches = 0;
    for (int i = 0; i < n; ++i) {
        const float u1 = uniform(rng), u2 = uniform(rng);
        k.work_reset();  // the searches count against the loop budget, which a sample resets
        const auto e = k.sample_environment(u1, u2);
        ASSERT_GT(e.pdf, 0.0f) << "sample " << i;
        ASSERT_NEAR(glm::length(e.dir), 1.0f, 1e-5f);
        // Exactly on a texel's edge, rounding may place the direction in its neighbour.
        const float pdf = k.environment_pdf(e.dir);
        if (std::abs(pdf - e.pdf) > 1e-4f * e.pdf) ++pdf_mismatches;
        counts[texel_of(e.dir, w, h)] += 1.0;
    }
    EXPECT_LT(pdf_mismatches, n / 1000);
    std::vector<double> expected(weights.size());
    for (std::size_t i = 0; i < weights.size(); ++i) {
        expected[i] = n * weights[i] / total;
        if (expected[i] == 0.0) {
            EXPECT_EQ(counts[i], 0.0) << "texel " << i << " has no weight";
        }
    }
    // Far into the tail, where a fair sampler lands once in three million runs:
    // six standard deviations above the mean at these ~127 degrees of freedom.
    const test::ChiSquareResult fit = test::chi_square_test(counts, expected);
    EXPECT_GT(fit.p_value, 3e-7) << fit;
    std::cout << fit << "\n";
}

// The density integrates to 1 over the sphere (midpoint rule in the image's
// coordinates, 8 x 8 points per texel, with the mapping's 2 pi^2 sin(theta)).
TEST(EnvironmentSampling, DensityIntegratesToOne) {
    const std::uint32_t w = 16, h = 8;
    const FlatScene g = flatten_scene(scene_under(random_image(w, h)));
    kernel::Kernel k = make_kernel(g);
    const int nu = 8 * w, nt = 8 * h;
    double sum = 0.0;
    for (int j = 0; j < nt; ++j) {
        const double theta = kPi * (j + 0.5) / nt;
        for (int i = 0; i < nu; ++i) {
            const double phi = 2 * kPi * ((i + 0.5) / nu - 0.5);
            const vec3 d(std::cos(phi) * std::sin(theta), std::cos(theta), std::sin(phi) * std::sin(theta));
            sum += k.environment_pdf(d) * 2 * kPi * kPi * std::sin(theta) / (double(nu) * nt);
        }
    }
    EXPECT_NEAR(sum, 1.0, 1e-4);
}

// A constant environment L around a diffuse sphere of albedo rho: the sphere is rho
// L everywhere (no other surface to see). By BSDF sampling alone each sample is
// exactly that; next-event estimation with MIS gets it on average. Both backends.
TEST(EnvironmentRender, ConstantEnvironmentLightsASphereAsItsAlbedoSays) {
    const std::filesystem::path file = write_environment("constant", 8, 4, [](auto, auto) { return vec3(0.5f, 0.25f, 1.0f); });
    Scene scene = scene_under(file, "", R"([ { "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m" } ])",
                              R"("mode": "global", "spp": 64, "max_bounces": 4)");
    const double rho = 0.6;
    const vec3 expected(rho * 0.5, rho * 0.25, rho * 1.0);
    for (const bool nee : {false, true}) {
        scene.render.nee = nee;
        for (const bool vulkan : {false, true}) {
            const RenderOutcome out = vulkan ? test::render_vulkan(scene) : test::render_cpu(scene);
            const std::string what = std::string(vulkan ? "vulkan" : "cpu") + (nee ? ", nee" : ", bsdf sampling");
            double mean[3] = {0, 0, 0};
            for (std::uint32_t y = 0; y < out.image.height; ++y) {
                for (std::uint32_t x = 0; x < out.image.width; ++x) {
                    const float* p = out.image.pixel(x, y);
                    for (int c = 0; c < 3; ++c) {
                        if (!nee) {
                            ASSERT_NEAR(p[c], expected[c], 2e-5 * expected[c]) << what << " pixel " << x << ", " << y;
                        }
                        mean[c] += p[c] / double(out.image.width * out.image.height);
                    }
                }
            }
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(mean[c], expected[c], 0.01 * expected[c]) << what << " channel " << c;
        }
    }
}

// Each output texel is the mean of the two by two (at an odd edge, more) it replaces.
TEST(EnvironmentImage, HalvingAveragesTexels) {
    LinearImage image;
    image.width = 5;
    image.height = 3;
    for (int i = 0; i < 15; ++i) image.texels.emplace_back(float(i), 0.0f, 0.0f, 1.0f);
    const LinearImage half = halve(image);
    ASSERT_EQ(half.width, 2u);
    ASSERT_EQ(half.height, 1u);
    // Columns 0-1 and 2-4 of all three rows.
    EXPECT_FLOAT_EQ(half.texels[0].r, (0 + 1 + 5 + 6 + 10 + 11) / 6.0f);
    EXPECT_FLOAT_EQ(half.texels[1].r, (2 + 3 + 4 + 7 + 8 + 9 + 12 + 13 + 14) / 9.0f);
}

TEST(EnvironmentImage, NegativeValuesBecomeZeroWithAWarning) {
    const std::filesystem::path file =
        write_environment("negative", 4, 2, [](std::uint32_t x, auto) { return vec3(x == 1 ? -2.0f : 1.0f, 1.0f, 1.0f); });
    const Scene scene = scene_under(file);
    ASSERT_EQ(scene.warnings.size(), 1u);
    EXPECT_NE(scene.warnings[0].find("2 negative channel values read as 0"), std::string::npos) << scene.warnings[0];
    EXPECT_EQ(scene.environment->image.texels[1].r, 0.0f);
}

// A black image lights nothing and is never sampled: next-event estimation keeps to
// the other lights.
TEST(EnvironmentImage, ABlackImageIsNotSampled) {
    const std::filesystem::path file = write_environment("black", 4, 2, [](auto, auto) { return vec3(0.0f); });
    const FlatScene g = flatten_scene(scene_under(file, "", "[ { \"type\": \"sphere\", \"center\": [0, 0, 0], \"radius\": 1, \"material\": \"m\" } ]"));
    EXPECT_TRUE(g.features.has(Feature::HAS_ENVIRONMENT_MAP));
    EXPECT_EQ(kernel::environment_choice(g.params), 0.0f);
}

void expect_scene_error(const std::string& background, std::initializer_list<std::string_view> pieces) {
    const std::string message = test::scene_error_of("bad_environment", R"({
          "camera": { "eye": [0, 0, 3], "look_at": [0, 0, 0], "fov": 10, "width": 4, "height": 4 },
          "render": { "mode": "global", "background": )" + background + R"( },
          "materials": { "m": { "diffuse": [0.6, 0.6, 0.6] } },
          "objects": [] })");
    test::expect_error_message(message, "", pieces);
}

TEST(EnvironmentErrors, EachMistakeIsNamed) {
    const std::string file = position_image().string();
    expect_scene_error(R"({ "image": "no_such_sky.hdr" })", {"render.background.image", "no_such_sky.hdr", "no such file"});
    expect_scene_error(R"({ "intensity": 2 })", {"render.background", "image"});
    expect_scene_error(R"({ "image": ")" + file + R"(", "intensity": -1 })", {"render.background.intensity"});
    expect_scene_error(R"({ "image": ")" + file + R"(", "up": [0, 0, 0] })", {"render.background.up", "non-zero"});
    expect_scene_error(R"({ "image": ")" + file + R"(", "colour": [1, 1, 1] })", {"render.background", "colour"});
}

}  // namespace
}  // namespace vkrt
