// Spot and directional lights (kernel/lights.glsl) against closed forms, pixel by
// pixel through the reference backend: a Lambertian floor under each, in global mode
// (physical: rho / pi * irradiance) and in local mode (the paper's Phong, no
// fall-off); a directional light's shadow cast by an occluder far up its beam; and
// the Vulkan backend against the reference on a scene with every kind of light.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <string>

#include <fmt/format.h>
#include <glm/glm.hpp>

#include "cpu/cpu_backend.hpp"
#include "flatten/flat_scene.hpp"
#include "kernel/kernel.hpp"
#include "render/render.hpp"
#include "test_support.hpp"

namespace vkrt {
namespace {

using glm::dvec3;

constexpr double kRho = 0.6;
constexpr std::uint32_t kWidth = 32, kHeight = 24;

// A floor y = 0 of albedo kRho seen from above, under `lights` (a JSON array), with
// more `objects` and a `floor` material as given. Global mode takes one sample per
// pixel through its centre and one bounce: the next-event estimate at the floor is
// the whole image, as the sky is black.
Scene floor_scene(bool global, const std::string& lights, const std::string& objects = "",
                  const std::string& floor = R"({ "diffuse": [0.6, 0.6, 0.6] })") {
    const std::string render = global ? R"({ "mode": "global", "spp": 1, "jitter": false, "max_bounces": 1 })"
                                      : R"({ "aa": 1 })";
    return test::scene_from_text("floor", fmt::format(R"({{
      "camera": {{ "eye": [0, 5, 3], "look_at": [0, 0, 0], "fov": 50, "width": {}, "height": {} }},
      "render": {},
      "materials": {{ "floor": {}, "stone": {{ "diffuse": [0.5, 0.5, 0.5] }} }},
      "lights": {},
      "objects": [ {{ "type": "quad", "corner": [-50, 0, -50], "edge1": [0, 0, 100], "edge2": [100, 0, 0],
                     "material": "floor" }}{} ]
    }})", kWidth, kHeight, render, floor, lights, objects));
}

// Where pixel (x, y)'s centre ray meets the floor, in the scene's coordinates and in
// double, and the unit direction back to the eye.
struct FloorPoint {
    dvec3 p;
    dvec3 to_eye;
};

FloorPoint floor_point(kernel::Kernel& k, const FlatScene& flat, std::uint32_t x, std::uint32_t y) {
    const kernel::Kernel::Ray ray = k.camera_ray(float(x) + 0.5f, float(y) + 0.5f);
    const dvec3 origin = dvec3(ray.origin) + flat.origin, dir(ray.dir);
    EXPECT_LT(dir.y, 0.0) << "pixel " << x << "," << y << " sees the floor";
    return {origin + (-origin.y / dir.y) * dir, -glm::normalize(dir)};
}

// glTF KHR_lights_punctual's cone: the square of the linear ramp in the cosine.
double cone(double cos_axis, double inner, double outer) {
    const double t = std::clamp((cos_axis - std::cos(outer)) / (std::cos(inner) - std::cos(outer)), 0.0, 1.0);
    return t * t;
}

// Every pixel of the reference's render against `expected` (radiance of the grey
// floor at a point), within 1e-5 of the brightest value.
void expect_floor(const Scene& scene, const std::function<double(const FloorPoint&)>& expected) {
    const FlatScene flat = flatten_scene(scene);
    kernel::Kernel k = make_kernel(flat);
    const RenderOutcome cpu = test::render_cpu(scene);
    double peak = 0.0;
    for (std::uint32_t y = 0; y < kHeight; ++y) {
        for (std::uint32_t x = 0; x < kWidth; ++x) peak = std::max(peak, expected(floor_point(k, flat, x, y)));
    }
    ASSERT_GT(peak, 0.0);
    for (std::uint32_t y = 0; y < kHeight; ++y) {
        for (std::uint32_t x = 0; x < kWidth; ++x) {
            const double want = expected(floor_point(k, flat, x, y));
            const std::size_t i = 3 * (std::size_t(y) * kWidth + x);
            EXPECT_NEAR(cpu.image.rgb[i], want, 1e-5 * peak) << "pixel " << x << "," << y;
        }
    }
}

// ------------------------------------------------------------------ directional

const dvec3 kSunTravels = glm::normalize(dvec3(1, -2, 0.5));  // the way its light travels
constexpr double kIrradiance = 2.5;
const std::string kSun = R"([{ "type": "directional", "direction": [1, -2, 0.5], "intensity": 2.5 }])";

TEST(DirectionalLight, GlobalLambertianFloorShowsRhoOverPiTimesIrradianceTimesCos) {
    const double cos_theta = -kSunTravels.y;
    expect_floor(floor_scene(true, kSun), [&](const FloorPoint&) { return kRho / M_PI * kIrradiance * cos_theta; });
}

TEST(DirectionalLight, LocalFloorShowsThePapersTermWithoutFalloff) {
    const double cos_theta = -kSunTravels.y;
    expect_floor(floor_scene(false, kSun), [&](const FloorPoint&) { return kRho * kIrradiance * cos_theta; });
}

// A sphere 200 units up the beam shadows the floor: the shadow ray toward a
// directional light has no end. Pixels whose ray to the light passes within 1e-3 of
// the sphere's silhouette are left out: there float rounding decides.
TEST(DirectionalLight, AnOccluderFarUpTheBeamCastsItsShadow) {
    const dvec3 centre = -200.0 * kSunTravels;
    constexpr double kRadius = 0.8;
    const Scene scene = floor_scene(
        false, kSun,
        fmt::format(R"(, {{ "type": "sphere", "center": [{}, {}, {}], "radius": {}, "material": "stone" }})",
                    centre.x, centre.y, centre.z, kRadius));
    const FlatScene flat = flatten_scene(scene);
    kernel::Kernel k = make_kernel(flat);
    const RenderOutcome cpu = test::render_cpu(scene);
    const double lit = kRho * kIrradiance * -kSunTravels.y;
    int shadowed = 0, in_light = 0;
    for (std::uint32_t y = 0; y < kHeight; ++y) {
        for (std::uint32_t x = 0; x < kWidth; ++x) {
            const dvec3 p = floor_point(k, flat, x, y).p;
            // The distance from the sphere's centre to the line from p toward the light.
            const dvec3 to_centre = centre - p;
            const double miss = glm::length(to_centre - glm::dot(to_centre, -kSunTravels) * -kSunTravels);
            if (std::abs(miss - kRadius) < 1e-3) continue;
            const bool shadow = miss < kRadius;
            (shadow ? shadowed : in_light) += 1;
            const float got = cpu.image.rgb[3 * (std::size_t(y) * kWidth + x)];
            EXPECT_NEAR(got, shadow ? 0.0 : lit, 1e-5) << "pixel " << x << "," << y << (shadow ? " in shadow" : " lit");
        }
    }
    EXPECT_GT(shadowed, 20);
    EXPECT_GT(in_light, 20);
}

// ------------------------------------------------------------------------- spot

const dvec3 kSpotAt(0.2, 2.0, -0.1);
const dvec3 kSpotAxis = glm::normalize(dvec3(0.3, -1, 0.2));
const double kInner = glm::radians(20.0), kOuter = glm::radians(35.0);
constexpr double kSpotIntensity = 3.0;
const std::string kSpot = R"([{ "type": "spot", "position": [0.2, 2.0, -0.1], "direction": [0.3, -1, 0.2],
                                "inner_angle": 20, "outer_angle": 35, "intensity": 3 }])";

