// A shadow ray's sphere test (shapes/sphere.glsl, sphere_blocks): whether the sphere has a
// root in (0, t_max). Hand-worked cases with exact floats, origins on the surface
// (which count as on it, whatever c rounds to), and agreement with intersect_sphere
// on random rays wherever the answer does not hang on a rounding.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "kernel/kernel.hpp"

namespace {

using vkrt::kernel::INFINITY_T;
using vkrt::kernel::Kernel;
using vkrt::kernel::vec3;

Kernel::Ray ray(vec3 origin, vec3 dir) { return Kernel::Ray(origin, dir); }

TEST(SphereBlocks, FromOutsideTheNearRootDecides) {
    Kernel k;
    const Kernel::Ray r = ray(vec3(0, 0, 5), vec3(0, 0, -1));  // roots 4 and 6
    EXPECT_TRUE(k.sphere_blocks(r, vec3(0), 1.0f, 4.5f));
    EXPECT_TRUE(k.sphere_blocks(r, vec3(0), 1.0f, INFINITY_T));
    EXPECT_FALSE(k.sphere_blocks(r, vec3(0), 1.0f, 4.0f)) << "t_max is exclusive";
    EXPECT_FALSE(k.sphere_blocks(r, vec3(0), 1.0f, 3.0f));
}

TEST(SphereBlocks, FromInsideTheFarRootDecides) {
    Kernel k;
    const Kernel::Ray r = ray(vec3(0), vec3(1, 0, 0));  // radius 2: roots -2 and 2
    EXPECT_TRUE(k.sphere_blocks(r, vec3(0), 2.0f, 2.5f));
    EXPECT_FALSE(k.sphere_blocks(r, vec3(0), 2.0f, 2.0f));
    EXPECT_FALSE(k.sphere_blocks(r, vec3(0), 2.0f, 1.0f)) << "a light inside the sphere with the ray";
}

TEST(SphereBlocks, RootsBehindOrNoneDoNotBlock) {
    Kernel k;
    EXPECT_FALSE(k.sphere_blocks(ray(vec3(0, 0, 5), vec3(0, 0, 1)), vec3(0), 1.0f, INFINITY_T)) << "behind";
    EXPECT_FALSE(k.sphere_blocks(ray(vec3(2, 0, 5), vec3(0, 0, -1)), vec3(0), 1.0f, INFINITY_T)) << "passes by";
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    EXPECT_FALSE(k.sphere_blocks(ray(vec3(nan, 0, 5), vec3(0, 0, -1)), vec3(0), 1.0f, INFINITY_T));
    EXPECT_FALSE(k.sphere_blocks(ray(vec3(0, 0, 5), vec3(0, 0, -1)), vec3(0), nan, INFINITY_T));
    EXPECT_FALSE(k.sphere_blocks(ray(vec3(0, 0, inf), vec3(0, 0, -1)), vec3(0), 1.0f, INFINITY_T));
}

// c is exactly 0: a ray leaving the surface is not blocked by its sphere; one that
// enters it is, at the far root 2 r cos.
TEST(SphereBlocks, OnTheSurfaceLeavingIsFreeAndEnteringIsBlocked) {
    Kernel k;
    const vec3 p(0, 0, 1);
    EXPECT_FALSE(k.sphere_blocks(ray(p, vec3(0, 0, 1)), vec3(0), 1.0f, INFINITY_T));
    EXPECT_FALSE(k.sphere_blocks(ray(p, vec3(0.6f, 0, 0.8f)), vec3(0), 1.0f, INFINITY_T));
    EXPECT_TRUE(k.sphere_blocks(ray(p, vec3(0, 0, -1)), vec3(0), 1.0f, 2.5f));
    EXPECT_FALSE(k.sphere_blocks(ray(p, vec3(0, 0, -1)), vec3(0), 1.0f, 1.5f));
    EXPECT_TRUE(k.sphere_blocks(ray(p, vec3(0.6f, 0, -0.8f)), vec3(0), 1.0f, 1.7f));  // far root 1.6
}

// Points on a sphere of radius 1e5 near its top, where |oc|^2 - r^2 is far below the
// rounding of |oc|^2, moved off it as the kernel moves shadow rays' origins
// (offset_ray_origin), and also left where they rounded: rays toward lights above
// the horizon are never blocked by the sphere they leave, rays into it always are.
TEST(SphereBlocks, ShadowRaysLeavingAHugeSphereAreNotBlockedByIt) {
    Kernel k;
    const float r = 1e5f;
    const vec3 centre(0, -1e5f, 0);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> spot(-20.0f, 20.0f);
    std::uniform_real_distribution<float> sky(-1.0f, 1.0f);
    int tested = 0;
    for (int i = 0; i < 2000; ++i) {
        // The hit of a ray from 1.5 above the top straight down through (x, 0, z).
        const vec3 eye(spot(rng), 1.5f, spot(rng));
        const Kernel::Ray down = ray(eye, vec3(0, -1, 0));
        const float t = k.intersect_sphere(down, centre, r, 0.0f, INFINITY_T);
        ASSERT_LT(t, INFINITY_T);
        const vec3 p = eye + t * down.dir;
        const vec3 n = k.unit_vector(p - centre);
        for (const vec3 origin : {p, k.offset_ray_origin(p, n)}) {
            const vec3 up = k.unit_vector(vec3(sky(rng), 0.05f + std::abs(sky(rng)), sky(rng)));
            if (up.x * n.x + up.y * n.y + up.z * n.z <= 0.01f) continue;  // at the horizon
            EXPECT_FALSE(k.sphere_blocks(ray(origin, up), centre, r, 100.0f)) << "point " << i;
            EXPECT_TRUE(k.sphere_blocks(ray(origin, -up), centre, r, INFINITY_T)) << "point " << i;
            ++tested;
        }
    }
    EXPECT_GT(tested, 3000);
}

// The roots of |o + t d - centre|^2 = r^2 in double, d unit.
struct Roots {
    bool real;
    double t0, t1;
};
Roots double_roots(vec3 o, vec3 d, vec3 centre, double r) {
    const double ox = double(o.x) - centre.x, oy = double(o.y) - centre.y, oz = double(o.z) - centre.z;
    const double b = ox * d.x + oy * d.y + oz * d.z;
    const double c = ox * ox + oy * oy + oz * oz - r * r;
    const double disc = b * b - c;
    if (disc < 0.0) return {false, 0.0, 0.0};
    return {true, -b - std::sqrt(disc), -b + std::sqrt(disc)};
}

// Random spheres and rays, with origins from deep inside to far outside (including
// the band 0.8 r to 1.5 r where intersect_sphere takes its error-free c): the answer
// equals intersect_sphere's wherever the double roots lie clear of 0, of t_max and
// of each other (a tangent ray) by a relative 1e-4.
TEST(SphereBlocks, AgreesWithIntersectSphereAwayFromRoundings) {
    Kernel k;
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::uniform_real_distribution<float> scale(-3.0f, 3.0f);
    std::uniform_real_distribution<float> how_far(0.0f, 3.0f);
    int compared = 0, blocked = 0;
    const int total = 100000;
    for (int i = 0; i < total; ++i) {
        const float r = std::pow(10.0f, scale(rng));
        const vec3 centre = r * vec3(u(rng), u(rng), u(rng)) * 10.0f;
        const vec3 from_centre = k.unit_vector(vec3(u(rng), u(rng), u(rng)));
        const vec3 o = centre + (how_far(rng) * r) * from_centre;
        const vec3 d = k.unit_vector(vec3(u(rng), u(rng), u(rng)));
        const float t_max = r * std::pow(10.0f, scale(rng) / 1.5f);
        const Roots roots = double_roots(o, d, centre, r);
        const double eps = 1e-4 * r;
        auto clear = [&](double t) { return std::abs(t) > eps && std::abs(t - t_max) > 1e-4 * t_max; };
        if (roots.real && (!clear(roots.t0) || !clear(roots.t1) || roots.t1 - roots.t0 < eps)) continue;
        ++compared;
        const bool want = k.intersect_sphere(ray(o, d), centre, r, 0.0f, t_max) != INFINITY_T;
        const bool got = k.sphere_blocks(ray(o, d), centre, r, t_max);
        ASSERT_EQ(got, want) << "case " << i << ": r " << r << ", t_max " << t_max << ", roots " << roots.t0 << " "
                             << roots.t1;
        blocked += got ? 1 : 0;
    }
    EXPECT_GT(compared, total * 9 / 10);
    EXPECT_GT(blocked, total / 10) << "the rays must be blocked often enough to test";
}

}  // namespace
