// The thin-lens camera (kernel/camera.glsl): the concentric disc map and the blur of
// a sphere out of focus against its closed form. Its rays' geometry is checked with
// the pinhole's, in sampling_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "flatten/flat_scene.hpp"
#include "kernel/kernel.hpp"
#include "test_support.hpp"

namespace {

using vkrt::kernel::Kernel;
using vkrt::kernel::vec2;
using vkrt::kernel::vec3;

TEST(ConcentricDisc, MapsTheSquareOntoTheUnitDisc) {
    Kernel k;
    EXPECT_EQ(k.concentric_disc(vec2(0.5f, 0.5f)), vec2(0.0f));
    // The middles of the square's sides go to the disc's axes.
    EXPECT_EQ(k.concentric_disc(vec2(1.0f, 0.5f)), vec2(1.0f, 0.0f));
    EXPECT_EQ(k.concentric_disc(vec2(0.0f, 0.5f)), vec2(-1.0f, 0.0f));
    const vec2 top = k.concentric_disc(vec2(0.5f, 1.0f));
    EXPECT_NEAR(top.x, 0.0f, 1e-7f);
    EXPECT_EQ(top.y, 1.0f);
    // A corner goes to the diagonal.
    const vec2 corner = k.concentric_disc(vec2(1.0f, 1.0f));
    EXPECT_NEAR(corner.x, std::sqrt(0.5f), 1e-6f);
    EXPECT_NEAR(corner.y, std::sqrt(0.5f), 1e-6f);
}

// It preserves area: the cells of a fine grid on the square carry equal weight, so
// their images sample the disc uniformly. The mean of |p|^2 is then 1/2 and the
// quarter of the disc in each quadrant holds a quarter of the points; and no point
// leaves the disc.
TEST(ConcentricDisc, IsUniformOnTheDisc) {
    Kernel k;
    const int n = 256;
    double r2 = 0.0;
    int inner = 0, quadrant[4] = {};
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            const vec2 p = k.concentric_disc(vec2((i + 0.5f) / n, (j + 0.5f) / n));
            const double d2 = double(p.x) * p.x + double(p.y) * p.y;
            ASSERT_LE(d2, 1.0 + 1e-6);
            r2 += d2;
            inner += d2 < 0.25;
            ++quadrant[(p.x < 0) + 2 * (p.y < 0)];
        }
    }
    EXPECT_NEAR(r2 / (n * n), 0.5, 1e-4);
    EXPECT_NEAR(double(inner) / (n * n), 0.25, 2e-3);  // the disc of radius 1/2
    for (int q : quadrant) EXPECT_EQ(q, n * n / 4);
}

TEST(ThinLens, FeatureOnlyWithALens) {
    vkrt::Scene scene = vkrt::test::scene_from_text("pinhole.json", R"({
      "camera": { "eye": [0, 0, 0], "look_at": [0, 0, -1] },
      "materials": { "m": { "diffuse": [1, 1, 1] } },
      "objects": [ { "type": "sphere", "center": [0, 0, -5], "radius": 1, "material": "m" } ] })");
    EXPECT_FALSE(vkrt::flatten_scene(scene).features.has(vkrt::Feature::HAS_LENS));
    scene.camera.lens_radius = 0.1;
    EXPECT_TRUE(vkrt::flatten_scene(scene).features.has(vkrt::Feature::HAS_LENS));
}

// A glowing sphere on the view axis at distance z, radius r, seen through a lens of
// radius R in focus at f. Through a pinhole its image is a uniform disc of radius
// a = r / sqrt(z^2 - r^2) on the plane at distance 1; the lens moves each point's
// image by the lens point times (z - f) / (z f), a uniform disc of radius
// b = R |z - f| / (z f), so the blurred image is the two discs convolved and its
// variance along x is (a^2 + b^2) / 4, less the 1/12 pixel^2 that reading each
// pixel's light at its centre leaves out.
double measured_variance_x(const vkrt::Image& im) {
    double sum = 0.0, sx = 0.0, sxx = 0.0;
    for (std::uint32_t y = 0; y < im.height; ++y) {
        for (std::uint32_t x = 0; x < im.width; ++x) {
            const double v = im.pixel(x, y)[0];
            sum += v;
            sx += v * (x + 0.5);
            sxx += v * (x + 0.5) * (x + 0.5);
        }
    }
    const double mean = sx / sum;
    return sxx / sum - mean * mean;
}

std::string glow_scene(double z, double r, double lens, double focus) {
    return R"({
      "camera": { "eye": [0, 0, 0], "look_at": [0, 0, -1], "fov": 40, "width": 72, "height": 72,
                  "lens_radius": )" + std::to_string(lens) + R"(, "focus_distance": )" + std::to_string(focus) + R"( },
      "render": { "spp": 256, "jitter": true },
      "materials": { "glow": { "diffuse": [0, 0, 0], "emission": [1, 1, 1] } },
      "objects": [ { "type": "sphere", "center": [0, 0, )" + std::to_string(-z) + R"(], "radius": )" +
           std::to_string(r) + R"(, "material": "glow" } ] })";
}

TEST(ThinLens, BlurMatchesTheCircleOfConfusion) {
    const double z = 10.0, r = 0.45, f = 5.0, lens = 1.1;
    const double pixel = 2.0 * std::tan(glm::radians(40.0) / 2.0) / 72.0;
    const double a = r / std::sqrt(z * z - r * r) / pixel;
    const double b = lens * (z - f) / (z * f) / pixel;
    ASSERT_GT(b, 2.0 * a);  // the lens's part dominates
    const vkrt::Image blurred = vkrt::test::render_cpu(vkrt::test::scene_from_text("blur.json", glow_scene(z, r, lens, f))).image;
    EXPECT_NEAR(measured_variance_x(blurred), (a * a + b * b) / 4.0 - 1.0 / 12.0, 0.02 * (a * a + b * b) / 4.0);
    // In focus, the same lens leaves the pinhole's sharp disc (whose pixels on the
    // edge are read off-centre, so it is compared with the pinhole's image, not with
    // a^2 / 4).
    const vkrt::Image sharp = vkrt::test::render_cpu(vkrt::test::scene_from_text("sharp.json", glow_scene(z, r, lens, z))).image;
    const vkrt::Image pinhole = vkrt::test::render_cpu(vkrt::test::scene_from_text("pinhole.json", glow_scene(z, r, 0.0, z))).image;
    EXPECT_NEAR(measured_variance_x(sharp), measured_variance_x(pinhole), 0.01 * measured_variance_x(pinhole));
    EXPECT_NEAR(measured_variance_x(pinhole), a * a / 4.0, 0.1 * a * a / 4.0);
}

}  // namespace