struct SpotView {
    dvec3 l;         // unit, from the point toward the light
    double r2;       // squared distance
    double cos_axis; // of the angle between the spot's axis and the way to the point
};

SpotView spot_view(const dvec3& p) {
    const dvec3 to = kSpotAt - p;
    const double r2 = glm::dot(to, to);
    const dvec3 l = to / std::sqrt(r2);
    return {l, r2, glm::dot(kSpotAxis, -l)};
}

// The floor must show all three parts of the cone.
TEST(SpotLight, TheTestViewSeesTheInnerConeTheFalloffAndTheDark) {
    const Scene scene = floor_scene(true, kSpot);
    const FlatScene flat = flatten_scene(scene);
    kernel::Kernel k = make_kernel(flat);
    int inside = 0, between = 0, outside = 0;
    for (std::uint32_t y = 0; y < kHeight; ++y) {
        for (std::uint32_t x = 0; x < kWidth; ++x) {
            const double c = spot_view(floor_point(k, flat, x, y).p).cos_axis;
            if (c >= std::cos(kInner)) ++inside;
            else if (c > std::cos(kOuter)) ++between;
            else ++outside;
        }
    }
    EXPECT_GT(inside, 20);
    EXPECT_GT(between, 20);
    EXPECT_GT(outside, 20);
}

