// Lit pixel values computed by hand, in double precision and with a camera model
// written independently of the kernel's, checked on both backends within 1e-4.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include <glm/glm.hpp>

#include "test_support.hpp"

namespace {

using namespace vkrt;
using glm::dvec3;

constexpr std::uint32_t kSize = 15;

// One shiny sphere, one coloured point light, ambient light, and a background.
Scene probe_scene() {
    Scene s;
    s.camera.eye = {0, 0, 5};
    s.camera.look_at = {0, 0, 0};
    s.camera.fov = 30;
    s.camera.width = kSize;
    s.camera.height = kSize;
    s.render.ambient = {0.1, 0.05, 0.02};
    s.render.background = {0.2, 0.3, 0.4};
    Material m;
    m.name = "probe";
    m.diffuse = {0.8, 0.6, 0.4};
    m.kd = 0.9;
    m.specular = {1.0, 0.9, 0.8};
    m.ks = 0.5;
    m.shininess = 10;
    s.materials.push_back(m);
    s.lights.push_back(Light{{2, 3, 6}, {1.0, 0.9, 0.8}, 1.5});
    s.spheres.push_back(Sphere{{0, 0, 0}, 1.0, 0});
    return s;
}

// The ray through the centre of pixel (px, py), from the field of view directly.
dvec3 pixel_direction(const Camera& c, std::uint32_t px, std::uint32_t py) {
    const dvec3 forward = glm::normalize(c.look_at - c.eye);
    const dvec3 right = glm::normalize(glm::cross(forward, c.up));
    const dvec3 up = glm::cross(right, forward);
    const double h = std::tan(glm::radians(c.fov) / 2.0);
    const double aspect = double(c.width) / c.height;
    const double sx = ((px + 0.5) / c.width * 2.0 - 1.0) * h * aspect;
    const double sy = (1.0 - (py + 0.5) / c.height * 2.0) * h;
    return glm::normalize(forward + sx * right + sy * up);
}

// The paper's local model at the first hit; nullopt near the silhouette, where a
// float/double difference could flip hit and miss.
std::optional<dvec3> expected_radiance(const Scene& s, std::uint32_t px, std::uint32_t py) {
    const dvec3 o = s.camera.eye;
    const dvec3 d = pixel_direction(s.camera, px, py);
    const Sphere& sp = s.spheres[0];
    const double b = glm::dot(o - sp.center, d);
    const double closest = glm::length(o - sp.center - b * d);
    if (closest > 0.97 * sp.radius) return std::nullopt;
    const double t = -b - std::sqrt(sp.radius * sp.radius - closest * closest);
    const dvec3 p = o + t * d;
    const dvec3 n = (p - sp.center) / sp.radius;
    const Material& m = s.materials[0];
    dvec3 color = s.render.ambient * m.kd * m.diffuse;
    const Light& light = s.lights[0];
    const dvec3 l = glm::normalize(light.position - p);
    const double cos_theta = glm::dot(n, l);
    if (cos_theta > 0.0) {
        const dvec3 r = 2.0 * cos_theta * n - l;
        const double cos_alpha = std::max(0.0, glm::dot(r, -d));
        color += light.color * light.intensity *
                 (m.kd * m.diffuse * cos_theta + m.ks * m.specular * std::pow(cos_alpha, m.shininess));
    }
    return color;
}

void check_probe(const RenderOutcome& out, const Scene& scene) {
    int lit = 0;
    int checked = 0;
    for (std::uint32_t y = 0; y < kSize; ++y) {
        for (std::uint32_t x = 0; x < kSize; ++x) {
            const float* got = out.image.pixel(x, y);
            const auto want = expected_radiance(scene, x, y);
            if (!want) continue;
            ++checked;
            if (want->r > 0.2) ++lit;
            EXPECT_NEAR(got[0], want->r, 1e-4) << "pixel " << x << "," << y;
            EXPECT_NEAR(got[1], want->g, 1e-4) << "pixel " << x << "," << y;
            EXPECT_NEAR(got[2], want->b, 1e-4) << "pixel " << x << "," << y;
        }
    }
    EXPECT_GT(checked, 50);  // the sphere fills much of the frame
    EXPECT_GT(lit, 20);
    // A corner pixel sees the background, exactly.
    EXPECT_EQ(out.image.pixel(0, 0)[0], 0.2f);
    EXPECT_EQ(out.image.pixel(0, 0)[2], 0.4f);
}

TEST(PixelProbe, ReferenceMatchesHandComputedShading) {
    const Scene scene = probe_scene();
    check_probe(test::render_cpu(scene), scene);
}

TEST(PixelProbe, VulkanMatchesHandComputedShading) {
    const Scene scene = probe_scene();
    const RenderOutcome out = test::render_vulkan(scene);
    EXPECT_EQ(out.stats.validation_messages, 0u);
    check_probe(out, scene);
}

// A lamp placed exactly on the ceiling must light the floor: the shadow ray toward it
// must not be stopped by the ceiling it sits on.
Scene lamp_on_ceiling(bool shadows) {
    Scene s;
    s.camera.eye = {0, 1, 3};
    s.camera.look_at = {0, 0.3, 0};
    s.camera.width = 16;
    s.camera.height = 12;
    s.render.shadows = shadows;
    Material m;
    m.diffuse = {0.7, 0.7, 0.7};
    s.materials.push_back(m);
    s.lights.push_back(Light{{0.1, 2.0, 0.2}, {1, 1, 1}, 1.0});
    auto quad = [&](dvec3 corner, dvec3 e1, dvec3 e2) {
        s.triangles.push_back(Triangle{{corner, corner + e1, corner + e1 + e2}, std::nullopt, 0});
        s.triangles.push_back(Triangle{{corner, corner + e1 + e2, corner + e2}, std::nullopt, 0});
    };
    quad({-3, 0, 3}, {6, 0, 0}, {0, 0, -6});  // floor, facing up
    quad({-3, 2, -3}, {6, 0, 0}, {0, 0, 6});  // ceiling, facing down, through the lamp
    return s;
}

TEST(PixelProbe, LampOnTheCeilingLightsTheFloor) {
    const RenderOutcome unshadowed = test::render_cpu(lamp_on_ceiling(false));
    for (const bool vulkan : {false, true}) {
        const Scene scene = lamp_on_ceiling(true);
        const RenderOutcome out = vulkan ? test::render_vulkan(scene) : test::render_cpu(scene);
        EXPECT_GT(out.image.pixel(8, 9)[0], 0.1f) << (vulkan ? "vulkan" : "cpu");
        for (std::size_t i = 0; i < out.image.rgb.size(); ++i) {
            ASSERT_NEAR(out.image.rgb[i], unshadowed.image.rgb[i], 1e-5) << (vulkan ? "vulkan" : "cpu") << " value " << i;
        }
    }
}

}  // namespace
