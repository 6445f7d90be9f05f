// Sampling the area lights by solid angle (shaders/kernel/solid_angle.glsl,
// emitters.glsl): the spherical rectangle and the sphere's cone against their
// closed-form solid angles and uniform densities, and the density a light sample
// states against the one multiple importance sampling computes when a ray hits the
// same light.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <random>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/constants.hpp>

#include "cpu/cpu_backend.hpp"
#include "flatten/flat_scene.hpp"
#include "image/image.hpp"
#include "image/image_files.hpp"
#include "kernel/kernel.hpp"
#include "statistics.hpp"
#include "test_support.hpp"

namespace {

using namespace vkrt;
using glm::dvec3;
using kernel::vec3;

constexpr double kPi = glm::pi<double>();

// The solid angle of triangle (a, b, c) seen from o: Van Oosterom & Strackee (1983).
double triangle_solid_angle(dvec3 o, dvec3 a, dvec3 b, dvec3 c) {
    a -= o, b -= o, c -= o;
    const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
    const double numerator = std::abs(glm::dot(a, glm::cross(b, c)));
    const double denominator = la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la;
    return 2.0 * std::atan2(numerator, denominator);
}

double rect_solid_angle(dvec3 o, dvec3 corner, dvec3 ex, dvec3 ey) {
    return triangle_solid_angle(o, corner, corner + ex, corner + ex + ey) +
           triangle_solid_angle(o, corner, corner + ex + ey, corner + ey);
}

struct RectCase {
    dvec3 o, corner, ex, ey;
};

// Seen from the front, the back, off to the side, close and grazing.
std::vector<RectCase> rect_cases() {
    std::vector<RectCase> cases = {
        {{0.2, -1.0, 0.3}, {0, 0, 0}, {1, 0, 0}, {0, 0, 1}},
        {{0.5, 1.0, 0.5}, {0, 0, 0}, {1, 0, 0}, {0, 0, 1}},
        {{3.0, -0.5, -2.0}, {0, 0, 0}, {1, 0, 0}, {0, 0, 2}},
        {{0.5, -0.01, 0.5}, {0, 0, 0}, {1, 0, 0}, {0, 0, 1}},
        {{-0.3, -0.2, 0.4}, {0, 0, 0}, {0.4, 0, 0}, {0, 0, 0.4}},
        {{0.0, 1.0, 3.4}, {-0.7, 1.99, -0.2}, {0.4, 0, 0}, {0, 0, 0.4}},  // scene K's lamp from the camera
    };
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-2.0, 2.0);
    for (int i = 0; i < 20; ++i) {
        const dvec3 ex{u(rng), u(rng), u(rng)};
        dvec3 ey = glm::cross(ex, dvec3{u(rng), u(rng), u(rng)});
        ey *= std::abs(u(rng)) / glm::length(ey);
        cases.push_back({{u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}, ex, ey});
    }
    return cases;
}

TEST(SphericalRect, SolidAngleMatchesTheTriangleFormula) {
    kernel::Kernel k;
    for (const RectCase& c : rect_cases()) {
        const double expected = rect_solid_angle(c.o, c.corner, c.ex, c.ey);
        const auto r = k.spherical_rect(vec3(c.o), vec3(c.corner), vec3(c.ex), vec3(c.ey));
        if (expected < 1e-3) continue;  // sampled by area there
        EXPECT_NEAR(r.solid_angle, expected, 2e-4 * expected) << c.o.x << " " << c.o.y << " " << c.o.z;
    }
}