TEST(SpotLight, GlobalFloorShowsTheConeTimesIntensityCosOverR2) {
    expect_floor(floor_scene(true, kSpot), [](const FloorPoint& f) {
        const SpotView v = spot_view(f.p);
        return kRho / M_PI * kSpotIntensity * cone(v.cos_axis, kInner, kOuter) * v.l.y / v.r2;
    });
}

// The paper's Phong term, times the cone, with no fall-off: diffuse and a highlight.
TEST(SpotLight, LocalFloorShowsThePapersPhongTimesTheCone) {
    constexpr double kKs = 0.5, kShininess = 8.0;
    const Scene scene =
        floor_scene(false, kSpot, "", R"({ "diffuse": [0.6, 0.6, 0.6], "specular": [1, 1, 1], "ks": 0.5, "shininess": 8 })");
    expect_floor(scene, [&](const FloorPoint& f) {
        const SpotView v = spot_view(f.p);
        const dvec3 n(0, 1, 0);
        const dvec3 mirrored = 2.0 * v.l.y * n - v.l;
        const double cos_alpha = glm::dot(mirrored, f.to_eye);
        const double specular = cos_alpha > 0.0 ? kKs * std::pow(cos_alpha, kShininess) : 0.0;
        return kSpotIntensity * cone(v.cos_axis, kInner, kOuter) * (kRho * v.l.y + specular);
    });
}

// A spot sends no shadow ray toward what lies outside its outer cone.
TEST(SpotLight, NoShadowRayOutsideTheCone) {
    const Scene narrow = floor_scene(false, R"([{ "type": "spot", "position": [0, 2, 0], "direction": [0, -1, 0],
                                                  "outer_angle": 5 }])");
    const Scene point = floor_scene(false, R"([{ "type": "point", "position": [0, 2, 0] }])");
    const RenderOutcome a = test::render_cpu(narrow), b = test::render_cpu(point);
    EXPECT_EQ(b.stats.shadow_rays, std::uint64_t(kWidth) * kHeight);
    EXPECT_GT(a.stats.shadow_rays, 0u);
    EXPECT_LT(a.stats.shadow_rays, std::uint64_t(kWidth) * kHeight / 10);
}

// ------------------------------------------------------------------ the backends

// Every kind of light at once, with a sphere casting a shadow from each: the Vulkan
// backend's image is the reference's, in both modes.
TEST(PunctualLightBackends, VulkanMatchesTheReference) {
    const std::string lights = R"([
        { "type": "point", "position": [-1, 2, 1], "intensity": 0.5 },
        { "type": "spot", "position": [0.2, 2.0, -0.1], "direction": [0.3, -1, 0.2], "inner_angle": 20,
          "outer_angle": 35, "color": [1, 0.8, 0.6], "intensity": 3 },
        { "type": "directional", "direction": [1, -2, 0.5], "color": [0.5, 0.6, 1], "intensity": 0.7 } ])";
    const std::string sphere = R"(, { "type": "sphere", "center": [0.3, 0.5, 0], "radius": 0.5, "material": "stone" })";
    for (const bool global : {false, true}) {
        SCOPED_TRACE(global ? "global" : "local");
        Scene scene = floor_scene(global, lights, sphere,
                                  R"({ "diffuse": [0.6, 0.6, 0.6], "specular": [1, 1, 1], "ks": 0.3, "shininess": 12 })");
        if (global) {
            scene.render.spp = 4;
            scene.render.max_bounces = 3;
        }
        const FlatScene flat = flatten_scene(scene);
        EXPECT_TRUE(flat.features.has(Feature::HAS_DIRECTED_LIGHTS));
        const RenderOutcome cpu = test::render_cpu(scene);
        const RenderOutcome vulkan = test::render_vulkan(scene);
        double mean = 0.0;
        for (float v : cpu.image.rgb) mean += v;
        EXPECT_GT(mean / double(cpu.image.rgb.size()), 0.05);
        EXPECT_LT(test::max_abs_difference(cpu.image, vulkan.image), 1e-4);
        EXPECT_EQ(cpu.stats.shadow_rays, vulkan.stats.shadow_rays);
    }
}

}  // namespace
}  // namespace vkrt
