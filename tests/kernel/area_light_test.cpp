// Area lights in local mode (kernel/area_lights.glsl): emissive primitives lighting
// other surfaces, checked against irradiance computed in closed form, on both
// backends, and for the determinism of their random numbers.
//
// A probe looks at one point of a Lambertian floor through a very narrow camera:
// every pixel sees the same point (to within 1e-5) with its own random stream, so the
// pixels are independent estimates of one radiance, and their spread gives the
// standard error that the tolerances are made of.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <set>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/constants.hpp>

#include "gpu/vulkan_backend.hpp"
#include "image/compare.hpp"
#include "kernel/kernel.hpp"
#include "cpu/cpu_backend.hpp"
#include "render/pixel_sums.hpp"
#include "flatten/flat_scene.hpp"
#include "test_support.hpp"

namespace {

using namespace vkrt;
using glm::dvec3;

constexpr double kPi = glm::pi<double>();
constexpr double kAlbedo = 0.5;  // the floor's diffuse reflectance, kd = 1
constexpr std::uint32_t kProbeSide = 16;

void add_quad(Scene& s, dvec3 corner, dvec3 e1, dvec3 e2, std::uint32_t material) {
    s.triangles.push_back(quad(corner, e1, e2, material));
}

// A grey Lambertian floor (material 0, y = 0, facing up) and an emissive material 1
// of radiance `le`, no point lights, no ambient.
Scene floor_scene(double le) {
    Scene s;
    Material floor;
    floor.name = "floor";
    floor.diffuse = dvec3(kAlbedo);
    Material lamp;
    lamp.name = "lamp";
    lamp.emission = dvec3(le);
    s.materials = {floor, lamp};
    add_quad(s, {-20, 0, -20}, {0, 0, 40}, {40, 0, 0}, 0);
    s.render.spp = 64;
    s.render.light_samples = 16;
    return s;
}

// A quad lamp parallel to the floor at height h, centred above (cx, cz), a by b,
// facing down (or up, when `facing_down` is false).
void add_lamp(Scene& s, double cx, double cz, double a, double b, double h, bool facing_down = true) {
    const dvec3 corner{cx - a / 2, h, cz - b / 2};
    if (facing_down) {
        add_quad(s, corner, {a, 0, 0}, {0, 0, b}, 1);  // cross = (0, -ab, 0)
    } else {
        add_quad(s, corner, {0, 0, b}, {a, 0, 0}, 1);
    }
}

struct Estimate {
    double mean = 0.0;   // red channel, averaged over the probe's pixels
    double error = 0.0;  // standard error of that mean
    RenderStats stats;
};

// The radiance leaving `point` toward `eye`, estimated by kProbeSide^2 independent
// pixels.
Estimate probe(Scene s, dvec3 point, dvec3 eye, bool vulkan = false) {
    s.camera.eye = eye;
    s.camera.look_at = point;
    s.camera.fov = 1e-3;
    s.camera.width = kProbeSide;
    s.camera.height = kProbeSide;
    const RenderOutcome out = vulkan ? test::render_vulkan(s) : test::render_cpu(s);
    EXPECT_EQ(out.stats.truncated_samples, 0u);
    EXPECT_EQ(out.stats.nonfinite_samples, 0u);
    const std::size_t n = std::size_t(kProbeSide) * kProbeSide;
    double sum = 0.0;
    double sum2 = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const double v = out.image.rgb[3 * i];
        sum += v;
        sum2 += v * v;
    }
    Estimate e;
    e.mean = sum / double(n);
    const double variance = std::max(0.0, (sum2 - sum * e.mean) / double(n - 1));
    e.error = std::sqrt(variance / double(n));
    e.stats = out.stats;
    return e;
}

// Irradiance at p (normal n) from a convex polygon of uniform radiance le, all of it
// above p's horizon: Lambert's formula, E = le/2 * sum over edges of the angle the
// edge subtends at p times the cosine between n and the normal of the plane through
// p and the edge.
double lambert_irradiance(const std::vector<dvec3>& polygon, dvec3 p, dvec3 n, double le) {
    double sum = 0.0;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const dvec3 u = glm::normalize(polygon[i] - p);
        const dvec3 w = glm::normalize(polygon[(i + 1) % polygon.size()] - p);
        sum += std::acos(std::clamp(glm::dot(u, w), -1.0, 1.0)) * glm::dot(n, glm::normalize(glm::cross(u, w)));
    }
    return le / 2.0 * std::abs(sum);
}