// Points lie on the rectangle, and each of its 4 x 4 sub-rectangles receives its
// share of the solid angle: the density is 1 / solid angle.
TEST(SphericalRect, PointsAreOnTheRectangleAndUniformInSolidAngle) {
    kernel::Kernel k;
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (const RectCase& c : rect_cases()) {
        const double total = rect_solid_angle(c.o, c.corner, c.ex, c.ey);
        if (total < 1e-2 || total > 6.0) continue;
        SCOPED_TRACE(testing::Message() << "o = " << c.o.x << " " << c.o.y << " " << c.o.z);
        const auto r = k.spherical_rect(vec3(c.o), vec3(c.corner), vec3(c.ex), vec3(c.ey));
        constexpr int kSide = 4;
        constexpr int n = 32000;
        std::array<double, kSide * kSide> counts{};
        const double lx = glm::length(c.ex), ly = glm::length(c.ey);
        for (int i = 0; i < n; ++i) {
            const dvec3 p = dvec3(k.spherical_rect_point(r, unit(rng), unit(rng))) - c.corner;
            const double s = glm::dot(p, c.ex) / (lx * lx);
            const double t = glm::dot(p, c.ey) / (ly * ly);
            const double off = glm::dot(p, glm::cross(c.ex, c.ey)) / (lx * ly);
            ASSERT_NEAR(off, 0.0, 1e-4 * (1.0 + glm::length(c.corner - c.o)));
            ASSERT_GE(s, -1e-4);
            ASSERT_LE(s, 1.0 + 1e-4);
            ASSERT_GE(t, -1e-4);
            ASSERT_LE(t, 1.0 + 1e-4);
            counts[std::min(int(s * kSide), kSide - 1) + kSide * std::min(int(t * kSide), kSide - 1)] += 1.0;
        }
        std::array<double, kSide * kSide> expected;
        for (int j = 0; j < kSide; ++j) {
            for (int i = 0; i < kSide; ++i) {
                const dvec3 corner = c.corner + (double(i) / kSide) * c.ex + (double(j) / kSide) * c.ey;
                const double share = rect_solid_angle(c.o, corner, c.ex / double(kSide), c.ey / double(kSide)) / total;
                expected[i + kSide * j] = share * n;
            }
        }
        // A fair sampler fails one rectangle in ten thousand.
        const test::ChiSquareResult fit = test::chi_square_test(counts, expected);
        EXPECT_GT(fit.p_value, 1e-4) << fit;
    }
}

TEST(SphereCone, SolidAnglePointsAndDensity) {
    kernel::Kernel k;
    std::mt19937 rng(13);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const dvec3 center{0.5, -0.2, 0.1};
    for (double distance : {1.01, 1.5, 4.0, 100.0}) {
        const double radius = 1.0;
        const dvec3 o = center + distance * glm::normalize(dvec3{0.3, 0.9, -0.2});
        const auto cone = k.sphere_cone(vec3(o), vec3(center), float(radius));
        const double cos_max = std::sqrt(1.0 - radius * radius / (distance * distance));
        EXPECT_NEAR(k.sphere_cone_solid_angle(cone), 2.0 * kPi * (1.0 - cos_max), 1e-5 * 2.0 * kPi * (1.0 - cos_max));
        constexpr int kBins = 8;
        constexpr int n = 16000;
        std::array<int, kBins> bins{};
        for (int i = 0; i < n; ++i) {
            const dvec3 y(k.sphere_cone_point(vec3(o), cone, float(radius), unit(rng), unit(rng)));
            ASSERT_NEAR(glm::length(y - center), radius, 1e-4 * distance);
            ASSERT_GT(glm::dot(y - center, o - y), -1e-4 * distance) << "on the side facing o";
            // Uniform in solid angle: cos(theta) from the axis uniform in [cos_max, 1].
            const double cos_theta = glm::dot(glm::normalize(y - o), glm::normalize(center - o));
            ++bins[std::clamp(int((1.0 - cos_theta) / (1.0 - cos_max) * kBins), 0, kBins - 1)];
        }
        for (int b : bins) EXPECT_NEAR(b / double(n), 1.0 / kBins, 5.0 * std::sqrt(1.0 / kBins / n)) << distance;
    }
}

