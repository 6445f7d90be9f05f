// The numerical-stability suite (docs/numerics.md), cases 9 and 10: extreme cameras
// and images, and global mode's stiff emitters (a tiny one of huge radiance, one of
// radiance 1e38), on both backends. Every case must give finite pixels and no
// truncated sample.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>

#include <fmt/format.h>

#include "kernel/kernel.hpp"
#include "cpu/cpu_backend.hpp"
#include "render/render.hpp"
#include "scene/load_scene.hpp"
#include "flatten/flat_scene.hpp"
#include "test_support.hpp"

namespace vkrt {
namespace {

// The fraction of pixels whose channels all agree within 1e-3.
double agreeing(const Image& a, const Image& b) {
    std::size_t same = 0;
    const std::size_t n = std::size_t(a.width) * a.height;
    for (std::size_t p = 0; p < n; ++p) {
        bool close = true;
        for (int c = 0; c < 3; ++c) close = close && std::abs(a.rgb[3 * p + c] - b.rgb[3 * p + c]) <= 1e-3f;
        same += close ? 1 : 0;
    }
    return double(same) / double(n);
}

// ---------------------------------------------------- case 9: cameras and images

Scene lit_sphere(double fov, std::uint32_t width, std::uint32_t height) {
    return test::scene_from_text("camera", fmt::format(R"({{
      "camera": {{ "eye": [0, 1, 5], "look_at": [0, 0.5, 0], "fov": {}, "width": {}, "height": {} }},
      "materials": {{ "m": {{ "diffuse": [0.8, 0.5, 0.3], "specular": [1, 1, 1], "ks": 0.5 }} }},
      "lights": [ {{ "type": "point", "position": [3, 4, 3] }} ],
      "objects": [ {{ "type": "sphere", "center": [0, 0.5, 0], "radius": 1, "material": "m" }},
                   {{ "type": "quad", "corner": [-20, -0.5, -20], "edge1": [0, 0, 40], "edge2": [40, 0, 0],
                      "material": "m" }} ]
    }})", fov, width, height));
}

struct CameraCase {
    std::string name;
    double fov;
    std::uint32_t width, height;
};

class ExtremeCamera : public ::testing::TestWithParam<CameraCase> {};

TEST_P(ExtremeCamera, FinitePixelsAndBothBackendsAgree) {
    const CameraCase& c = GetParam();
    const Scene scene = lit_sphere(c.fov, c.width, c.height);
    const RenderOutcome cpu = test::render_cpu(scene);
    const RenderOutcome vulkan = test::render_vulkan(scene);
    test::expect_sane(cpu);
    test::expect_sane(vulkan);
    EXPECT_EQ(cpu.image.width, c.width);
    EXPECT_EQ(cpu.image.height, c.height);
    EXPECT_GE(agreeing(cpu.image, vulkan.image), 0.999);
    EXPECT_EQ(cpu.stats.eye_hits, vulkan.stats.eye_hits);
}

INSTANTIATE_TEST_SUITE_P(
    Stability, ExtremeCamera,
    ::testing::Values(CameraCase{"fov_one_thousandth_degree", 1e-3, 64, 48},
                      CameraCase{"fov_179_degrees", 179.0, 64, 48},
                      CameraCase{"one_pixel", 40.0, 1, 1},
                      CameraCase{"wide_strip_16384x8", 40.0, 16384, 8}),
    [](const ::testing::TestParamInfo<CameraCase>& param) { return param.param.name; });

// At a thousandth of a degree every pixel sees the sphere's centre, nearly alike.
TEST(ExtremeCamera, NarrowViewIsAlmostUniform) {
    const RenderOutcome out = test::render_cpu(lit_sphere(1e-3, 16, 12));
    const float first = out.image.rgb[0];
    EXPECT_GT(first, 0.0f);
    for (std::size_t i = 0; i < out.image.rgb.size(); i += 3) {
        EXPECT_NEAR(out.image.rgb[i], first, 1e-3f * first) << "pixel " << i / 3;
    }
}

// ------------------------------------------------------ case 8: Phong exponents

// pow(c, n) for the highlight: pow(0, 0) is undefined in GLSL (lavapipe gives 0, C++
// 1), so the kernel raises only cosines > 0 (phong.glsl, bsdf.glsl); and the device
// computes pow as exp2(n log2 c), whose error grows with n. Exponents 0, 1, 1e4 and
// 1e6 in both modes: finite everywhere, and the backends agree to a tolerance that
// grows with the exponent. Measured, largest channel difference (local / global):
// n = 0: 0 / 0; 1: 1.2e-7 / 3.7e-9; 1e4: 2.7e-6 / 3.4e-6; 1e6: 0 / 0 (the highlight
// is narrower than a pixel).
Scene shiny_sphere(double shininess, bool global) {
    return test::scene_from_text("shiny", fmt::format(R"({{
      "camera": {{ "eye": [0, 0, 4], "look_at": [0, 0, 0], "fov": 30, "width": 32, "height": 24 }},
      "render": {},
      "materials": {{ "m": {{ "diffuse": [0.3, 0.3, 0.3], "specular": [1, 1, 1], "ks": 0.7,
                              "shininess": {} }} }},
      "lights": [ {{ "type": "point", "position": [2, 2, 4] }} ],
      "objects": [ {{ "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m" }} ]
    }})", global ? R"({ "mode": "global", "spp": 4, "max_bounces": 2 })" : R"({ "aa": 2 })", shininess));
}