std::vector<dvec3> rectangle(double x0, double x1, double z0, double z1, double h) {
    return {{x0, h, z0}, {x1, h, z0}, {x1, h, z1}, {x0, h, z1}};
}

// Irradiance at the point a distance h below the centre of a parallel a x b
// rectangle of radiance le. The differential-area-to-rectangle form factor with the
// normal through a corner is F = 1/(2 pi) [X/sqrt(1+X^2) atan(Y/sqrt(1+X^2)) +
// Y/sqrt(1+Y^2) atan(X/sqrt(1+Y^2))], X and Y the sides over h; below the centre the
// rectangle is four such quarters of sides a/2, b/2, and E = pi le * 4F.
double rectangle_centre_irradiance(double a, double b, double h, double le) {
    const double x = a / (2.0 * h);
    const double y = b / (2.0 * h);
    const double sx = std::sqrt(1.0 + x * x);
    const double sy = std::sqrt(1.0 + y * y);
    return 2.0 * le * (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy));
}

// Lambertian radiance under irradiance e: kd * diffuse / pi * e (the 1/pi convention).
double radiance(double irradiance) { return kAlbedo / kPi * irradiance; }

// How close an estimate can come to a closed form: its standard errors, but no
// closer than the kernel's single precision allows (a light sampled by solid angle,
// with Sobol points, leaves almost no noise to hide rounding in).
double tolerance(const Estimate& e, double want) { return std::max(4.0 * e.error, 1e-4 * want); }

// --------------------------------------------------------------- the closed forms

TEST(AreaLightFormulas, RectangleClosedFormAgreesWithLambertsFormula) {
    for (const auto& [a, b, h] : {std::array<double, 3>{4, 4, 1}, {1, 3, 2}, {0.2, 0.1, 5}}) {
        const double closed = rectangle_centre_irradiance(a, b, h, 1.0);
        const double lambert = lambert_irradiance(rectangle(-a / 2, a / 2, -b / 2, b / 2, h), {0, 0, 0}, {0, 1, 0}, 1.0);
        EXPECT_NEAR(closed, lambert, 1e-12 * lambert) << a << " x " << b << " at " << h;
    }
    // A rectangle that fills the sky gives pi * le, the irradiance of a uniform sky.
    EXPECT_NEAR(rectangle_centre_irradiance(1e7, 1e7, 1.0, 1.0), kPi, 1e-6);
}

// ------------------------------------------------------------- analytic radiances

// (a) A small emitting sphere straight above the floor. A sphere of radiance le seen
// under the half-angle asin(R/d) gives, on a surface facing its centre, exactly
// E = pi le (R/d)^2: no small-angle approximation involved.
TEST(AreaLight, SphereAboveTheFloorGivesTheExactIrradiance) {
    Scene s = floor_scene(10.0);
    s.spheres.push_back(Sphere{{0, 2, 0}, 0.25, 1});
    const Estimate e = probe(s, {0, 0, 0}, {0, 1, 3});
    const double want = radiance(kPi * 10.0 * (0.25 / 2.0) * (0.25 / 2.0));
    std::printf("sphere: %.6f +- %.6f, exact %.6f\n", e.mean, e.error, want);
    EXPECT_GT(e.error, 0.0);
    EXPECT_LT(e.error, 0.01 * want);  // the test has power: a 4% error would fail it
    EXPECT_NEAR(e.mean, want, tolerance(e, want));
}

