// The quad test (intersect_quad) through the reference backend: a scene file's quad
// is one parallelogram record, tested once. Hand-worked values where every
// intermediate is exact in float, the triangle case against intersect_triangle bit
// for bit, rays through a shared edge, and the scene-level switch (HAS_QUADS).
#include <gtest/gtest.h>

#include <cstdint>
#include <random>

#include "flatten/flat_scene.hpp"
#include "kernel/kernel.hpp"
#include "render/render.hpp"
#include "scene/scene.hpp"
#include "test_support.hpp"

namespace {

using vkrt::kernel::INFINITY_T;
using vkrt::kernel::Kernel;
using vkrt::kernel::vec3;

Kernel::Ray ray(vec3 origin, vec3 dir) { return Kernel::Ray(origin, dir); }

// The parallelogram (0,0,0), (2,0,0), (3,1,0), (1,1,0): edges e1 = (2,0,0), e2 = (1,1,0).
const vec3 kP0(0, 0, 0), kP1(2, 0, 0), kP2(3, 1, 0), kP3(1, 1, 0);

TEST(QuadIntersect, HitGivesDistanceAndHalfTheEdgeCoordinates) {
    Kernel k;
    // (1.5, 0.5) = p0 + 0.5 e1 + 0.5 e2: u = v = 0.25.
    const auto h = k.intersect_quad(ray(vec3(1.5f, 0.5f, 4), vec3(0, 0, -1)), kP0, kP1, kP2, kP3, 0.0f, INFINITY_T);
    EXPECT_EQ(h.t, 4.0f);
    EXPECT_EQ(h.u, 0.25f);
    EXPECT_EQ(h.v, 0.25f);
    // (2.75, 0.75) = p0 + 1 e1 + 0.75 e2, in the half the first triangle p0 p1 p2 lacks.
    const auto g = k.intersect_quad(ray(vec3(2.5f, 0.75f, 4), vec3(0, 0, -1)), kP0, kP1, kP2, kP3, 0.0f, INFINITY_T);
    EXPECT_EQ(g.t, 4.0f);
    EXPECT_EQ(g.u, 0.5f * 0.875f);
    EXPECT_EQ(g.v, 0.5f * 0.75f);
}

TEST(QuadIntersect, HitsBothFaces) {
    Kernel k;
    EXPECT_EQ(k.intersect_quad(ray(vec3(1, 0.5f, -2), vec3(0, 0, 1)), kP0, kP1, kP2, kP3, 0.0f, INFINITY_T).t, 2.0f);
}

TEST(QuadIntersect, MissesBeyondEachEdgeAndOutsideTheInterval) {
    Kernel k;
    const vec3 down(0, 0, -1);
    auto t_at = [&](float x, float y) {
        return k.intersect_quad(ray(vec3(x, y, 4), down), kP0, kP1, kP2, kP3, 0.0f, INFINITY_T).t;
    };
    EXPECT_EQ(t_at(1.0f, -0.25f), INFINITY_T);  // below p0 p1
    EXPECT_EQ(t_at(2.75f, 0.5f), INFINITY_T);   // right of p1 p2 (x - y > 2)
    EXPECT_EQ(t_at(2.0f, 1.25f), INFINITY_T);   // above p2 p3
    EXPECT_EQ(t_at(0.25f, 0.5f), INFINITY_T);   // left of p3 p0 (x < y)
    EXPECT_EQ(t_at(1.0f, 0.5f), 4.0f);
    // In the quad's plane, behind the origin, beyond t_max.
    EXPECT_EQ(k.intersect_quad(ray(vec3(-1, 0.5f, 0), vec3(1, 0, 0)), kP0, kP1, kP2, kP3, 0.0f, INFINITY_T).t,
              INFINITY_T);
    EXPECT_EQ(k.intersect_quad(ray(vec3(1, 0.5f, 4), vec3(0, 0, 1)), kP0, kP1, kP2, kP3, 0.0f, INFINITY_T).t,
              INFINITY_T);
    EXPECT_EQ(k.intersect_quad(ray(vec3(1, 0.5f, 4), down), kP0, kP1, kP2, kP3, 0.0f, 4.0f).t, INFINITY_T);
}

// With p3 = p2 the fourth edge function is exactly zero: intersect_triangle's result,
// bit for bit, on random triangles and rays.
TEST(QuadIntersect, WithTheFourthVertexOnTheThirdIsTheTriangleTest) {
    Kernel k;
    std::mt19937 gen(7);
    std::uniform_real_distribution<float> coord(-2.0f, 2.0f);
    auto point = [&] { return vec3(coord(gen), coord(gen), coord(gen)); };
    int hits = 0;
    for (int i = 0; i < 20000; ++i) {
        const vec3 a = point(), b = point(), c = point();
        const vec3 o = point() * 3.0f;
        const vec3 d = glm::normalize((a + b + c) / 3.0f + 0.5f * point() - o);
        const auto tri = k.intersect_triangle(ray(o, d), a, b, c, 0.0f, INFINITY_T);
        const auto quad = k.intersect_quad(ray(o, d), a, b, c, c, 0.0f, INFINITY_T);
        ASSERT_EQ(tri.t, quad.t) << i;
        ASSERT_EQ(tri.u, quad.u) << i;
        ASSERT_EQ(tri.v, quad.v) << i;
        hits += tri.t != INFINITY_T;
    }
    EXPECT_GT(hits, 5000);
}

// Two parallelograms sharing an edge: a ray through any point of the edge hits one
// of them at least (the edge functions of both come from the same sheared vertices).
TEST(QuadIntersect, RaysThroughASharedEdgeHitOneSide) {
    Kernel k;
    const vec3 a(-0.3f, 0.1f, 0.2f), b(0.7f, -0.2f, 0.4f);  // the shared edge
    const vec3 left(-0.1f, 0.9f, 0.3f), right(0.2f, -0.8f, -0.1f);
    std::mt19937 gen(11);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int i = 0; i < 20000; ++i) {
        const vec3 on_edge = a + unit(gen) * (b - a);
        const vec3 o = vec3(unit(gen) - 0.5f, unit(gen) - 0.5f, 2.0f + unit(gen));
        const Kernel::Ray r = ray(o, glm::normalize(on_edge - o));
        // a b (b+left) (a+left) and b a (a+right) (b+right): both wound the same way.
        const bool hit_left = k.intersect_quad(r, a, b, b + left, a + left, 0.0f, INFINITY_T).t != INFINITY_T;
        const bool hit_right = k.intersect_quad(r, b, a, a + right, b + right, 0.0f, INFINITY_T).t != INFINITY_T;
        ASSERT_TRUE(hit_left || hit_right) << i;
    }
}