TEST(PhongExponents, FiniteAndAgreeingForShininess0To1e6) {
    for (bool global : {false, true}) {
        for (double n : {0.0, 1.0, 1e4, 1e6}) {
            SCOPED_TRACE(fmt::format("{} mode, shininess {}", global ? "global" : "local", n));
            const Scene scene = shiny_sphere(n, global);
            const RenderOutcome cpu = test::render_cpu(scene);
            const RenderOutcome vulkan = test::render_vulkan(scene);
            test::expect_sane(cpu);
            test::expect_sane(vulkan);
            const float worst = test::max_abs_difference(cpu.image, vulkan.image);
            EXPECT_LE(worst, 1e-5f * std::max(1.0f, float(n) / 1000.0f));
        }
    }
}

// ------------------------------------------- case 10: stiff emitters, global mode

// A grey floor lit by one emitting sphere above it, out of the camera's view.
Scene floor_under_emitter(double radius, double emission) {
    return test::scene_from_text("emitter", fmt::format(R"({{
      "camera": {{ "eye": [0, 0.5, 3], "look_at": [0, 0, 0], "fov": 40, "width": 12, "height": 9 }},
      "render": {{ "mode": "global", "spp": 1024, "max_bounces": 1, "seed": 3 }},
      "materials": {{ "floor": {{ "diffuse": [0.5, 0.5, 0.5] }},
                     "lamp": {{ "diffuse": [0, 0, 0], "emission": [{}, {}, {}] }} }},
      "objects": [ {{ "type": "quad", "corner": [-20, 0, -20], "edge1": [0, 0, 40], "edge2": [40, 0, 0],
                      "material": "floor" }},
                   {{ "type": "sphere", "center": [0, 2, 0], "radius": {}, "material": "lamp" }} ]
    }})", emission, emission, emission, radius));
}

struct MeanAndError {
    double mean = 0.0;
    double standard_error = 0.0;
};

// The image's mean radiance (red) over all samples, and its standard error, through
// the reference kernel; every pixel sees the floor, so samples are comparable.
MeanAndError image_mean(const Scene& scene) {
    const FlatScene gpu = flatten_scene(scene);
    kernel::Kernel k = make_kernel(gpu);
    double sum = 0.0, sum2 = 0.0, n = 0.0;
    for (std::uint32_t y = 0; y < scene.camera.height; ++y) {
        for (std::uint32_t x = 0; x < scene.camera.width; ++x) {
            for (std::uint32_t i = 0; i < gpu.samples_per_pixel; ++i) {
                const double v = k.render_sample(x, y, i).radiance.x;
                sum += v;
                sum2 += v * v;
                n += 1.0;
            }
        }
    }
    const double mean = sum / n;
    return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / (n - 1.0))};
}

// A sphere of radius r and radiance L lights the points above its horizon like a
// point of intensity L pi r^2: shrinking r by 1000 and raising L by 10^6 keeps the
// floor's light, while the light samples now land on a sphere of radius 1e-4.
TEST(StiffEmitters, TinyEmitterOfHugeRadianceLightsLikeItsLargeTwin) {
    const MeanAndError large = image_mean(floor_under_emitter(0.1, 10.0));
    const MeanAndError tiny = image_mean(floor_under_emitter(1e-4, 1e7));
    EXPECT_GT(large.mean, 0.0);
    EXPECT_NEAR(tiny.mean, large.mean, 3.0 * std::hypot(tiny.standard_error, large.standard_error))
        << "standard errors " << tiny.standard_error << ", " << large.standard_error;
    test::expect_sane(test::render_vulkan(floor_under_emitter(1e-4, 1e7)));
}

// The loader refuses magnitudes above 1e12 (docs/scene-format.md); a scene built in
// code is not checked, so radiance 1e38 reaches the kernel. Products overflow to
// infinity there: such samples are discarded and counted, never summed, and a
// sample above the sums' range is clamped and counted. The image stays finite.
TEST(StiffEmitters, RadianceOf1e38GivesFinitePixels) {
    Scene scene = floor_under_emitter(0.1, 10.0);
    for (Material& m : scene.materials) {
        if (m.name == "lamp") m.emission = dvec3(1e38);
    }
    scene.camera.eye = dvec3(0.0, 3.0, 3.0);  // the lamp in view too, 15 degrees off the axis
    scene.camera.look_at = dvec3(0.0, 1.0, 0.0);
    scene.render.spp = 16;
    for (const RenderOutcome& out : {test::render_cpu(scene), test::render_vulkan(scene)}) {
        EXPECT_EQ(test::nonfinite_values(out.image), 0u);
        EXPECT_EQ(out.stats.truncated_samples, 0u);
        EXPECT_GT(out.stats.clamped_samples + out.stats.nonfinite_samples, 0u);
    }
}

}  // namespace
}  // namespace vkrt