// A disc of radius R at height h, facing down, centred above the point: E = pi le R^2
// / (h^2 + R^2) (the classic disc form factor). As a ring with a hole of radius a,
// the difference of two discs. A capped cylinder standing above the point lights it
// through its base cap alone (its side faces away from its axis, so from below only
// its back would be seen), and an open one not at all: emission leaves front faces.
TEST(AreaLight, RingsAndCylindersAreLightsToo) {
    const double le = 10.0, h = 2.0, outer = 0.6, inner = 0.3;
    auto disc = [&](double r) { return kPi * le * r * r / (h * h + r * r); };
    const dvec3 point{0, 0, 0}, eye{0, 1, 3};
    {
        Scene s = floor_scene(le);
        s.rings.push_back(Ring{{0, h, 0}, {0, -1, 0}, inner, outer, 1});
        const Estimate e = probe(s, point, eye);
        const double want = radiance(disc(outer) - disc(inner));
        std::printf("ring: %.6f +- %.6f, exact %.6f\n", e.mean, e.error, want);
        EXPECT_LT(e.error, 0.02 * want);
        EXPECT_NEAR(e.mean, want, tolerance(e, want));
        const Estimate v = probe(s, point, eye, true);
        EXPECT_NEAR(v.mean, e.mean, 1e-4 * want) << "the same samples on Vulkan";
    }
    {
        Scene s = floor_scene(le);
        s.cylinders.push_back(Cylinder{{0, h, 0}, {0, h + 1.0, 0}, outer, true, 1});
        const Estimate e = probe(s, point, eye);
        const double want = radiance(disc(outer));
        std::printf("capped cylinder: %.6f +- %.6f, exact %.6f\n", e.mean, e.error, want);
        EXPECT_LT(e.error, 0.05 * want);
        EXPECT_NEAR(e.mean, want, tolerance(e, want));
        s.cylinders[0].capped = false;
        EXPECT_EQ(probe(s, point, eye).mean, 0.0);
    }
}

// (a) A small triangle far above, facing down, centroid straight above the point.
// The small-solid-angle value le A cos cos' / r^2 = le A / h^2 is not exact, but the
// integrand cos cos' / r^2 = h^2 / r^4 lies between h^2 / r_max^4 and 1 / h^2 over
// the triangle, which brackets the true irradiance; the bracket is the tolerance.
TEST(AreaLight, SmallTriangleFarAboveMatchesTheSolidAngleApproximation) {
    const double le = 50.0;
    const double h = 3.0;
    Scene s = floor_scene(le);
    const std::array<dvec3, 3> v{dvec3{-0.1, h, -0.0577350269}, dvec3{0.1, h, -0.0577350269}, dvec3{0, h, 0.1154700538}};
    s.triangles.push_back(Triangle{v, std::nullopt, 1});  // cross(v1 - v0, v2 - v0) points down
    const double area = 0.5 * glm::length(glm::cross(v[1] - v[0], v[2] - v[0]));
    double r_max = 0.0;
    for (const dvec3& p : v) r_max = std::max(r_max, glm::length(p));
    const double approx = radiance(le * area / (h * h));
    const double lower = radiance(le * area * h * h / std::pow(r_max, 4));
    const Estimate e = probe(s, {0, 0, 0}, {0, 1, 3});
    std::printf("triangle: %.6f +- %.6f, bracket [%.6f, %.6f]\n", e.mean, e.error, lower, approx);
    EXPECT_LT(approx - lower, 0.01 * approx);  // a small light indeed
    EXPECT_GT(e.mean, lower - 4.0 * e.error);
    EXPECT_LT(e.mean, approx + 4.0 * e.error);
    // Every light sample of a flat light wholly above the point passes the facing
    // tests and sends its shadow ray: the count is exact.
    EXPECT_EQ(e.stats.shadow_rays, std::uint64_t(kProbeSide) * kProbeSide * 64 * 16);
}

// (b) A 4 x 4 quad one unit above the point: a light filling most of the sky, against
// the closed form, on both backends.
void expect_large_quad(bool vulkan) {
    Scene s = floor_scene(1.0);
    add_lamp(s, 0, 0, 4, 4, 1);
    const Estimate e = probe(s, {0, 0, 0}, {0.5, 0.5, 3}, vulkan);
    const double want = radiance(rectangle_centre_irradiance(4, 4, 1, 1.0));
    std::printf("large quad (%s): %.6f +- %.6f, closed form %.6f\n", vulkan ? "vulkan" : "cpu", e.mean, e.error, want);
    EXPECT_GT(e.error, 0.0);
    EXPECT_LT(e.error, 0.01 * want);
    EXPECT_NEAR(e.mean, want, tolerance(e, want));
    EXPECT_EQ(e.stats.shadow_rays, std::uint64_t(kProbeSide) * kProbeSide * 64 * 16);
}