// Several kinds of lights, each sampled its own way, seen from points around them:
// a ray toward each light sample hits the light it came from, and the density
// light_pdf_of_hit gives that hit (what path tracing weighs a bounce with) is the
// sample's own. Among them a rectangle and a triangle with an emission texture
// (black and bright halves): their densities come from the texture's mean, never
// from the radiance at the point.
TEST(LightPdf, AHitOnALightHasTheDensityItsSampleStated) {
    Image halves(2, 1);
    halves.pixel(1, 0)[0] = halves.pixel(1, 0)[1] = halves.pixel(1, 0)[2] = 3.0f;
    const std::filesystem::path glow = test::temp_dir("light_pdf_texture") / "halves.exr";
    write_image(halves, glow);
    const Scene scene = test::scene_from_text("lights", R"({
      "camera": { "eye": [0, 0, 8], "look_at": [0, 0, 0], "width": 4, "height": 4 },
      "render": { "mode": "global" },
      "materials": { "lamp": { "emission": [2, 1, 1] }, "dim": { "emission": [0.2, 0.2, 0.2] },
                     "glow": { "emission": [1, 0.5, 0.5], "emission_texture": ")" + glow.string() + R"(" } },
      "objects": [
        { "type": "quad", "corner": [-1, 2, -1], "edge1": [2, 0, 0], "edge2": [0, 0, 1.5], "material": "lamp" },
        { "type": "quad", "corner": [2, -1, 0], "edge1": [0, 1, 0], "edge2": [0.5, 0.5, 1], "material": "dim" },
        { "type": "sphere", "center": [-2, 0, 0], "radius": 0.5, "material": "lamp" },
        { "type": "sphere", "center": [0, -20, 0], "radius": 0.05, "material": "lamp" },
        { "type": "triangle", "vertices": [[0, -2, 0], [1, -2, 0], [0, -2, 1]], "material": "dim" },
        { "type": "ring", "center": [0, 0, -2], "normal": [0, 0, 1], "inner": 0.2, "outer": 0.6, "material": "dim" },
        { "type": "quad", "corner": [-1, -1, 2], "edge1": [0, 1.5, 0], "edge2": [2, 0, 0], "material": "glow" },
        { "type": "triangle", "vertices": [[-2, 2, 0], [-2, 2, 1], [-1, 2, 0]], "material": "glow" }
      ]
    })");
    const FlatScene flat = flatten_scene(scene);
    ASSERT_EQ(flat.emitters.size(), 8u);
    kernel::Kernel k = make_kernel(flat);
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> spread(-1.5f, 1.5f);
    int compared = 0, textured = 0;
    for (int i = 0; i < 4000; ++i) {
        const vec3 o = vec3(spread(rng), spread(rng), spread(rng)) - vec3(flat.origin);
        auto r = k.rng_start(uint32_t(i), 0u, 3u);
        const auto y = k.sample_light(o, r);
        if (!(y.pdf > 0.0f)) continue;
        const vec3 to_light = y.position - o;
        const float distance = std::sqrt(glm::dot(to_light, to_light));
        const kernel::Kernel::Ray ray{o, to_light / distance};
        // Seen from behind there is no light; nearly edge-on, r^2 / cos turns the
        // rounding of two ways of computing the point into a large relative error.
        if (-glm::dot(y.normal, ray.dir) < 0.05f) continue;
        const auto hit = k.closest_hit(ray, kernel::INFINITY_T);
        if (!(std::abs(hit.t - distance) < 1e-3f * distance) || !hit.front_face) continue;  // blocked by another light
        const float pdf = k.light_pdf_of_hit(ray, hit);
        ASSERT_NEAR(pdf, y.pdf, 2e-3f * y.pdf) << "sample " << i;
        ++compared;
        textured += flat.materials[hit.material].emission_map != 0u ? 1 : 0;
    }
    EXPECT_GT(compared, 2000);
    EXPECT_GT(textured, 200);
}

// A quad whose edges are not perpendicular is a parallelogram, sampled by area.
TEST(LightPdf, AParallelogramIsNoRectangle) {
    Scene s;
    Material lamp;
    lamp.name = "lamp";
    lamp.emission = dvec3(1.0);
    s.materials = {lamp};
    s.triangles.push_back(quad({0, 0, 0}, {1, 0, 0}, {0.5, 0, 1}, 0));
    s.triangles.push_back(quad({0, 2, 0}, {1, 0, 0}, {0, 0, 1}, 0));
    const FlatScene g = flatten_scene(s);
    ASSERT_EQ(g.emitters.size(), 2u);
    EXPECT_EQ(g.triangles[0].meta.z, kernel::SHAPE_PARALLELOGRAM);
    EXPECT_EQ(g.triangles[1].meta.z, kernel::SHAPE_RECTANGLE);
    EXPECT_EQ(g.emitters[0].cdf.x, 0.5f);  // equal areas and radiance: equal power
    EXPECT_EQ(g.emitters[1].cdf.y, 0.5f);
}

}  // namespace
