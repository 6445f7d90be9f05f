// The kernel's scene-level functions (hit records, closest hit, shadow queries, local
// shading, one whole sample and its accumulation) through the reference backend's
// view of the shared GLSL, on scenes built by hand. As in intersect_test.cpp
// the inputs are chosen so that intermediates are exact in float wherever the maths
// allows, and the checks are then equalities; the shading formula is recomputed here
// in double, straight from docs/architecture.md ("Numbers and conventions"), and
// compared within a float's rounding.
//
// Exact loop-iteration counts are deliberately not pinned: what a loop costs is an
// accounting choice of budget.glsl, tested in loop_budget_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "kernel/kernel.hpp"
#include "render/pixel_sums.hpp"

namespace {

using vkrt::kernel::INFINITY_T;
using vkrt::kernel::REF_NONE;
using vkrt::kernel::Kernel;
using vkrt::kernel::Material;
using vkrt::kernel::Light;
using vkrt::kernel::Sphere;
using vkrt::kernel::Triangle;
using vkrt::kernel::uvec4;
using vkrt::kernel::vec2;
using vkrt::kernel::vec3;
using vkrt::kernel::vec4;
namespace kernel = vkrt::kernel;
using vkrt::radiance_sum;
using vkrt::samples_summed;

Kernel::Ray ray(vec3 origin, vec3 dir) { return Kernel::Ray(origin, dir); }

// Exact vector equality with both sides printed on failure.
::testing::AssertionResult same(const vec3& got, const vec3& want) {
    if (got == want) {
        return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure() << "got (" << got.x << ", " << got.y << ", " << got.z << "), want ("
                                         << want.x << ", " << want.y << ", " << want.z << ")";
}

// A point light as the host writes it (layout.glsl): w = 1, and the cone that lets
// everything through.
Light point_light(vec3 position, vec3 radiance) {
    return Light{vec4(position, 1.0f), vec4(radiance, 0.0f), vec4(0.0f, 0.0f, 0.0f, 1.0f)};
}

Sphere sphere(vec3 center, float radius, std::uint32_t material) {
    return Sphere{vec4(center, radius), uvec4(material, 0u, 0u, 0u)};
}

// A flat triangle: meta.y = 0, the vertex normals are zero and must not be read.
Triangle triangle(vec3 p0, vec3 p1, vec3 p2, std::uint32_t material) {
    return Triangle{vec4(p0, 0.0f), vec4(p1, 0.0f), vec4(p2, 0.0f), vec4(0.0f), vec4(0.0f), vec4(0.0f),
                    uvec4(material, 0u, 0u, 0u)};
}

Triangle smooth_triangle(vec3 p0, vec3 p1, vec3 p2, vec3 n0, vec3 n1, vec3 n2, std::uint32_t material) {
    return Triangle{vec4(p0, 0.0f), vec4(p1, 0.0f), vec4(p2, 0.0f), vec4(n0, 0.0f), vec4(n1, 0.0f), vec4(n2, 0.0f),
                    uvec4(material, 1u, 0u, 0u)};
}

// The arrays a Kernel reads, owned here so the spans stay valid. kernel() sets the
// counts from the array sizes; every feature but the grid stays on (the Kernel's
// default) unless a test turns it off. These scenes are traced by brute force; the
// grid has its own tests (grid_traversal_test.cpp).
struct TestScene {
    std::vector<Material> materials;
    std::vector<Sphere> spheres;
    std::vector<Triangle> triangles;
    std::vector<Light> lights;

    Kernel kernel() const {
        Kernel k;
        k.HAS_GRID = false;
        k.HAS_AREA_LIGHTS = false;  // no emitter list here
        k.materials = materials;
        k.spheres = spheres;
        k.triangles = triangles;
        k.lights = lights;
        kernel::set_sphere_count(k.params, static_cast<std::uint32_t>(spheres.size()));
        kernel::set_triangle_count(k.params, static_cast<std::uint32_t>(triangles.size()));
        kernel::set_light_count(k.params, static_cast<std::uint32_t>(lights.size()));
        kernel::set_material_count(k.params, static_cast<std::uint32_t>(materials.size()));
        kernel::set_loop_budget(k.params, kernel::DEFAULT_LOOP_BUDGET);
        return k;
    }
};

// The nearest hit a trace records (shapes/records.glsl), as <kind>_hit takes it: at
// t, or where a triangle test found it, with its weights.
Kernel::Nearest nearest_at(float t) {
    return Kernel::Nearest(t, REF_NONE, vec2(0.0f), 0u);
}

Kernel::Nearest nearest_of(const Kernel::TriangleHit& th) {
    return Kernel::Nearest(th.t, REF_NONE, vec2(th.u, th.v), 0u);
}

// ---------------------------------------------------------------- sphere_hit

TEST(SphereHit, FromOutsideTheNormalPointsOutAndTheFaceIsFront) {
    TestScene scene;
    scene.spheres = {sphere(vec3(0, 0, 0), 2.0f, 7)};
    Kernel k = scene.kernel();
    const Kernel::Hit h = k.sphere_hit(ray(vec3(0, 0, 5), vec3(0, 0, -1)), 0, nearest_at(3.0f));
    EXPECT_EQ(h.t, 3.0f);
    EXPECT_TRUE(same(h.normal, vec3(0, 0, 1)));
    EXPECT_TRUE(same(h.geo_normal, vec3(0, 0, 1)));
    EXPECT_TRUE(h.front_face);
    EXPECT_EQ(h.material, 7u);
}

TEST(SphereHit, OffCentreNormalIsUnitLength) {
    TestScene scene;
    scene.spheres = {sphere(vec3(0, 0, 0), 5.0f, 0)};
    Kernel k = scene.kernel();
    // 3 units off axis: the near root is t = 6, at (3, 0, 4), whose normal is
    // (3, 0, 4) / 5; both quotients are correctly rounded, hence 0.6f and 0.8f.
    const Kernel::Ray r = ray(vec3(3, 0, 10), vec3(0, 0, -1));
    const float t = k.intersect_sphere(r, vec3(0), 5.0f, 0.0f, INFINITY_T);
    ASSERT_EQ(t, 6.0f);
    const Kernel::Hit h = k.sphere_hit(r, 0, nearest_at(t));
    EXPECT_TRUE(same(h.normal, vec3(0.6f, 0.0f, 0.8f)));
    EXPECT_TRUE(h.front_face);
}

TEST(SphereHit, FromInsideTheNormalIsFlippedToFaceTheRay) {
    TestScene scene;
    scene.spheres = {sphere(vec3(0, 0, 0), 2.0f, 0)};
    Kernel k = scene.kernel();
    // Leaving through (2, 0, 0): the outward normal is (1, 0, 0), the ray goes +x.
    const Kernel::Hit h = k.sphere_hit(ray(vec3(0, 0, 0), vec3(1, 0, 0)), 0, nearest_at(2.0f));
    EXPECT_TRUE(same(h.normal, vec3(-1, 0, 0)));
    EXPECT_TRUE(same(h.geo_normal, vec3(-1, 0, 0)));
    EXPECT_FALSE(h.front_face);
}

TEST(SphereHit, CameraInsideASphereSeesItsInsideFacingBack) {
    TestScene scene;
    scene.spheres = {sphere(vec3(1, 0, 0), 4.0f, 3)};
    Kernel k = scene.kernel();
    // From (0, 0, 0) looking down -y: the far wall is at x = 0 distance sqrt(16 - 1),
    // not exact, so the check is on the facing, not on the point.
    const Kernel::Ray r = ray(vec3(0, 0, 0), vec3(0, -1, 0));
    const Kernel::Hit h = k.closest_hit(r, INFINITY_T);
    ASSERT_LT(h.t, INFINITY_T);
    EXPECT_NEAR(h.t, std::sqrt(15.0f), 1e-6f);
    EXPECT_FALSE(h.front_face);
    EXPECT_LT(glm::dot(h.normal, r.dir), 0.0f) << "normal must face the incoming ray";
    EXPECT_EQ(h.normal, h.geo_normal);
    EXPECT_NEAR(glm::length(h.normal), 1.0f, 1e-6f);
    EXPECT_EQ(h.material, 3u);
    // Straight along +x the hit is exact: (5, 0, 0), inward normal (-1, 0, 0).
    const Kernel::Hit hx = k.closest_hit(ray(vec3(0, 0, 0), vec3(1, 0, 0)), INFINITY_T);
    EXPECT_EQ(hx.t, 5.0f);
    EXPECT_TRUE(same(hx.normal, vec3(-1, 0, 0)));
    EXPECT_FALSE(hx.front_face);
}

// ---------------------------------------------------------------- triangle_hit

// Right triangle in the z = 0 plane, front face +z (cross(p1 - p0, p2 - p0)).
const vec3 kP0(0, 0, 0), kP1(1, 0, 0), kP2(0, 1, 0);

TEST(TriangleHit, FrontFaceFollowsTheWinding) {
    TestScene scene;
    scene.triangles = {triangle(kP0, kP1, kP2, 4), triangle(kP0, kP2, kP1, 5)};
    Kernel k = scene.kernel();
    const Kernel::Ray down = ray(vec3(0.25f, 0.5f, 2), vec3(0, 0, -1));
    const Kernel::Ray up = ray(vec3(0.25f, 0.5f, -3), vec3(0, 0, 1));

    const Kernel::Hit a = k.triangle_hit(down, 0,
                                         nearest_of(k.intersect_triangle(down, kP0, kP1, kP2, 0.0f, INFINITY_T)));
    EXPECT_EQ(a.t, 2.0f);
    EXPECT_TRUE(a.front_face);
    EXPECT_TRUE(same(a.geo_normal, vec3(0, 0, 1)));
    EXPECT_TRUE(same(a.normal, vec3(0, 0, 1)));
    EXPECT_EQ(a.material, 4u);

    const Kernel::Hit b = k.triangle_hit(up, 0,
                                         nearest_of(k.intersect_triangle(up, kP0, kP1, kP2, 0.0f, INFINITY_T)));
    EXPECT_EQ(b.t, 3.0f);
    EXPECT_FALSE(b.front_face);
    EXPECT_TRUE(same(b.geo_normal, vec3(0, 0, -1)));
    EXPECT_TRUE(same(b.normal, vec3(0, 0, -1)));

    // Reversed winding: its front is -z, so the ray from above sees its back.
    const Kernel::Hit c = k.triangle_hit(down, 1,
                                         nearest_of(k.intersect_triangle(down, kP0, kP2, kP1, 0.0f, INFINITY_T)));
    EXPECT_FALSE(c.front_face);
    EXPECT_TRUE(same(c.geo_normal, vec3(0, 0, 1)));
    EXPECT_EQ(c.material, 5u);
    const Kernel::Hit d = k.triangle_hit(up, 1,
                                         nearest_of(k.intersect_triangle(up, kP0, kP2, kP1, 0.0f, INFINITY_T)));
    EXPECT_TRUE(d.front_face);
    EXPECT_TRUE(same(d.geo_normal, vec3(0, 0, -1)));
}

// Vertex normals whose blend at the hit point (u = 0.25, v = 0.5, so weights 0.25,
// 0.25, 0.5) is (0, 1.5, 2): length 2.5, unit normal (0, 0.6, 0.8), all exact.
const vec3 kN0(0, 0, 4), kN1(0, 0, 4), kN2(0, 3, 0);

TEST(TriangleHit, SmoothNormalIsInterpolatedAndFlippedToTheViewer) {
    TestScene scene;
    scene.triangles = {smooth_triangle(kP0, kP1, kP2, kN0, kN1, kN2, 0)};
    Kernel k = scene.kernel();
    ASSERT_TRUE(k.HAS_SMOOTH_NORMALS);
    const Kernel::Ray down = ray(vec3(0.25f, 0.5f, 2), vec3(0, 0, -1));
    const Kernel::TriangleHit th_down = k.intersect_triangle(down, kP0, kP1, kP2, 0.0f, INFINITY_T);
    ASSERT_EQ(th_down.u, 0.25f);
    ASSERT_EQ(th_down.v, 0.5f);
    const Kernel::Hit front = k.triangle_hit(down, 0, nearest_of(th_down));
    EXPECT_TRUE(front.front_face);
    EXPECT_TRUE(same(front.geo_normal, vec3(0, 0, 1)));
    EXPECT_TRUE(same(front.normal, vec3(0.0f, 0.6f, 0.8f)));

    const Kernel::Ray up = ray(vec3(0.25f, 0.5f, -3), vec3(0, 0, 1));
    const Kernel::Hit back = k.triangle_hit(up, 0,
                                            nearest_of(k.intersect_triangle(up, kP0, kP1, kP2, 0.0f, INFINITY_T)));
    EXPECT_FALSE(back.front_face);
    EXPECT_TRUE(same(back.geo_normal, vec3(0, 0, -1)));
    EXPECT_TRUE(same(back.normal, vec3(0.0f, -0.6f, -0.8f)));
}

TEST(TriangleHit, FlatTrianglesUseTheFaceNormal) {
    TestScene scene;
    // Same vertex normals, but meta.y = 0: the scene gave none, so they are ignored.
    Triangle flat = smooth_triangle(kP0, kP1, kP2, kN0, kN1, kN2, 0);
    flat.meta.y = 0u;
    scene.triangles = {flat, smooth_triangle(kP0, kP1, kP2, kN0, kN1, kN2, 0)};
    Kernel k = scene.kernel();
    const Kernel::Ray down = ray(vec3(0.25f, 0.5f, 2), vec3(0, 0, -1));
    const Kernel::TriangleHit th = k.intersect_triangle(down, kP0, kP1, kP2, 0.0f, INFINITY_T);
    EXPECT_TRUE(same(k.triangle_hit(down, 0, nearest_of(th)).normal, vec3(0, 0, 1)));
    // A smooth triangle in a pipeline built without the feature is shaded flat too.
    k.HAS_SMOOTH_NORMALS = false;
    EXPECT_TRUE(same(k.triangle_hit(down, 1, nearest_of(th)).normal, vec3(0, 0, 1)));
}

// ---------------------------------------------------------------- closest_hit

// Along -z from the origin: spheres at t = 9 (material 0) and t = 5 (material 1), a
// sphere behind the origin (material 9), triangles at t = 4 (material 2) and t = 7
// (material 3). The triangles' Möller-Trumbore terms are all small powers of two.
TestScene nearest_scene() {
    TestScene scene;
    scene.spheres = {sphere(vec3(0, 0, -10), 1.0f, 0), sphere(vec3(0, 0, 4), 1.0f, 9),
                     sphere(vec3(0, 0, -6), 1.0f, 1)};
    scene.triangles = {triangle(vec3(-1, -1, -7), vec3(3, -1, -7), vec3(-1, 3, -7), 3),
                       triangle(vec3(-1, -1, -4), vec3(3, -1, -4), vec3(-1, 3, -4), 2)};
    return scene;
}

const Kernel::Ray kDownZ = Kernel::Ray(vec3(0, 0, 0), vec3(0, 0, -1));

TEST(ClosestHit, PicksTheNearestOfSpheresAndTriangles) {
    const TestScene scene = nearest_scene();
    Kernel k = scene.kernel();
    const Kernel::Hit h = k.closest_hit(kDownZ, INFINITY_T);
    EXPECT_EQ(h.t, 4.0f);
    EXPECT_EQ(h.material, 2u);
    EXPECT_TRUE(h.front_face);
    EXPECT_TRUE(same(h.normal, vec3(0, 0, 1)));
    EXPECT_FALSE(k.budget_exhausted());
}

TEST(ClosestHit, NearestSphereWhenItIsCloserThanEveryTriangle) {
    TestScene scene = nearest_scene();
    scene.spheres.push_back(sphere(vec3(0, 0, -2), 0.5f, 6));  // t = 1.5
    Kernel k = scene.kernel();
    const Kernel::Hit h = k.closest_hit(kDownZ, INFINITY_T);
    EXPECT_EQ(h.t, 1.5f);
    EXPECT_EQ(h.material, 6u);
    EXPECT_TRUE(same(h.normal, vec3(0, 0, 1)));
}

TEST(ClosestHit, WithoutTrianglesTheyAreIgnored) {
    const TestScene scene = nearest_scene();
    Kernel k = scene.kernel();
    k.HAS_TRIANGLES = false;
    const Kernel::Hit h = k.closest_hit(kDownZ, INFINITY_T);
    EXPECT_EQ(h.t, 5.0f);
    EXPECT_EQ(h.material, 1u);
    // And the other way round.
    k.HAS_TRIANGLES = true;
    k.HAS_SPHERES = false;
    const Kernel::Hit t = k.closest_hit(kDownZ, INFINITY_T);
    EXPECT_EQ(t.t, 4.0f);
    EXPECT_EQ(t.material, 2u);
    // A triangle-only scene, with a pipeline built without triangles, sees nothing.
    k.HAS_TRIANGLES = false;
    EXPECT_EQ(k.closest_hit(kDownZ, INFINITY_T).t, INFINITY_T);
}

TEST(ClosestHit, CountsBoundTheArrays) {
    const TestScene scene = nearest_scene();
    Kernel k = scene.kernel();
    // Only the first triangle (t = 7) and the first two spheres (t = 9, behind) count.
    kernel::set_sphere_count(k.params, 2);
    kernel::set_triangle_count(k.params, 1);
    const Kernel::Hit h = k.closest_hit(kDownZ, INFINITY_T);
    EXPECT_EQ(h.t, 7.0f);
    EXPECT_EQ(h.material, 3u);
}

TEST(ClosestHit, TMaxBoundsTheSearch) {
    const TestScene scene = nearest_scene();
    Kernel k = scene.kernel();
    // t_max is exclusive: the triangle at exactly 4 is out, and so is everything else.
    const Kernel::Hit none = k.closest_hit(kDownZ, 4.0f);
    EXPECT_EQ(none.t, INFINITY_T);
    EXPECT_FALSE(none.front_face);
    EXPECT_EQ(k.closest_hit(kDownZ, 4.5f).t, 4.0f);
    k.HAS_TRIANGLES = false;
    EXPECT_EQ(k.closest_hit(kDownZ, 5.0f).t, INFINITY_T);
    EXPECT_EQ(k.closest_hit(kDownZ, 6.0f).material, 1u);
    // A t_max inside the sphere still finds its near root.
    EXPECT_EQ(k.closest_hit(kDownZ, 5.5f).t, 5.0f);
}

TEST(ClosestHit, EmptySceneMisses) {
    const TestScene scene;
    Kernel k = scene.kernel();
    const Kernel::Hit h = k.closest_hit(kDownZ, INFINITY_T);
    EXPECT_EQ(h.t, INFINITY_T);
}

// ---------------------------------------------------------------- occluded

TEST(Occluded, BlockerBetweenOriginAndTMax) {
    TestScene scene;
    scene.spheres = {sphere(vec3(0, 0, -5), 1.0f, 0)};  // covers t in [4, 6]
    Kernel k = scene.kernel();
    EXPECT_TRUE(k.occluded(kDownZ, 10.0f));
    EXPECT_TRUE(k.occluded(kDownZ, 4.5f));
    // Beyond t_max (exclusive) and behind the origin do not block.
    EXPECT_FALSE(k.occluded(kDownZ, 4.0f));
    EXPECT_FALSE(k.occluded(kDownZ, 3.0f));
    EXPECT_FALSE(k.occluded(ray(vec3(0, 0, 0), vec3(0, 0, 1)), 100.0f));
}

TEST(Occluded, TrianglesBlockTooUnlessCompiledOut) {
    TestScene scene;
    scene.triangles = {triangle(vec3(-1, -1, -4), vec3(3, -1, -4), vec3(-1, 3, -4), 0)};
    Kernel k = scene.kernel();
    EXPECT_TRUE(k.occluded(kDownZ, 4.5f));
    EXPECT_FALSE(k.occluded(kDownZ, 4.0f));
    EXPECT_FALSE(k.occluded(ray(vec3(0, 0, 0), vec3(0, 0, 1)), 100.0f));
    // The back face blocks just as well as the front.
    EXPECT_TRUE(k.occluded(ray(vec3(0, 0, -8), vec3(0, 0, 1)), 100.0f));
    k.HAS_TRIANGLES = false;
    EXPECT_FALSE(k.occluded(kDownZ, 4.5f));
}

TEST(Occluded, AnyBlockerAmongSeveral) {
    TestScene scene = nearest_scene();
    Kernel k = scene.kernel();
    EXPECT_TRUE(k.occluded(kDownZ, 100.0f));
    EXPECT_TRUE(k.occluded(kDownZ, 4.5f));   // only the near triangle is in range
    EXPECT_FALSE(k.occluded(kDownZ, 4.0f));  // nothing in (0, 4)
    EXPECT_FALSE(k.occluded(ray(vec3(0, 0, -20), vec3(0, 0, -1)), 100.0f));  // all behind
}

// ---------------------------------------------------------------- shade_local

// The local model (docs/architecture.md, "Numbers and conventions") for one point
// light, computed here in double from the geometry: colour * intensity * (kd * diffuse * cos(theta) + ks * specular *
// cos(alpha)^shininess), alpha between the light vector mirrored about the normal
// and the eye vector. No clamping is needed for the configurations below.
glm::dvec3 paper_light_term(glm::dvec3 point, glm::dvec3 normal, glm::dvec3 eye, glm::dvec3 light_pos,
                            glm::dvec3 color_times_intensity, const Material& m) {
    const glm::dvec3 l = glm::normalize(light_pos - point);
    const glm::dvec3 v = glm::normalize(eye - point);
    const double cos_theta = glm::dot(normal, l);
    const glm::dvec3 r = 2.0 * cos_theta * normal - l;
    const double cos_alpha = glm::dot(r, v);
    const glm::dvec3 diffuse = double(m.kd) * glm::dvec3(m.diffuse) * cos_theta;
    const glm::dvec3 specular = double(m.ks) * glm::dvec3(m.specular) * std::pow(cos_alpha, double(m.shininess));
    return color_times_intensity * (diffuse + specular);
}

void expect_near(const vec3& got, const glm::dvec3& want) {
    const double tolerance = 1e-6 * std::max(1.0, glm::length(want));
    EXPECT_NEAR(got.x, want.x, tolerance);
    EXPECT_NEAR(got.y, want.y, tolerance);
    EXPECT_NEAR(got.z, want.z, tolerance);
}

// The eye at (0, 0, 5) looks down -z at a unit sphere: hit at (0, 0, 1), normal +z.
// The light at (3, 0, 5) is 5 away along (0.6, 0, 0.8): cos(theta) = 0.8, mirrored
// vector (-0.6, 0, 0.8), cos(alpha) = 0.8, so with shininess 3 the highlight is 0.512.
struct ShadeSetup {
    TestScene scene;
    const glm::dvec3 eye{0, 0, 5};
    const glm::dvec3 point{0, 0, 1};
    const glm::dvec3 normal{0, 0, 1};
    const glm::dvec3 light_pos{3, 0, 5};
    const glm::dvec3 light_color{1.0, 0.5, 0.25};
    const double light_intensity = 8.0;
    const Kernel::Ray eye_ray = Kernel::Ray(vec3(0, 0, 5), vec3(0, 0, -1));

    ShadeSetup() {
        Material m{};
        m.diffuse = vec3(0.5f, 0.25f, 1.0f);
        m.kd = 0.5f;
        m.specular = vec3(1.0f, 0.5f, 0.25f);
        m.ks = 0.25f;
        m.shininess = 3.0f;
        scene.materials = {m};
        scene.spheres = {sphere(vec3(0, 0, 0), 1.0f, 0)};
        scene.lights = {point_light(vec3(light_pos), vec3(light_color * light_intensity))};
    }
    Kernel kernel() const {
        Kernel k = scene.kernel();
        k.HAS_AMBIENT = false;
        k.HAS_EMISSION = false;
        return k;
    }
    glm::dvec3 paper() const {
        return paper_light_term(point, normal, eye, light_pos, light_color * light_intensity, scene.materials[0]);
    }
};

TEST(ShadeLocal, OneLightMatchesThePaperFormula) {
    const ShadeSetup s;
    Kernel k = s.kernel();
    const Kernel::Hit hit = k.closest_hit(s.eye_ray, INFINITY_T);
    ASSERT_EQ(hit.t, 4.0f);
    std::uint32_t shadow_rays = 0;
    Kernel::Rng rng{};  // only area lights draw from it
    const vec3 color = k.shade_local(s.eye_ray, hit, rng, shadow_rays);
    // By hand: diffuse 0.5 * (0.5, 0.25, 1) * 0.8 = (0.2, 0.1, 0.4), specular
    // 0.25 * (1, 0.5, 0.25) * 0.512 = (0.128, 0.064, 0.032), light (8, 4, 2):
    // (2.624, 0.656, 0.864).
    const glm::dvec3 want = s.paper();
    EXPECT_NEAR(want.x, 2.624, 1e-12);
    EXPECT_NEAR(want.y, 0.656, 1e-12);
    EXPECT_NEAR(want.z, 0.864, 1e-12);
    expect_near(color, want);
    EXPECT_EQ(shadow_rays, 1u);
}

TEST(ShadeLocal, SpecularAndDiffuseAreSeparateFeatures) {
    const ShadeSetup s;
    Kernel k = s.kernel();
    k.HAS_SPECULAR = false;
    const Kernel::Hit hit = k.closest_hit(s.eye_ray, INFINITY_T);
    std::uint32_t shadow_rays = 0;
    Kernel::Rng rng{};  // only area lights draw from it
    // Diffuse only: (0.2, 0.1, 0.4) * (8, 4, 2).
    expect_near(k.shade_local(s.eye_ray, hit, rng, shadow_rays), glm::dvec3(1.6, 0.4, 0.8));
}

TEST(ShadeLocal, AmbientAndEmissionAddToTheLight) {
    ShadeSetup s;
    s.scene.materials[0].emission = vec3(0.5f, 0.25f, 0.125f);
    Kernel k = s.scene.kernel();  // ambient and emission on
    kernel::set_ambient_light(k.params, vec3(0.5f, 1.0f, 2.0f));
    const Kernel::Hit hit = k.closest_hit(s.eye_ray, INFINITY_T);
    ASSERT_TRUE(hit.front_face);
    std::uint32_t shadow_rays = 0;
    Kernel::Rng rng{};  // only area lights draw from it
    // ambient * kd * diffuse = (0.5, 1, 2) * (0.25, 0.125, 0.5).
    const glm::dvec3 want = s.paper() + glm::dvec3(0.5, 0.25, 0.125) + glm::dvec3(0.125, 0.125, 1.0);
    expect_near(k.shade_local(s.eye_ray, hit, rng, shadow_rays), want);
    EXPECT_EQ(shadow_rays, 1u);
}

TEST(ShadeLocal, EmissionIsSeenFromTheFrontFaceOnly) {
    TestScene scene;
    Material m{};
    m.emission = vec3(1.0f, 2.0f, 3.0f);
    scene.materials = {m};
    scene.spheres = {sphere(vec3(0, 0, 0), 2.0f, 0)};
    Kernel k = scene.kernel();
    std::uint32_t shadow_rays = 0;
    Kernel::Rng rng{};  // only area lights draw from it
    const Kernel::Ray outside = ray(vec3(0, 0, 5), vec3(0, 0, -1));
    EXPECT_TRUE(same(k.shade_local(outside, k.closest_hit(outside, INFINITY_T), rng, shadow_rays), vec3(1, 2, 3)));
    const Kernel::Ray inside = ray(vec3(0, 0, 0), vec3(0, 0, -1));
    EXPECT_TRUE(same(k.shade_local(inside, k.closest_hit(inside, INFINITY_T), rng, shadow_rays), vec3(0)));
    EXPECT_EQ(shadow_rays, 0u);
}

TEST(ShadeLocal, BlockedLightAddsNothingButCountsItsShadowRay) {
    ShadeSetup s;
    // A small sphere halfway between the hit point (0, 0, 1) and the light (3, 0, 5),
    // well off the eye ray.
    s.scene.spheres.push_back(sphere(vec3(1.5f, 0.0f, 3.0f), 0.5f, 0));
    Kernel k = s.kernel();
    const Kernel::Hit hit = k.closest_hit(s.eye_ray, INFINITY_T);
    ASSERT_EQ(hit.t, 4.0f);
    std::uint32_t shadow_rays = 0;
    Kernel::Rng rng{};  // only area lights draw from it
    EXPECT_TRUE(same(k.shade_local(s.eye_ray, hit, rng, shadow_rays), vec3(0)));
    EXPECT_EQ(shadow_rays, 1u);

    // Without shadows the blocker is ignored and no shadow ray is cast.
    k.HAS_SHADOWS = false;
    shadow_rays = 0;
    expect_near(k.shade_local(s.eye_ray, hit, rng, shadow_rays), s.paper());
    EXPECT_EQ(shadow_rays, 0u);
}

TEST(ShadeLocal, BlockerBeyondTheLightDoesNotShadow) {
    ShadeSetup s;
    // On the line from the hit point through the light, but past it.
    s.scene.spheres.push_back(sphere(vec3(6.0f, 0.0f, 9.0f), 0.5f, 0));
    Kernel k = s.kernel();
    const Kernel::Hit hit = k.closest_hit(s.eye_ray, INFINITY_T);
    std::uint32_t shadow_rays = 0;
    Kernel::Rng rng{};  // only area lights draw from it
    expect_near(k.shade_local(s.eye_ray, hit, rng, shadow_rays), s.paper());
    EXPECT_EQ(shadow_rays, 1u);
}

TEST(ShadeLocal, LightsBelowTheSurfaceCastNoShadowRay) {
    ShadeSetup s;
    // Straight below the hit point, on the far side of the sphere, and one exactly in
    // the tangent plane (cos(theta) = 0).
    s.scene.lights.push_back(point_light(vec3(0.0f, 0.0f, -5.0f), vec3(100.0f)));
    s.scene.lights.push_back(point_light(vec3(4.0f, 0.0f, 1.0f), vec3(100.0f)));
    // A second lit light, opposite the first: same cos(theta), mirrored highlight.
    s.scene.lights.push_back(s.scene.lights[0]);
    s.scene.lights.back().position = vec4(-3.0f, 0.0f, 5.0f, 1.0f);
    Kernel k = s.kernel();
    const Kernel::Hit hit = k.closest_hit(s.eye_ray, INFINITY_T);
    std::uint32_t shadow_rays = 0;
    Kernel::Rng rng{};  // only area lights draw from it
    const vec3 color = k.shade_local(s.eye_ray, hit, rng, shadow_rays);
    EXPECT_EQ(shadow_rays, 2u);
    expect_near(color, 2.0 * s.paper());
    // Shadow rays add up across calls: the counter is the caller's.
    k.shade_local(s.eye_ray, hit, rng, shadow_rays);
    EXPECT_EQ(shadow_rays, 4u);
}

TEST(ShadeLocal, NoHighlightWhenTheMirroredLightPointsAwayFromTheEye) {
    ShadeSetup s;
    // Eye and light on the same side at grazing angles: the eye looks at the hit
    // point (0, 0, 1) from (4, 0, 4) (direction (-0.8, 0, -0.6) exactly), the light
    // is at (3, 0, 5); the mirrored light vector (-0.6, 0, 0.8) makes cos(alpha) =
    // (-0.6)(0.8) + 0.8 (0.6) = 0, no highlight, only the diffuse part.
    Kernel k = s.kernel();
    const Kernel::Ray eye_ray = ray(vec3(4, 0, 4), vec3(-0.8f, 0.0f, -0.6f));
    const Kernel::Hit hit = k.closest_hit(eye_ray, INFINITY_T);
    ASSERT_LT(hit.t, INFINITY_T);
    std::uint32_t shadow_rays = 0;
    Kernel::Rng rng{};  // only area lights draw from it
    const vec3 color = k.shade_local(eye_ray, hit, rng, shadow_rays);
    EXPECT_EQ(shadow_rays, 1u);
    expect_near(color, glm::dvec3(1.6, 0.4, 0.8));
}

// ---------------------------------------------------------------- render_sample

// The Vulkan test's tiny view: 4x4 pixels, 90 degrees, looking down -z at a sphere
// of radius 1.5 three units away that covers exactly the central 2x2 pixels. A
// light sits at the eye, so every visible sphere point is lit and casts one shadow
// ray.
const vec3 kBackground(0.25f, 0.5f, 0.75f);

TestScene tiny_view() {
    TestScene scene;
    Material m{};
    m.diffuse = vec3(0.8f, 0.2f, 0.2f);
    m.kd = 1.0f;
    scene.materials = {m};
    scene.spheres = {sphere(vec3(0, 0, -3), 1.5f, 0)};
    scene.lights = {point_light(vec3(0.0f), vec3(1.0f))};
    return scene;
}

Kernel tiny_kernel(const TestScene& scene) {
    Kernel k = scene.kernel();
    kernel::set_camera_eye(k.params, vec3(0.0f));
    kernel::set_camera_corner(k.params, vec3(-1.0f, 1.0f, -1.0f));
    kernel::set_camera_right(k.params, vec3(0.5f, 0.0f, 0.0f));
    kernel::set_camera_down(k.params, vec3(0.0f, -0.5f, 0.0f));
    kernel::set_background(k.params, vec3(kBackground));
    kernel::set_image_width(k.params, 4);
    kernel::set_image_height(k.params, 4);
    kernel::set_aa_per_side(k.params, 1);
    k.HAS_JITTER = false;
    k.HAS_AMBIENT = false;
    k.HAS_GLOBAL = false;  // local mode: these tests check the paper's shading
    k.HAS_ENVIRONMENT_MAP = false;  // rays that miss see the background colour
    return k;
}

TEST(RenderSample, BackgroundWhereNothingIsHit) {
    const TestScene scene = tiny_view();
    Kernel k = tiny_kernel(scene);
    const Kernel::SampleResult s = k.render_sample(0, 0, 0);
    EXPECT_TRUE(same(s.radiance, kBackground));
    EXPECT_EQ(s.shadow_rays, 0u);
    EXPECT_FALSE(s.truncated);
}

TEST(RenderSample, ShadesTheClosestHitOfTheCameraRay) {
    const TestScene scene = tiny_view();
    Kernel k = tiny_kernel(scene);
    const Kernel::SampleResult s = k.render_sample(1, 2, 0);
    EXPECT_FALSE(s.truncated);
    EXPECT_EQ(s.shadow_rays, 1u);
    // The same steps by hand: pixel (1, 2) at its centre, aa = 1, no jitter.
    const Kernel::Ray r = k.camera_ray(1.5f, 2.5f);
    const Kernel::Hit h = k.closest_hit(r, INFINITY_T);
    ASSERT_LT(h.t, INFINITY_T);
    std::uint32_t shadow_rays = 0;
    Kernel::Rng rng{};  // only area lights draw from it
    EXPECT_TRUE(same(s.radiance, k.shade_local(r, h, rng, shadow_rays)));
    // The light at the eye: cos(theta) = cos(alpha) > 0, so some red must show.
    EXPECT_GT(s.radiance.x, 0.0f);
    EXPECT_GT(s.radiance.x, s.radiance.y);
}

TEST(RenderSample, EachSampleStartsWithAFullBudget) {
    const TestScene scene = tiny_view();
    Kernel k = tiny_kernel(scene);
    // A budget that one sample fits in many times over, but not a hundred samples:
    // the count must start afresh with every sample.
    kernel::set_loop_budget(k.params, 100);
    for (std::uint32_t i = 0; i < 100; ++i) {
        ASSERT_FALSE(k.render_sample(2, 2, i).truncated) << "sample " << i;
    }
}

TEST(AccumulateSample, GoodSamplesAddRadianceAndCount) {
    const TestScene scene = tiny_view();
    Kernel k = tiny_kernel(scene);
    kernel::PixelSum accum{};
    kernel::Counters counters{};
    const Kernel::SampleResult hit = k.render_sample(1, 1, 0);
    const Kernel::SampleResult miss = k.render_sample(3, 0, 0);
    k.accumulate_sample(hit, accum, counters);
    k.accumulate_sample(miss, accum, counters);
    kernel::PixelSum want{};
    kernel::add_sample(want, hit.radiance, k.HAS_SQUARES);
    kernel::add_sample(want, miss.radiance, k.HAS_SQUARES);
    EXPECT_EQ(accum, want);
    EXPECT_EQ(samples_summed(accum), 2u);
    EXPECT_NEAR(radiance_sum(accum).r, double(hit.radiance.r) + double(miss.radiance.r), 1e-11);
    EXPECT_EQ(counters.rays[kernel::RAYS_EYE], 2u);
    EXPECT_EQ(counters.rays[kernel::RAYS_SHADOW], 1u);
    EXPECT_EQ(counters.work[kernel::WORK_TRUNCATED], 0u);
    EXPECT_EQ(counters.work[kernel::WORK_NONFINITE], 0u);
}

TEST(AccumulateSample, TruncatedSampleAddsNoRadianceAndNoSampleCount) {
    const TestScene scene = tiny_view();
    Kernel k = tiny_kernel(scene);
    kernel::PixelSum accum{};
    kernel::Counters counters{};
    k.accumulate_sample(k.render_sample(1, 1, 0), accum, counters);
    const kernel::PixelSum after_good = accum;
    ASSERT_EQ(samples_summed(after_good), 1u);

    // A sphere pixel needs at least one sphere test and one light iteration: a budget
    // of one cannot cover it, however loop entries are charged.
    kernel::set_loop_budget(k.params, 1);
    const Kernel::SampleResult cut = k.render_sample(1, 1, 1);
    EXPECT_TRUE(cut.truncated);
    k.accumulate_sample(cut, accum, counters);
    EXPECT_EQ(accum, after_good);
    EXPECT_EQ(counters.rays[kernel::RAYS_EYE], 2u);
    EXPECT_EQ(counters.work[kernel::WORK_TRUNCATED], 1u);
    EXPECT_EQ(counters.work[kernel::WORK_NONFINITE], 0u);
    EXPECT_EQ(counters.rays[kernel::RAYS_SHADOW], 1u + cut.shadow_rays);

    // With no budget at all even a background pixel is cut.
    kernel::set_loop_budget(k.params, 0);
    const Kernel::SampleResult none = k.render_sample(0, 0, 2);
    EXPECT_TRUE(none.truncated);
    k.accumulate_sample(none, accum, counters);
    EXPECT_EQ(accum, after_good);
    EXPECT_EQ(counters.rays[kernel::RAYS_EYE], 3u);
    EXPECT_EQ(counters.work[kernel::WORK_TRUNCATED], 2u);

    // The budget restored, the next sample counts again.
    kernel::set_loop_budget(k.params, kernel::DEFAULT_LOOP_BUDGET);
    k.accumulate_sample(k.render_sample(1, 1, 3), accum, counters);
    EXPECT_EQ(samples_summed(accum), 2u);
    EXPECT_EQ(counters.work[kernel::WORK_TRUNCATED], 2u);
}

Kernel::SampleResult sample_result(vec3 radiance, std::uint32_t shadow_rays, std::uint32_t cells, std::uint32_t tests,
                                   bool truncated) {
    Kernel::SampleResult r{};
    r.radiance = radiance;
    r.shadow_rays = shadow_rays;
    r.cells_visited = cells;
    r.intersection_tests = tests;
    r.truncated = truncated;
    return r;
}

TEST(AccumulateSample, NonFiniteSampleIsCountedNotSummed) {
    Kernel k;
    kernel::PixelSum accum{};
    kernel::add_sample(accum, vec3(1.0f, 2.0f, 3.0f), false);
    const kernel::PixelSum before = accum;
    kernel::Counters counters{uvec4(1u, 0u, 0u, 0u), uvec4(0u), uvec4(0u), uvec4(0u)};
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    k.accumulate_sample(sample_result(vec3(0.0f, nan, 0.0f), 2u, 3u, 5u, false), accum, counters);
    k.accumulate_sample(sample_result(vec3(inf, 0.0f, 0.0f), 0u, 0u, 1u, false), accum, counters);
    EXPECT_EQ(accum, before);
    EXPECT_EQ(counters.rays, uvec4(3u, 2u, 0u, 0u));
    EXPECT_EQ(counters.work, uvec4(3u, 6u, 0u, 2u));
    // Truncation takes precedence: a cut sample is reported as cut, whatever its value.
    k.accumulate_sample(sample_result(vec3(nan), 0u, 0u, 0u, true), accum, counters);
    EXPECT_EQ(counters.rays, uvec4(4u, 2u, 0u, 0u));
    EXPECT_EQ(counters.work, uvec4(3u, 6u, 1u, 2u));
    EXPECT_EQ(accum, before);
}

}  // namespace