TEST(AreaLight, LargeQuadMatchesTheRectangleClosedFormOnTheReference) { expect_large_quad(false); }
TEST(AreaLight, LargeQuadMatchesTheRectangleClosedFormOnVulkan) { expect_large_quad(true); }

// (c) Emission leaves the front face only: the same quad turned to face up lights
// nothing below it, and no shadow ray is even sent.
TEST(AreaLight, AQuadFacingAwayLightsNothing) {
    for (const bool vulkan : {false, true}) {
        Scene s = floor_scene(1.0);
        add_lamp(s, 0, 0, 4, 4, 1, false);
        const Estimate e = probe(s, {0, 0, 0}, {0.5, 0.5, 3}, vulkan);
        EXPECT_EQ(e.mean, 0.0) << (vulkan ? "vulkan" : "cpu");
        EXPECT_EQ(e.stats.shadow_rays, 0u) << (vulkan ? "vulkan" : "cpu");
    }
}

// A surface that reflects nothing sends no light samples: a black emitting sphere
// facing a second lamp shows its own emission and costs no shadow ray.
TEST(AreaLight, ABlackSurfaceSendsNoShadowRays) {
    Scene s = floor_scene(2.0);
    s.spheres.push_back(Sphere{{0, 1, 0}, 0.5, 1});
    add_lamp(s, 3, 0, 1, 1, 3);  // above and beside the sphere's top, facing down
    const Estimate e = probe(s, {0, 1.5, 0}, {0, 4, 0.5});
    EXPECT_EQ(e.mean, 2.0);
    EXPECT_EQ(e.stats.shadow_rays, 0u);
}

// (d) Soft shadows. A 1 x 1 lamp at height 2 over a blocker strip at height 1 that
// covers x in [-0.5, 0.5] (and all z that matter): the floor at x = 0 sees none of
// the lamp (umbra), at x = 2.5 all of it, and at x = 1 exactly the part x > 0 of it,
// whose irradiance Lambert's formula gives.
Scene penumbra_scene(bool blocker = true) {
    Scene s = floor_scene(5.0);
    add_lamp(s, 0, 0, 1, 1, 2);
    if (blocker) add_quad(s, {-0.5, 1, -5}, {1, 0, 0}, {0, 0, 10}, 0);
    return s;
}

Estimate penumbra_probe(double x, bool blocker = true) {
    return probe(penumbra_scene(blocker), {x, 0, 0}, {x, 0.3, 4});
}

TEST(AreaLight, PenumbraLiesStrictlyBetweenUmbraAndFullLight) {
    const Estimate umbra = penumbra_probe(0.0);
    const Estimate penumbra = penumbra_probe(1.0);
    const Estimate unblocked = penumbra_probe(1.0, false);
    const Estimate lit = penumbra_probe(2.5);
    const dvec3 up{0, 1, 0};
    const auto lamp = rectangle(-0.5, 0.5, -0.5, 0.5, 2);
    const double want_penumbra = radiance(lambert_irradiance(rectangle(0.0, 0.5, -0.5, 0.5, 2), {1, 0, 0}, up, 5.0));
    const double want_unblocked = radiance(lambert_irradiance(lamp, {1, 0, 0}, up, 5.0));
    const double want_lit = radiance(lambert_irradiance(lamp, {2.5, 0, 0}, up, 5.0));
    std::printf("at x = 1: penumbra %.6f +- %.6f (exact %.6f), without the blocker %.6f +- %.6f (exact %.6f)\n"
                "umbra %.6f; fully lit at x = 2.5: %.6f +- %.6f (exact %.6f)\n",
                penumbra.mean, penumbra.error, want_penumbra, unblocked.mean, unblocked.error, want_unblocked,
                umbra.mean, lit.mean, lit.error, want_lit);
    EXPECT_EQ(umbra.mean, 0.0);
    // The lamp's nearer half is visible from x = 1: 59.5% of its light, well away
    // from both ends.
    EXPECT_GT(penumbra.mean, 0.25 * unblocked.mean);
    EXPECT_LT(penumbra.mean, 0.75 * unblocked.mean);
    EXPECT_NEAR(penumbra.mean, want_penumbra, tolerance(penumbra, want_penumbra));
    EXPECT_NEAR(unblocked.mean, want_unblocked, tolerance(unblocked, want_unblocked));
    // Beyond the penumbra the blocker takes nothing: a shadow ray it does not block
    // leaves the estimate as without it.
    EXPECT_NEAR(lit.mean, want_lit, tolerance(lit, want_lit));
}