// A quad in a scene: one record, the HAS_QUADS feature on, and left out of a scene of
// triangles only.
TEST(QuadScene, OneRecordAndTheFeatureOnlyWhereNeeded) {
    vkrt::Scene s;
    s.materials.push_back(vkrt::Material{});
    s.triangles.push_back(vkrt::quad({0, 0, 0}, {1, 0, 0}, {0, 0, 1}, 0));
    const vkrt::FlatScene with = vkrt::flatten_scene(s);
    EXPECT_EQ(with.triangles.size(), 1u);
    EXPECT_TRUE(with.features.has(vkrt::Feature::HAS_QUADS));
    s.triangles[0].parallelogram = false;
    EXPECT_FALSE(vkrt::flatten_scene(s).features.has(vkrt::Feature::HAS_QUADS));
}

// A room of axis-aligned quads under a point light, once as quads and once as the
// two triangles each quad used to be: the same image bit for bit (the planes are
// exact, and the diagonal was no edge the image could show), from half the tests.
TEST(QuadScene, RendersAsItsTwoTrianglesWithHalfTheTests) {
    using glm::dvec3;
    vkrt::Scene quads;
    quads.camera = vkrt::Camera{{0, 1, 3.4}, {0, 1, 0}, {0, 1, 0}, 40.0, 48, 36, 0.0, {}};
    vkrt::Material white;
    white.diffuse = dvec3(0.75);
    quads.materials = {white};
    quads.lights.push_back(vkrt::Light{{0.3, 1.8, 0.2}, dvec3(1.0), 1.0});
    quads.triangles = {vkrt::quad({-1, 0, -1}, {0, 0, 2}, {2, 0, 0}, 0), vkrt::quad({-1, 2, -1}, {2, 0, 0}, {0, 0, 2}, 0),
                       vkrt::quad({-1, 0, -1}, {2, 0, 0}, {0, 2, 0}, 0), vkrt::quad({-1, 0, -1}, {0, 2, 0}, {0, 0, 2}, 0),
                       vkrt::quad({1, 0, -1}, {0, 0, 2}, {0, 2, 0}, 0)};
    quads.spheres.push_back(vkrt::Sphere{{0.2, 0.4, -0.2}, 0.3, 0});
    vkrt::Scene halves = quads;
    halves.triangles.clear();
    for (const vkrt::Triangle& q : quads.triangles) {
        const auto& v = q.vertices;
        halves.triangles.push_back(vkrt::Triangle{{v[0], v[1], v[2]}, std::nullopt, q.material});
        halves.triangles.push_back(vkrt::Triangle{{v[0], v[2], v[0] + v[2] - v[1]}, std::nullopt, q.material});
    }
    const vkrt::RenderOutcome a = vkrt::test::render_cpu(quads);
    const vkrt::RenderOutcome b = vkrt::test::render_cpu(halves);
    EXPECT_EQ(vkrt::test::max_abs_difference(a.image, b.image), 0.0f);
    // The sphere's test is one of 6 per ray against one of 11.
    EXPECT_LT(double(a.stats.intersection_tests), 0.6 * double(b.stats.intersection_tests));
}

}  // namespace
