// Kernel intersection maths through the reference backend's view of the shared
// GLSL, with expected values worked out by hand. The inputs are chosen so that
// every intermediate is exact in float, so the checks are equalities.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>

#include <algorithm>
#include <limits>

#include "kernel/kernel.hpp"

namespace {

using vkrt::kernel::INFINITY_T;
using vkrt::kernel::Kernel;
using vkrt::kernel::vec3;

Kernel::Ray ray(vec3 origin, vec3 dir) { return Kernel::Ray(origin, dir); }

TEST(SphereIntersect, HitsNearSideFromOutside) {
    Kernel k;
    // Origin 5 units from the centre of a unit sphere: roots at 4 and 6.
    EXPECT_EQ(k.intersect_sphere(ray(vec3(0, 0, 5), vec3(0, 0, -1)), vec3(0), 1.0f, 0.0f, INFINITY_T), 4.0f);
}

TEST(SphereIntersect, HitsFarSideFromInside) {
    Kernel k;
    EXPECT_EQ(k.intersect_sphere(ray(vec3(0, 0, 0), vec3(1, 0, 0)), vec3(0), 2.0f, 0.0f, INFINITY_T), 2.0f);
}

TEST(SphereIntersect, OffCentreHitMatchesPythagoras) {
    Kernel k;
    // The ray runs 3 units from the centre of a radius-5 sphere: half-chord 4,
    // closest approach at t = 10, so the near root is 6.
    EXPECT_EQ(k.intersect_sphere(ray(vec3(3, 0, 10), vec3(0, 0, -1)), vec3(0), 5.0f, 0.0f, INFINITY_T), 6.0f);
}

TEST(SphereIntersect, Misses) {
    Kernel k;
    EXPECT_EQ(k.intersect_sphere(ray(vec3(2, 0, 5), vec3(0, 0, -1)), vec3(0), 1.0f, 0.0f, INFINITY_T), INFINITY_T);
    // Sphere behind the ray.
    EXPECT_EQ(k.intersect_sphere(ray(vec3(0, 0, 5), vec3(0, 0, 1)), vec3(0), 1.0f, 0.0f, INFINITY_T), INFINITY_T);
}

TEST(SphereIntersect, RespectsTheInterval) {
    Kernel k;
    const auto r = ray(vec3(0, 0, 5), vec3(0, 0, -1));
    EXPECT_EQ(k.intersect_sphere(r, vec3(0), 1.0f, 0.0f, 4.0f), INFINITY_T);  // t_max is exclusive
    EXPECT_EQ(k.intersect_sphere(r, vec3(0), 1.0f, 4.5f, INFINITY_T), 6.0f);  // near root cut by t_min
}

TEST(TriangleIntersect, HitGivesDistanceAndBarycentrics) {
    Kernel k;
    // Right triangle in the z = 0 plane; the ray comes down the z axis at (0.25, 0.5).
    const auto h = k.intersect_triangle(ray(vec3(0.25f, 0.5f, 2), vec3(0, 0, -1)), vec3(0, 0, 0), vec3(1, 0, 0),
                                        vec3(0, 1, 0), 0.0f, INFINITY_T);
    EXPECT_EQ(h.t, 2.0f);
    EXPECT_EQ(h.u, 0.25f);
    EXPECT_EQ(h.v, 0.5f);
}

TEST(TriangleIntersect, HitsBackFaceToo) {
    Kernel k;
    const auto h = k.intersect_triangle(ray(vec3(0.25f, 0.25f, -3), vec3(0, 0, 1)), vec3(0, 0, 0), vec3(1, 0, 0),
                                        vec3(0, 1, 0), 0.0f, INFINITY_T);
    EXPECT_EQ(h.t, 3.0f);
}

TEST(TriangleIntersect, Misses) {
    Kernel k;
    const vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
    // Outside the hypotenuse: u + v = 1.25 > 1.
    EXPECT_EQ(k.intersect_triangle(ray(vec3(0.75f, 0.5f, 2), vec3(0, 0, -1)), a, b, c, 0.0f, INFINITY_T).t, INFINITY_T);
    // u < 0.
    EXPECT_EQ(k.intersect_triangle(ray(vec3(-0.25f, 0.5f, 2), vec3(0, 0, -1)), a, b, c, 0.0f, INFINITY_T).t, INFINITY_T);
    // Parallel to the plane.
    EXPECT_EQ(k.intersect_triangle(ray(vec3(0.25f, 0.25f, 1), vec3(1, 0, 0)), a, b, c, 0.0f, INFINITY_T).t, INFINITY_T);
    // Behind the origin.
    EXPECT_EQ(k.intersect_triangle(ray(vec3(0.25f, 0.25f, 2), vec3(0, 0, 1)), a, b, c, 0.0f, INFINITY_T).t, INFINITY_T);
    // Beyond t_max.
    EXPECT_EQ(k.intersect_triangle(ray(vec3(0.25f, 0.25f, 2), vec3(0, 0, -1)), a, b, c, 0.0f, 2.0f).t, INFINITY_T);
}

TEST(TriangleNormals, FaceNormalFollowsWinding) {
    Kernel k;
    const vec3 n = k.triangle_face_normal(vec3(0, 0, 0), vec3(2, 0, 0), vec3(0, 2, 0));
    EXPECT_EQ(n, vec3(0, 0, 1));
    EXPECT_EQ(k.triangle_face_normal(vec3(0, 0, 0), vec3(0, 2, 0), vec3(2, 0, 0)), vec3(0, 0, -1));
}

TEST(TriangleNormals, InterpolationUsesBarycentricWeights) {
    Kernel k;
    const vec3 face(0, 0, 1);
    // At a vertex the blend is that vertex's normal.
    EXPECT_EQ(k.interpolate_normal(vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1), 0.0f, 0.0f, face), vec3(1, 0, 0));
    EXPECT_EQ(k.interpolate_normal(vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1), 1.0f, 0.0f, face), vec3(0, 1, 0));
    // Halfway along the edge p1-p2 with unnormalized vertex normals (0, 3, 0) and
    // (0, 0, 4): the blend (0, 1.5, 2) has length 2.5, so the result is (0, 0.6, 0.8).
    const vec3 n = k.interpolate_normal(vec3(1, 0, 0), vec3(0, 3, 0), vec3(0, 0, 4), 0.5f, 0.5f, face);
    EXPECT_FLOAT_EQ(n.x, 0.0f);
    EXPECT_FLOAT_EQ(n.y, 0.6f);
    EXPECT_FLOAT_EQ(n.z, 0.8f);
}