// --------------------------------------------------------- backends and streams

// (e) Both backends draw the same random numbers: the penumbra, where every pixel
// depends on which of its shadow rays are blocked, agrees pixel by pixel (to the
// cross-check rule) and the shadow-ray counts agree.
TEST(AreaLight, BothBackendsGiveTheSameSoftShadow) {
    Scene s = penumbra_scene();
    s.camera.eye = {1, 3, 3};
    s.camera.look_at = {1, 0, 0};
    s.camera.fov = 60;
    s.camera.width = 48;
    s.camera.height = 32;
    s.render.spp = 4;
    const RenderOutcome cpu = test::render_cpu(s);
    const RenderOutcome gpu = test::render_vulkan(s);
    const ImageDiff d = compare_images(gpu.image, cpu.image, 1e-3);
    std::printf("penumbra image: %zu of %zu pixels over 1e-3, max abs %.3g\n", d.pixels_over, d.pixels, d.max_abs);
    EXPECT_LE(d.fraction_over(), 0.001);
    EXPECT_EQ(gpu.stats.shadow_rays, cpu.stats.shadow_rays);
    // ... and it is a soft shadow: many pixels strictly between dark and lit.
    std::size_t between = 0;
    for (std::size_t i = 0; i < cpu.image.rgb.size(); i += 3) {
        if (cpu.image.rgb[i] > 0.02f && cpu.image.rgb[i] < 0.15f) ++between;
    }
    EXPECT_GT(between, cpu.image.rgb.size() / 3 / 20);
}

// (f) The same seed gives the same image, bit for bit, on the reference whatever the
// thread count; another seed gives another image.
TEST(AreaLight, SameSeedSameImageAcrossRunsAndThreadCounts) {
    const Scene scene = test::load_at_size(test::source_dir() / "scenes" / "area_light.json", 40, 30);
    const FlatScene gpu = flatten_scene(scene);
    ASSERT_TRUE(gpu.features.has(Feature::HAS_AREA_LIGHTS));
    const SampleRange all{0, gpu.samples_per_pixel};
    const RenderResult one = make_cpu_backend(1)->render(gpu, all);
    const RenderResult two = make_cpu_backend(2)->render(gpu, all);
    const RenderResult again = make_cpu_backend(3)->render(gpu, all);
    ASSERT_EQ(one.sums.size(), two.sums.size());
    for (std::size_t p = 0; p < one.sums.size(); ++p) {
        ASSERT_EQ(one.sums[p], two.sums[p]) << "pixel " << p;
        ASSERT_EQ(one.sums[p], again.sums[p]) << "pixel " << p;
        ASSERT_EQ(one.counters[p], two.counters[p]) << "pixel " << p;
    }
    Scene reseeded = scene;
    reseeded.render.seed += 1;
    const RenderResult other = make_cpu_backend(2)->render(flatten_scene(reseeded), all);
    std::size_t lit = 0;
    std::size_t differing = 0;
    for (std::size_t p = 0; p < one.sums.size(); ++p) {
        lit += mean_radiance(one.sums[p]).r > 0.0f ? 1 : 0;  // the background is black under any seed
        differing += other.sums[p] != one.sums[p] ? 1 : 0;
    }
    EXPECT_GT(lit, one.sums.size() / 4);
    EXPECT_GT(differing, lit * 9 / 10);
}

