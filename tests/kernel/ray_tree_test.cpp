// Mirrors and glass (shaders/kernel/lobes/mirror.glsl, lobes/glass.glsl, sample.glsl): the Fresnel and
// Snell maths against closed forms, the children a hit spawns, and whole samples
// against what optics says they must show, through the reference backend's kernel.
// Also the decision hash the cross-check relies on, and the SPD corner sampling.
#include <gtest/gtest.h>

#include <cmath>

#include "cpu/cpu_backend.hpp"
#include "flatten/flat_scene.hpp"
#include "test_support.hpp"

namespace {

using namespace vkrt;
using kernel::Kernel;
using kernel::vec3;
using glm::dvec3;

// Mean of the s- and p-polarized Fresnel reflectances, in double.
double fresnel(double cos_i, double eta) {
    const double sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    if (sin2_t >= 1.0) return 1.0;
    const double cos_t = std::sqrt(1.0 - sin2_t);
    const double rs = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    const double rp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return 0.5 * (rs * rs + rp * rp);
}

TEST(Fresnel, NormalIncidenceObliqueAndSnell) {
    Kernel k;
    // Head on, air to glass: ((1 - 1.5) / (1 + 1.5))^2 = 0.04, straight through.
    const Kernel::Refraction head_on = k.refract_fresnel(vec3(0, 0, -1), vec3(0, 0, 1), 1.0f / 1.5f);
    EXPECT_FALSE(head_on.total);
    EXPECT_NEAR(head_on.reflectance, 0.04, 1e-7);
    EXPECT_NEAR(head_on.dir.z, -1.0, 1e-7);
    // 60 degrees: sin(theta_t) = sin(theta_i) / 1.5, and R from the exact equations.
    const double theta = glm::radians(60.0);
    const vec3 d(float(std::sin(theta)), 0.0f, float(-std::cos(theta)));
    const Kernel::Refraction r = k.refract_fresnel(d, vec3(0, 0, 1), 1.0f / 1.5f);
    EXPECT_NEAR(r.dir.x, std::sin(theta) / 1.5, 1e-6);
    EXPECT_NEAR(glm::length(r.dir), 1.0, 1e-6);
    EXPECT_LT(r.dir.z, 0.0f);
    EXPECT_NEAR(r.reflectance, fresnel(std::cos(theta), 1.0 / 1.5), 1e-6);
    // Same index on both sides: nothing reflects, nothing bends.
    const Kernel::Refraction same = k.refract_fresnel(d, vec3(0, 0, 1), 1.0f);
    EXPECT_NEAR(same.reflectance, 0.0, 1e-7);
    EXPECT_NEAR(same.dir.x, d.x, 1e-6);
    // Grazing: everything reflects.
    EXPECT_NEAR(k.refract_fresnel(vec3(1, 0, 0), vec3(0, 0, 1), 1.0f / 1.5f).reflectance, 1.0, 1e-6);
}

TEST(Fresnel, BrewstersAngleAgainstTheSineForms) {
    // Independent of the kernel's cosine forms: at Brewster's angle tan(theta_i) = n
    // the p-polarized reflectance vanishes, theta_i + theta_t = 90 degrees, and the
    // s-polarized one is sin^2(theta_i - theta_t) / sin^2(theta_i + theta_t).
    Kernel k;
    const double theta_i = std::atan(1.5);
    const double theta_t = std::asin(std::sin(theta_i) / 1.5);
    EXPECT_NEAR(theta_i + theta_t, glm::radians(90.0), 1e-12);
    const double rs = std::sin(theta_i - theta_t) / std::sin(theta_i + theta_t);
    const vec3 d(float(std::sin(theta_i)), 0.0f, float(-std::cos(theta_i)));
    const Kernel::Refraction r = k.refract_fresnel(d, vec3(0, 0, 1), 1.0f / 1.5f);
    EXPECT_NEAR(r.reflectance, 0.5 * rs * rs, 1e-6);
    // And at 30 degrees, both sine and tangent forms.
    const double i30 = glm::radians(30.0), t30 = std::asin(std::sin(i30) / 1.5);
    const double s30 = std::sin(i30 - t30) / std::sin(i30 + t30);
    const double p30 = std::tan(i30 - t30) / std::tan(i30 + t30);
    const Kernel::Refraction r30 =
        k.refract_fresnel(vec3(float(std::sin(i30)), 0.0f, float(-std::cos(i30))), vec3(0, 0, 1), 1.0f / 1.5f);
    EXPECT_NEAR(r30.reflectance, 0.5 * (s30 * s30 + p30 * p30), 1e-6);
}

TEST(Fresnel, AtAndBeyondTheCriticalAngleAllIsReflected) {
    Kernel k;
    // Glass to air: critical angle asin(1 / 1.5).
    const double critical = std::asin(1.0 / 1.5);
    for (double theta : {critical, critical + 1e-4, critical + 0.1, glm::radians(89.0)}) {
        const vec3 d(float(std::sin(theta)), 0.0f, float(-std::cos(theta)));
        const Kernel::Refraction r = k.refract_fresnel(d, vec3(0, 0, 1), 1.5f);
        // At the critical angle itself float rounding may leave a refracted ray
        // grazing the surface; its share is then nil all the same.
        EXPECT_GE(r.reflectance, theta == critical ? 1.0f - 1e-3f : 1.0f) << theta;
        if (theta > critical) {
            EXPECT_TRUE(r.total) << theta;
        }
    }
    // Just below: a refracted ray with a real share.
    const double below = critical - 0.05;
    const Kernel::Refraction r = k.refract_fresnel(vec3(float(std::sin(below)), 0.0f, float(-std::cos(below))),
                                                   vec3(0, 0, 1), 1.5f);
    EXPECT_FALSE(r.total);
    EXPECT_NEAR(r.reflectance, fresnel(std::cos(below), 1.5), 1e-5);
}

// ---- scenes -------------------------------------------------------------------------

Material material(dvec3 diffuse, dvec3 reflect = dvec3(0.0), dvec3 transmit = dvec3(0.0), double ior = 1.5) {
    Material m;
    m.diffuse = diffuse;
    m.reflect = reflect;
    m.transmit = transmit;
    m.ior = ior;
    return m;
}

void add_quad(Scene& s, dvec3 corner, dvec3 e1, dvec3 e2, std::uint32_t material) {
    s.triangles.push_back(quad(corner, e1, e2, material));
}

Scene empty_scene() {
    Scene s;
    s.camera.eye = {0, 0, 0};
    s.camera.look_at = {1, 0, 0};
    s.camera.width = 1;
    s.camera.height = 1;
    s.render.grid.mode = GridMode::Off;
    return s;
}

// The children one hit spawns, through the kernel's own spawn_children.
struct Spawned {
    Kernel::RayQueue q{};
    Kernel::SampleResult s{};
};
Spawned spawn(Kernel& k, const Kernel::PendingRay& ray, const Kernel::Hit& hit) {
    Spawned out;
    out.q.top = 0u;
    out.q.has_next = false;
    k.spawn_children(ray, hit, out.q, out.s);
    return out;
}

TEST(RayTree, AGlassSlabShiftsARayWithoutTurningIt) {
    // Slab 0.5 thick: top face y = 0 facing up, bottom y = -0.5 facing down.
    const double d = 0.5;
    Scene scene = empty_scene();
    scene.materials = {material(dvec3(0.0), dvec3(0.0), dvec3(1.0), 1.5)};
    add_quad(scene, {-50, 0, 50}, {100, 0, 0}, {0, 0, -100}, 0);
    add_quad(scene, {-50, -d, -50}, {100, 0, 0}, {0, 0, 100}, 0);
    const FlatScene gpu = flatten_scene(scene);
    Kernel k = make_kernel(gpu);

    const double theta = glm::radians(40.0);
    const dvec3 dir(std::sin(theta), -std::cos(theta), 0.0);
    const Kernel::PendingRay eye{Kernel::Ray(vec3(0.0f, 1.0f, 0.0f), vec3(dir)), vec3(1.0f), 0u, glm::vec4(0.0f)};
    const Kernel::Hit top = k.closest_hit(eye.ray, kernel::INFINITY_T);
    ASSERT_TRUE(top.front_face);
    const Spawned in = spawn(k, eye, top);
    ASSERT_TRUE(in.q.has_next);
    ASSERT_EQ(in.q.top, 1u);  // refraction traced next, reflection stacked
    EXPECT_EQ(in.s.refraction_rays, 1u);
    EXPECT_EQ(in.s.reflection_rays, 1u);
    const double theta_t = std::asin(std::sin(theta) / 1.5);
    EXPECT_NEAR(in.q.next.ray.dir.x, std::sin(theta_t), 1e-6);

    const Kernel::Hit bottom = k.closest_hit(in.q.next.ray, kernel::INFINITY_T);
    ASSERT_LT(bottom.t, kernel::INFINITY_T);
    EXPECT_FALSE(bottom.front_face) << "leaving the slab through its back";
    const Spawned out = spawn(k, in.q.next, bottom);
    ASSERT_TRUE(out.q.has_next);
    const Kernel::Ray exit = out.q.next.ray;
    // Parallel to the entering ray ...
    EXPECT_NEAR(exit.dir.x, dir.x, 2e-6);
    EXPECT_NEAR(exit.dir.y, dir.y, 2e-6);
    // ... displaced sideways by d sin(theta - theta_t) / cos(theta_t), measured at
    // the exit point. Each secondary ray starts off its surface by the self-
    // intersection offset, 2^-16 near the origin (ray.glsl), which bounds the error.
    const dvec3 exit_point = dvec3(in.q.next.ray.origin) + double(bottom.t) * dvec3(in.q.next.ray.dir);
    const dvec3 from_entry = exit_point - dvec3(0.0, 1.0, 0.0);
    const double shift = glm::length(from_entry - glm::dot(from_entry, dir) * dir);
    EXPECT_NEAR(shift, d * std::sin(theta - theta_t) / std::cos(theta_t), 2 * 0x1p-16);
    // The Fresnel split: refracted in, refracted out.
    const double t_in = 1.0 - fresnel(std::cos(theta), 1.0 / 1.5);
    const double t_out = 1.0 - fresnel(std::cos(theta_t), 1.5);
    EXPECT_NEAR(out.q.next.weight.x, t_in * t_out, 1e-6);
}

TEST(RayTree, TotalInternalReflectionSpawnsOnlyTheReflection) {
    Scene scene = empty_scene();
    scene.materials = {material(dvec3(0.0), dvec3(0.0), dvec3(0.8, 0.9, 1.0), 1.5)};
    scene.spheres.push_back(Sphere{{0, 0, 0}, 1.0, 0});
    const FlatScene gpu = flatten_scene(scene);
    Kernel k = make_kernel(gpu);
    // From inside, meeting the surface at sin(theta) = 0.9 > 1 / 1.5.
    const Kernel::PendingRay ray{Kernel::Ray(vec3(0.0f, 0.9f, 0.0f), vec3(1, 0, 0)), vec3(1.0f), 0u, glm::vec4(0.0f)};
    const Kernel::Hit hit = k.closest_hit(ray.ray, kernel::INFINITY_T);
    ASSERT_FALSE(hit.front_face);
    const Spawned s = spawn(k, ray, hit);
    ASSERT_TRUE(s.q.has_next);
    EXPECT_EQ(s.q.top, 0u);
    EXPECT_EQ(s.s.refraction_rays, 0u);
    EXPECT_EQ(s.s.reflection_rays, 1u);
    // All of the transmitted share goes to the reflection.
    EXPECT_EQ(s.q.next.weight, vec3(0.8f, 0.9f, 1.0f));
}

TEST(RayTree, APerfectMirrorShowsTheLitPlaneExactly) {
    // A mirror floor (y = 0) under a matte ceiling (y = 2) lit by a point light at
    // y = 1: looking down at the mirror shows the ceiling, Lambert-lit.
    Scene scene = empty_scene();
    scene.camera.eye = {0, 1, 3};
    scene.camera.look_at = {0, 0, 0};
    scene.materials = {material(dvec3(0.0), dvec3(1.0)), material(dvec3(0.5, 0.25, 1.0))};
    scene.materials[0].kd = 0.0;
    add_quad(scene, {-20, 0, 20}, {40, 0, 0}, {0, 0, -40}, 0);
    add_quad(scene, {-20, 2, -20}, {40, 0, 0}, {0, 0, 40}, 1);
    scene.lights.push_back(Light{{0, 1, 0}, {1, 1, 1}, 2.0});
    const FlatScene gpu = flatten_scene(scene);
    Kernel k = make_kernel(gpu);
    const Kernel::SampleResult r = k.render_sample(0, 0, 0);
    EXPECT_EQ(r.reflection_rays, 1u);
    EXPECT_EQ(r.shadow_rays, 2u);  // one from the mirror (black, but lit), one from the ceiling
    // The pixel is the ceiling's shading along the mirrored ray, bit for bit: the
    // mirror adds nothing and weighs it by exactly 1.
    const Kernel::Ray eye = k.camera_ray(0.5f, 0.5f);
    const Kernel::Hit mirror = k.closest_hit(eye, kernel::INFINITY_T);
    const Spawned child = spawn(k, Kernel::PendingRay{eye, vec3(1.0f), 0u, glm::vec4(0.0f)}, mirror);
    ASSERT_TRUE(child.q.has_next);
    EXPECT_EQ(child.q.next.weight, vec3(1.0f));
    std::uint32_t shadow_rays = 0;
    Kernel::Rng rng{};  // only area lights draw from it
    const vec3 ceiling =
        k.shade_local(child.q.next.ray, k.closest_hit(child.q.next.ray, kernel::INFINITY_T), rng, shadow_rays);
    EXPECT_EQ(r.radiance, ceiling);
    // And that is the Lambert term at the point the optics predicts: the eye ray
    // meets the mirror at the origin and goes on to the ceiling at (0, 2, -6), where
    // cos(theta) to the light is 1 / sqrt(37); times intensity 2 and the diffuse colour.
    const double cos_theta = 1.0 / std::sqrt(37.0);
    for (int c = 0; c < 3; ++c) {
        const double want = scene.materials[1].diffuse[c] * 2.0 * cos_theta;
        EXPECT_NEAR(r.radiance[c], want, 1e-5 * want) << "channel " << c;
    }
}

TEST(RayTree, GlassCastsAnOpaqueShadow) {
    // The renderer's rule (docs/scene-format.md): shadow rays stop at any surface,
    // glass included. A glass ball between a light and a floor darkens the floor
    // below it as fully as a stone would.
    Scene scene = empty_scene();
    scene.camera.eye = {0, 3, 0.001};
    scene.camera.look_at = {0, 0, 0};
    scene.materials = {material(dvec3(0.8)), material(dvec3(0.0), dvec3(0.0), dvec3(1.0), 1.5)};
    add_quad(scene, {-20, 0, 20}, {40, 0, 0}, {0, 0, -40}, 0);
    scene.spheres.push_back(Sphere{{0, 1.5, 0}, 0.4, 1});
    scene.lights.push_back(Light{{0, 10, 0}, {1, 1, 1}, 1.0});
    const FlatScene gpu = flatten_scene(scene);
    Kernel k = make_kernel(gpu);
    // A ray straight down through the ball reaches the floor's shadowed centre.
    const Kernel::Ray down(vec3(0.0f, 1.0f, 0.0f), vec3(0, -1, 0));
    const Kernel::Hit floor = k.closest_hit(down, kernel::INFINITY_T);
    std::uint32_t shadow_rays = 0;
    Kernel::Rng rng{};  // only area lights draw from it
    EXPECT_EQ(k.shade_local(down, floor, rng, shadow_rays), vec3(0.0f));
    EXPECT_EQ(shadow_rays, 1u);
    // Beside the ball, lit.
    const Kernel::Ray beside(vec3(2.0f, 1.0f, 0.0f), vec3(0, -1, 0));
    EXPECT_GT(k.shade_local(beside, k.closest_hit(beside, kernel::INFINITY_T), rng, shadow_rays).x, 0.5f);
}

// Two parallel mirrors, the eye between them looking at one: the eye ray bounces
// back and forth, one reflection ray a generation.
Scene facing_mirrors(double reflectance, std::uint32_t max_depth, double min_weight) {
    Scene scene = empty_scene();
    scene.materials = {material(dvec3(0.0), dvec3(reflectance))};
    // Mirrors reflect on both faces, so which way each quad faces does not matter.
    add_quad(scene, {1, -10, -10}, {0, 20, 0}, {0, 0, 20}, 0);   // x = 1
    add_quad(scene, {-1, -10, -10}, {0, 0, 20}, {0, 20, 0}, 0);  // x = -1
    scene.render.max_depth = max_depth;
    scene.render.min_weight = min_weight;
    scene.render.background = {1, 1, 1};
    return scene;
}

TEST(RayTree, DepthLimitAndWeightThresholdAreObeyedAndCounted) {
    {
        const FlatScene gpu = flatten_scene(facing_mirrors(1.0, 5, 0.0));
        const Kernel::SampleResult r = make_kernel(gpu).render_sample(0, 0, 0);
        EXPECT_EQ(r.reflection_rays, 5u);
        EXPECT_EQ(r.dropped_weight, 0u);
        EXPECT_EQ(r.eye_hits, 1u);
        EXPECT_EQ(r.radiance, vec3(0.0f)) << "black mirrors, and the last ray stops at a mirror";
    }
    {
        // Weights 0.1, 0.01, then 0.001 under the threshold 0.005: two traced, one dropped.
        const FlatScene gpu = flatten_scene(facing_mirrors(0.1, 5, 0.005));
        const Kernel::SampleResult r = make_kernel(gpu).render_sample(0, 0, 0);
        EXPECT_EQ(r.reflection_rays, 2u);
        EXPECT_EQ(r.dropped_weight, 1u);
    }
    {
        // max_depth 0: the eye ray alone (the feature is left out altogether).
        const FlatScene gpu = flatten_scene(facing_mirrors(1.0, 0, 0.0));
        EXPECT_FALSE(gpu.features.has(Feature::HAS_REFLECTION));
        EXPECT_EQ(make_kernel(gpu).render_sample(0, 0, 0).reflection_rays, 0u);
    }
}

TEST(RayTree, AFullStackDropsRaysAndSaysSo) {
    // Two glass panes (x = +-1) between two mirrors (x = +-2), constant weights and
    // no threshold: every pane hit branches into two rays that both meet a pane or a
    // mirror again, so at depth 14 the tree needs more than the 8 stacked rays, and
    // those beyond are dropped and counted.
    Scene scene = facing_mirrors(1.0, 14, 0.0);
    scene.materials.push_back(material(dvec3(0.0), dvec3(0.0), dvec3(1.0), 1.5));
    scene.materials[1].fresnel = false;
    for (Triangle& t : scene.triangles) {
        for (dvec3& v : t.vertices) v.x *= 2.0;  // the mirrors move out to x = +-2
    }
    add_quad(scene, {1, -10, -10}, {0, 20, 0}, {0, 0, 20}, 1);
    add_quad(scene, {-1, -10, -10}, {0, 0, 20}, {0, 20, 0}, 1);
    scene.render.loop_budget = 65000;
    const FlatScene gpu = flatten_scene(scene);
    const Kernel::SampleResult r = make_kernel(gpu).render_sample(0, 0, 0);
    EXPECT_FALSE(r.truncated);
    EXPECT_GT(r.dropped_stack, 0u) << r.reflection_rays << " reflection, " << r.refraction_rays << " refraction";
    EXPECT_GT(r.reflection_rays + r.refraction_rays, 100u);
    EXPECT_TRUE(std::isfinite(r.radiance.x));
    // At max_depth 8 the stack is just deep enough.
    scene.render.max_depth = kernel::RAY_STACK_SIZE;
    const FlatScene deep8 = flatten_scene(scene);
    EXPECT_EQ(make_kernel(deep8).render_sample(0, 0, 0).dropped_stack, 0u);
}

TEST(DecisionHash, DifferentDecisionsHashDifferently) {
    // The cross-check tells flips from arithmetic by these hashes: each kind of
    // decision must change it, and the same decisions must give the same hash.
    Scene scene = empty_scene();
    scene.materials = {material(dvec3(0.5)), material(dvec3(0.0), dvec3(0.0), dvec3(1.0), 1.5)};
    scene.spheres.push_back(Sphere{{0, 0, 0}, 1.0, 1});
    scene.spheres.push_back(Sphere{{5, 0, 0}, 1.0, 0});
    const FlatScene gpu = flatten_scene(scene);
    Kernel k = make_kernel(gpu);
    auto hash = [&](auto&& run) {
        k.work_reset();
        run();
        return k.g_decisions;
    };
    // Blocked and clear shadow rays; the same query twice.
    const auto blocked = [&] { k.occluded(Kernel::Ray(vec3(-3, 0, 0), vec3(1, 0, 0)), 10.0f); };
    const auto clear = [&] { k.occluded(Kernel::Ray(vec3(-3, 3, 0), vec3(1, 0, 0)), 10.0f); };
    EXPECT_NE(hash(blocked), hash(clear));
    EXPECT_EQ(hash(blocked), hash(blocked));
    // Which primitive a ray hits, and from which side (outside, or inside the glass).
    const auto first = [&] { k.closest_hit(Kernel::Ray(vec3(-3, 0, 0), vec3(1, 0, 0)), kernel::INFINITY_T); };
    const auto second = [&] { k.closest_hit(Kernel::Ray(vec3(8, 0, 0), vec3(-1, 0, 0)), kernel::INFINITY_T); };
    const auto inside = [&] { k.closest_hit(Kernel::Ray(vec3(0, 0, 0), vec3(-1, 0, 0)), kernel::INFINITY_T); };
    EXPECT_NE(hash(first), hash(second));
    EXPECT_NE(hash(first), hash(inside)) << "same sphere, hit from inside";
    // Total internal reflection against refraction, from inside the glass sphere.
    auto spawn_from = [&](vec3 origin, vec3 dir) {
        return [&k, origin, dir] {
            const Kernel::PendingRay ray{Kernel::Ray(origin, dir), vec3(1.0f), 0u, glm::vec4(0.0f)};
            spawn(k, ray, k.closest_hit(ray.ray, kernel::INFINITY_T));
        };
    };
    const auto total = spawn_from(vec3(0.0f, 0.9f, 0.0f), vec3(1, 0, 0));
    const auto refracts = spawn_from(vec3(0.0f, 0.1f, 0.0f), vec3(1, 0, 0));
    EXPECT_NE(hash(total), hash(refracts));
    EXPECT_EQ(hash(total), hash(total));
}

TEST(Corners, EachCornerRayGoesThroughItsPixelCorner) {
    // With render.corners the kernel renders the (w+1) x (h+1) corner grid; its ray
    // (x, y) must be the plain image's ray through continuous position (x, y).
    Scene scene = empty_scene();
    scene.camera.eye = {1, 2, 3};
    scene.camera.look_at = {0, 0, 0};
    scene.camera.fov = 50;
    scene.camera.width = 6;
    scene.camera.height = 4;
    scene.materials = {material(dvec3(0.5))};
    scene.spheres.push_back(Sphere{{0, 0, 0}, 1.0, 0});
    Kernel plain = make_kernel(flatten_scene(scene));
    scene.render.corners = true;
    const FlatScene gpu = flatten_scene(scene);
    EXPECT_EQ(gpu.width(), 7u);
    EXPECT_EQ(gpu.height(), 5u);
    EXPECT_EQ(gpu.samples_per_pixel, 1u);
    Kernel corners = make_kernel(gpu);
    for (float y = 0; y <= 4; ++y) {
        for (float x = 0; x <= 6; ++x) {
            const vec3 want = plain.camera_ray(x, y).dir;
            const vec3 got = corners.camera_ray(x + 0.5f, y + 0.5f).dir;  // the sample offset of aa = 1
            EXPECT_NEAR(got.x, want.x, 1e-6);
            EXPECT_NEAR(got.y, want.y, 1e-6);
            EXPECT_NEAR(got.z, want.z, 1e-6);
        }
    }
}

TEST(Corners, EachPixelAveragesItsFourCornersLeavingOutLostOnes) {
    RenderResult r;
    r.width = 3;
    r.height = 2;
    // Corner radiance sums over `n` samples; corner (2, 1) lost its sample.
    auto sums = [](glm::vec3 sum, std::uint32_t n) {
        kernel::PixelSum s{};
        for (std::uint32_t i = 0; i < n; ++i) kernel::add_sample(s, sum / float(n), false);
        return s;
    };
    r.sums = {sums({1, 2, 3}, 1), sums({2, 4, 6}, 2), sums({9, 9, 9}, 1),
              sums({3, 3, 3}, 1), sums({5, 5, 5}, 1), kernel::PixelSum{}};
    const Image image = resolve_image(r, true);
    ASSERT_EQ(image.width, 2u);
    ASSERT_EQ(image.height, 1u);
    // Pixel 0: corners (1,2,3), (1,2,3), (3,3,3), (5,5,5).
    EXPECT_FLOAT_EQ(image.rgb[0], 2.5f);
    EXPECT_FLOAT_EQ(image.rgb[1], 3.0f);
    EXPECT_FLOAT_EQ(image.rgb[2], 3.5f);
    // Pixel 1: corners (1,2,3), (9,9,9), (5,5,5) and the lost one, left out.
    EXPECT_FLOAT_EQ(image.rgb[3], 5.0f);
    EXPECT_FLOAT_EQ(image.rgb[4], 16.0f / 3.0f);
    EXPECT_FLOAT_EQ(image.rgb[5], 17.0f / 3.0f);
}

TEST(RayTree, FeaturesFollowTheMaterials) {
    Scene scene = facing_mirrors(0.5, 5, 0.0);
    FlatScene gpu = flatten_scene(scene);
    EXPECT_TRUE(gpu.features.has(Feature::HAS_REFLECTION));
    EXPECT_FALSE(gpu.features.has(Feature::HAS_REFRACTION));
    scene.materials[0] = material(dvec3(0.5), dvec3(0.0), dvec3(0.5));
    gpu = flatten_scene(scene);
    EXPECT_FALSE(gpu.features.has(Feature::HAS_REFLECTION));
    EXPECT_TRUE(gpu.features.has(Feature::HAS_REFRACTION));
    scene.materials[0] = material(dvec3(0.5));
    gpu = flatten_scene(scene);
    EXPECT_FALSE(gpu.features.has(Feature::HAS_REFLECTION));
    EXPECT_FALSE(gpu.features.has(Feature::HAS_REFRACTION));
}

TEST(RayTree, BothBackendsTraceTheSameTree) {
    // Same counts and the same image on a scene with mirrors and glass.
    const Scene scene = test::load_at_size(test::source_dir() / "scenes" / "gallery" / "g_glass_sphere.json", 64, 48);
    const RenderOutcome cpu = test::render_cpu(scene);
    const RenderOutcome gpu = test::render_vulkan(scene);
    EXPECT_GT(cpu.stats.refraction_rays, 0u);
    // Counts may differ by the odd decision flip between the two float paths.
    EXPECT_NEAR(double(gpu.stats.reflection_rays), double(cpu.stats.reflection_rays),
                0.002 * double(cpu.stats.reflection_rays));
    EXPECT_NEAR(double(gpu.stats.refraction_rays), double(cpu.stats.refraction_rays),
                0.002 * double(cpu.stats.refraction_rays));
    EXPECT_EQ(gpu.stats.eye_hits, cpu.stats.eye_hits);
}

}  // namespace