TEST(TriangleNormals, OpposingNormalsFallBackToFace) {
    Kernel k;
    const vec3 face(0, 0, 1);
    // Halfway between opposite vertex normals the blend is zero.
    EXPECT_EQ(k.interpolate_normal(vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), 0.5f, 0.0f, face), face);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(k.interpolate_normal(vec3(nan), vec3(0, 1, 0), vec3(0, 1, 0), 0.2f, 0.2f, face), face);
}

// Near the origin the offset is fixed: 2^-16 of the normal within 1/32 of it, both
// times 2^-offset_shrink() (decision 0053), exactly.
TEST(RayOffset, NearTheOriginMovesByTheScenesScale) {
    Kernel k;
    const vec3 n(0.0f, 0.0f, 1.0f);
    EXPECT_EQ(k.offset_ray_origin(vec3(0.0f, 0.0f, 0.01f), n).z, 0.01f + 0x1p-16f);
    vkrt::kernel::set_offset_shrink(k.params, 17u);
    // 2^-22 is the origin region now: 1e-7 lies inside, 1e-6 outside.
    EXPECT_EQ(k.offset_ray_origin(vec3(0.0f, 0.0f, 1e-7f), n).z, 1e-7f + 0x1p-33f);
    const float outside = 1e-6f;
    EXPECT_EQ(k.offset_ray_origin(vec3(0.0f, 0.0f, outside), n).z,
              std::bit_cast<float>(std::bit_cast<std::int32_t>(outside) + 256));
    // 0.01 was inside the origin region at shrink 0 and is outside it now: 256 ULPs.
    EXPECT_EQ(k.offset_ray_origin(vec3(0.0f, 0.0f, 0.01f), n).z,
              std::bit_cast<float>(std::bit_cast<std::int32_t>(0.01f) + 256));
}

TEST(RayOffset, MovesAlongTheNormalAtEveryScale) {
    Kernel k;
    for (float scale : {1e-3f, 1.0f, 1e3f, 1e5f, 1e7f}) {
        const vec3 p(scale, -scale, 0.5f * scale);
        const vec3 n(0, 0, 1);
        const vec3 q = k.offset_ray_origin(p, n);
        EXPECT_EQ(q.x, p.x) << scale;
        EXPECT_EQ(q.y, p.y) << scale;
        EXPECT_GT(q.z, p.z) << scale;
        // Small relative to the magnitude: a few hundred ULPs at most.
        EXPECT_LT(q.z - p.z, 1e-4f * std::max(1.0f, scale)) << scale;
    }
}

}  // namespace