// Split invariance (docs/architecture.md, principle 4) holds for the light samples too: their
// numbers come from the sample's own stream.
TEST(AreaLight, SplitSamplesDrawTheSameLightSamples) {
    const Scene scene = test::load_at_size(test::source_dir() / "scenes" / "area_light.json", 32, 24);
    const FlatScene gpu = flatten_scene(scene);
    auto backend = make_cpu_backend(2);
    const RenderResult whole = backend->render(gpu, SampleRange{0, 5});
    const RenderResult first = backend->render(gpu, SampleRange{0, 2});
    const RenderResult rest = backend->render(gpu, SampleRange{2, 3});
    for (std::size_t p = 0; p < whole.sums.size(); ++p) {
        ASSERT_EQ(first.counters[p] + rest.counters[p], whole.counters[p]) << "pixel " << p;
        ASSERT_EQ(kernel::add_sums(first.sums[p], rest.sums[p]), whole.sums[p]) << "pixel " << p;
    }
}

// ------------------------------------------------------- sampling in the kernel

// A reference kernel over the emitter list the host builds for `s`.
struct EmitterKernel {
    FlatScene gpu;
    kernel::Kernel k;
    explicit EmitterKernel(const Scene& s) : gpu(flatten_scene(s)) {
        k.params = gpu.params;
        k.materials = gpu.materials;
        k.spheres = gpu.spheres;
        k.triangles = gpu.triangles;
        k.emitters = gpu.emitters;
    }
};

TEST(EmitterSampling, PickFollowsTheCumulativeFractions) {
    Scene s = floor_scene(1.0);
    add_lamp(s, 0, 0, 1, 1, 2);                      // a rectangle of area 1: one emitter
    s.spheres.push_back(Sphere{{0, 1, 0}, std::sqrt(1.0 / (4.0 * kPi)), 1});  // area 1
    s.triangles.push_back(Triangle{{dvec3{0, 3, 0}, dvec3{1, 3, 0}, dvec3{0, 3, 1}}, std::nullopt, 1});  // area 1/2
    EmitterKernel e(s);
    ASSERT_EQ(e.gpu.emitters.size(), 3u);  // sphere, rectangle, triangle: fractions 2/5, 4/5, 1
    EXPECT_EQ(e.k.pick_emitter(0.0f), 0u);
    EXPECT_EQ(e.k.pick_emitter(0.3999f), 0u);
    EXPECT_EQ(e.k.pick_emitter(0.4001f), 1u);
    EXPECT_EQ(e.k.pick_emitter(0.7999f), 1u);
    EXPECT_EQ(e.k.pick_emitter(0.8001f), 2u);
    EXPECT_EQ(e.k.pick_emitter(1.0f - 0x1p-24f), 2u);  // the largest number rng_1d returns
}

// One slot per light sample, whatever is picked and wherever it is seen from: the
// stream stays in step.
TEST(EmitterSampling, EveryDrawTakesOneSlot) {
    Scene s = floor_scene(1.0);
    add_lamp(s, 0, 0, 1, 1, 2);
    s.spheres.push_back(Sphere{{0, 1, 0}, 0.3, 1});
    EmitterKernel e(s);
    auto rng = e.k.rng_start(5, 7, 11);
    for (uint32_t i = 1; i <= 100; ++i) {
        e.k.sample_light(kernel::vec3(0.1f * float(i % 7), 0.5f, 0.2f), rng);
        ASSERT_EQ(rng.dim, i);
    }
}

// The number that picks an emitter also places the point on it, rescaled to the
// emitter's share: of a pixel's first 256 Sobol samples, each of two equal lamps gets
// 128, and their points are a net again, one in each of 128 columns and one in each
// of 128 rows. (Far from the lamps, so that they are sampled by area, where a
// point's position gives back its two numbers.)
TEST(EmitterSampling, EachEmittersPointsStayStratified) {
    Scene s = floor_scene(1.0);
    add_lamp(s, 0.5, 0.5, 1, 1, 40);  // corner (0, 40, 0)
    add_lamp(s, 2.5, 0.5, 1, 1, 40);  // corner (2, 40, 0)
    ASSERT_EQ(s.render.sampler, Sampler::Sobol);
    EmitterKernel e(s);
    ASSERT_EQ(e.gpu.emitters.size(), 2u);
    for (uint32_t pixel : {0u, 17u, 4242u}) {
        std::array<std::set<int>, 2> columns, rows;
        for (uint32_t i = 0; i < 256; ++i) {
            auto rng = e.k.rng_start(pixel, i, 1);
            const auto y = e.k.sample_light(kernel::vec3(1.5f, 0.0f, 0.5f), rng);
            const int lamp = y.position.x < 1.5f ? 0 : 1;
            const float u = y.position.x - 2.0f * float(lamp), v = y.position.z;
            ASSERT_TRUE(u >= 0.0f && u < 1.0f && v >= 0.0f && v < 1.0f) << u << " " << v;
            columns[lamp].insert(int(u * 128.0f));
            rows[lamp].insert(int(v * 128.0f));
        }
        for (int lamp = 0; lamp < 2; ++lamp) {
            EXPECT_EQ(columns[lamp].size(), 128u) << "pixel " << pixel << ", lamp " << lamp;
            EXPECT_EQ(rows[lamp].size(), 128u) << "pixel " << pixel << ", lamp " << lamp;
        }
    }
}

// Points on a triangle lie in it and are uniform: their mean is the centroid, and
// the share in the sub-triangle cut off at half height is a quarter of them.
TEST(EmitterSampling, TrianglePointsAreUniformByArea) {
    Scene s = floor_scene(1.0);
    const std::array<dvec3, 3> v{dvec3{0, 2, 0}, dvec3{4, 2, 0}, dvec3{1, 2, 3}};
    s.triangles.push_back(Triangle{v, std::nullopt, 1});  // faces down
    EmitterKernel e(s);
    const int n = 40000;
    dvec3 sum{0.0};
    int near_apex = 0;
    for (int i = 0; i < n; ++i) {
        auto rng = e.k.rng_start(uint32_t(i), 0, 1);
        const auto p = e.k.sample_light(kernel::vec3(1, 0, 1), rng);  // a lone triangle: by area
        ASSERT_EQ(p.normal, kernel::vec3(0, -1, 0));
        ASSERT_EQ(p.emission, kernel::vec3(1.0f));
        ASSERT_FLOAT_EQ(p.position.y, 2.0f);
        // Inside: z >= 0 and on the inner side of both slanted edges.
        ASSERT_GE(p.position.z, 0.0f);
        ASSERT_GE(3.0 * p.position.x - p.position.z, -1e-5);
        ASSERT_GE(-3.0 * (p.position.x - 4.0) - 3.0 * p.position.z, -1e-5);
        sum += dvec3(p.position);
        near_apex += p.position.z > 1.5f ? 1 : 0;
    }
    const dvec3 mean = sum / double(n);
    // Standard deviations of a uniform triangle's coordinates are below 1; 5 sigma.
    EXPECT_NEAR(mean.x, 5.0 / 3.0, 5.0 / std::sqrt(double(n)));
    EXPECT_NEAR(mean.z, 1.0, 5.0 / std::sqrt(double(n)));
    EXPECT_NEAR(near_apex / double(n), 0.25, 5.0 * std::sqrt(0.25 * 0.75 / n));
}

// Points on a sphere lie on it, with the outward normal, and are uniform: every
// octant gets an eighth.
TEST(EmitterSampling, SpherePointsAreUniformOverTheSurface) {
    Scene s = floor_scene(1.0);
    const dvec3 c{1, 2, 3};
    s.spheres.push_back(Sphere{c, 0.5, 1});
    EmitterKernel e(s);
    const int n = 40000;
    std::array<int, 8> octants{};
    for (int i = 0; i < n; ++i) {
        auto rng = e.k.rng_start(uint32_t(i), 3, 1);
        const float u1 = e.k.rng_next(rng);
        const float u2 = e.k.rng_next(rng);
        const auto p = e.k.emitter_point(e.k.load_emitter(0), u1, u2);  // by area: the fallback
        const dvec3 d = dvec3(p.position) - c;
        ASSERT_NEAR(glm::length(d), 0.5, 1e-6);
        ASSERT_NEAR(glm::length(dvec3(p.normal) - d / 0.5), 0.0, 1e-5);
        ++octants[(d.x > 0 ? 1 : 0) + (d.y > 0 ? 2 : 0) + (d.z > 0 ? 4 : 0)];
    }
    for (int count : octants) EXPECT_NEAR(count / double(n), 0.125, 5.0 * std::sqrt(0.125 * 0.875 / n));
}

// ------------------------------------------------------------ the emitter list

TEST(EmitterList, OneEntryPerEmitterWithPowerFractions) {
    Scene s = floor_scene(1.0);
    add_lamp(s, 0, 0, 2, 1, 2);                     // a rectangle of area 2: one emitter, radiance 1
    s.spheres.push_back(Sphere{{0, 1, 0}, 0.5, 1});  // area pi, radiance 1
    s.spheres.push_back(Sphere{{2, 1, 0}, 0.5, 0});  // not emissive
    Material dim;
    dim.name = "dim";
    dim.emission = dvec3(0.3, 0.0, 0.0);             // mean radiance 0.1
    s.materials.push_back(dim);
    s.triangles.push_back(Triangle{{dvec3{0, 3, 0}, dvec3{0, 3, 2}, dvec3{2, 3, 0}}, std::nullopt, 2});  // area 2
    const FlatScene g = flatten_scene(s);
    ASSERT_TRUE(g.features.has(Feature::HAS_AREA_LIGHTS));
    ASSERT_EQ(g.emitters.size(), 3u);
    const double total = kPi + 2.0 + 0.2;  // area times mean radiance
    EXPECT_NEAR(kernel::emitter_power(g.params), total, 1e-6);
    EXPECT_EQ(kernel::emitter_count(g.params), 3u);
    EXPECT_EQ(kernel::light_samples(g.params), 16u);
    // Spheres first, then triangle records (the floor is record 0); the lamp is one
    // record, a rectangle.
    EXPECT_EQ(g.emitters[0].prim.x, (kernel::REF_SPHERE << kernel::REF_KIND_SHIFT) | 0u);
    EXPECT_EQ(g.emitters[1].prim.x, (kernel::REF_TRIANGLE << kernel::REF_KIND_SHIFT) | 1u);
    EXPECT_EQ(g.emitters[2].prim.x, (kernel::REF_TRIANGLE << kernel::REF_KIND_SHIFT) | 2u);
    EXPECT_EQ(g.triangles[1].meta.z, kernel::SHAPE_RECTANGLE);
    EXPECT_EQ(g.triangles[2].meta.z, kernel::SHAPE_TRIANGLE);
    EXPECT_NEAR(g.emitters[0].cdf.x, kPi / total, 1e-7);
    EXPECT_NEAR(g.emitters[1].cdf.x, (kPi + 2.0) / total, 1e-7);
    EXPECT_EQ(g.emitters[2].cdf.x, 1.0f);
    // Each entry also holds the fraction before it, exactly the previous entry's.
    EXPECT_EQ(g.emitters[0].cdf.y, 0.0f);
    EXPECT_EQ(g.emitters[1].cdf.y, g.emitters[0].cdf.x);
    EXPECT_EQ(g.emitters[2].cdf.y, g.emitters[1].cdf.x);
    bool listed = false;
    for (const BufferSize& b : g.built_buffers()) listed = listed || b.name == "emitters";
    EXPECT_TRUE(listed);
}

TEST(EmitterList, NoLightSamplesNoAreaLights) {
    Scene s = floor_scene(1.0);
    add_lamp(s, 0, 0, 2, 1, 2);
    s.render.light_samples = 0;
    const FlatScene g = flatten_scene(s);
    EXPECT_FALSE(g.features.has(Feature::HAS_AREA_LIGHTS));
    EXPECT_TRUE(g.features.has(Feature::HAS_EMISSION));  // the lamp is still seen
    EXPECT_FALSE(g.features.has(Feature::HAS_SHADOWS));  // nothing casts any
    EXPECT_TRUE(g.emitters.empty());
    EXPECT_EQ(kernel::emitter_count(g.params), 0u);
}

TEST(EmitterList, AnUnusedEmissiveMaterialMakesNoLight) {
    Scene s = floor_scene(1.0);  // material 1 emits, but nothing uses it
    const FlatScene g = flatten_scene(s);
    EXPECT_FALSE(g.features.has(Feature::HAS_AREA_LIGHTS));
    EXPECT_TRUE(g.emitters.empty());
}

}  // namespace
