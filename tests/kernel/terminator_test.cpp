// The shadow terminator fix (kernel/terminator.glsl): shadow rays of a smooth
// triangle leave from the quadratic surface its vertex normals describe (Hanika
// 2021). The lift is checked against the construction recomputed in double, for
// its properties (zero at the corners, on flat and concave triangles and for broken
// normals; the same on both sides of a shared edge; toward a sphere the normals come
// from), and the whole effect on images: a coarse smooth tube renders like a fine
// one, where without the lift its terminator follows the facets.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "image/image.hpp"
#include "kernel/kernel.hpp"
#include "test_support.hpp"

namespace {

using vkrt::kernel::Kernel;
using vkrt::kernel::Triangle;
using vkrt::kernel::uvec4;
using vkrt::kernel::vec3;
using vkrt::kernel::vec4;
using dvec3 = glm::dvec3;

Triangle smooth_triangle(vec3 p0, vec3 p1, vec3 p2, vec3 n0, vec3 n1, vec3 n2) {
    return Triangle{vec4(p0, 0.0f), vec4(p1, 0.0f), vec4(p2, 0.0f), vec4(n0, 0.0f), vec4(n1, 0.0f), vec4(n2, 0.0f),
                    uvec4(0u, 1u, 0u, 0u)};
}

// Hanika's construction in double: p projected onto each corner's tangent plane
// where it lies below it, the projections blended by the barycentric weights.
dvec3 expected_lift(const Triangle& t, double u, double v, double side) {
    const double w = 1.0 - u - v;
    const std::array<dvec3, 3> p = {dvec3(t.p0), dvec3(t.p1), dvec3(t.p2)};
    const std::array<dvec3, 3> n = {side * dvec3(t.n0), side * dvec3(t.n1), side * dvec3(t.n2)};
    const std::array<double, 3> b = {w, u, v};
    const dvec3 at = w * p[0] + u * p[1] + v * p[2];
    dvec3 lifted(0.0);
    for (int i = 0; i < 3; ++i) {
        const double below = std::min(0.0, glm::dot(at - p[i], n[i]));
        lifted += b[i] * (at - below * n[i]);
    }
    return lifted - at;
}

const vec3 kUp(0, 0, 1);
// A triangle in the plane z = 0, its front face up.
const vec3 kP0(0, 0, 0), kP1(1, 0, 0), kP2(0, 1, 0);

// Normals leaning away from the triangle's middle, as on a dome.
Triangle dome() {
    return smooth_triangle(kP0, kP1, kP2, glm::normalize(vec3(-0.3f, -0.3f, 1)), glm::normalize(vec3(0.4f, -0.1f, 1)),
                           glm::normalize(vec3(-0.1f, 0.4f, 1)));
}

TEST(TerminatorLift, MatchesTheConstructionInDouble) {
    Kernel k;
    const Triangle t = dome();
    for (const auto& [u, v] : std::array<std::pair<float, float>, 5>{{{0.25f, 0.25f}, {0.5f, 0.25f}, {0.1f, 0.8f},
                                                                       {0.5f, 0.5f}, {0.0f, 0.5f}}}) {
        const vec3 got = k.terminator_lift(t, u, v, 1.0f, kUp);
        const dvec3 want = expected_lift(t, u, v, 1.0);
        EXPECT_GT(want.z, 1e-3) << "a dome lifts its inside";
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], 1e-7) << "u " << u << " v " << v << " axis " << c;
    }
}

TEST(TerminatorLift, IsZeroAtTheCorners) {
    Kernel k;
    const Triangle t = dome();
    EXPECT_EQ(k.terminator_lift(t, 0.0f, 0.0f, 1.0f, kUp), vec3(0.0f));
    EXPECT_EQ(k.terminator_lift(t, 1.0f, 0.0f, 1.0f, kUp), vec3(0.0f));
    EXPECT_EQ(k.terminator_lift(t, 0.0f, 1.0f, 1.0f, kUp), vec3(0.0f));
}

TEST(TerminatorLift, IsZeroOnAFlatTriangle) {
    Kernel k;
    const Triangle t = smooth_triangle(kP0, kP1, kP2, kUp, kUp, kUp);
    EXPECT_EQ(k.terminator_lift(t, 0.25f, 0.5f, 1.0f, kUp), vec3(0.0f));
    EXPECT_EQ(k.terminator_lift(t, 0.25f, 0.5f, -1.0f, -kUp), vec3(0.0f));
}

TEST(TerminatorLift, IsZeroWhereTheSurfaceIsConcave) {
    Kernel k;
    // Normals leaning toward the middle, as in a bowl: p is above every tangent plane.
    const Triangle bowl = smooth_triangle(kP0, kP1, kP2, glm::normalize(vec3(0.3f, 0.3f, 1)),
                                          glm::normalize(vec3(-0.4f, 0.1f, 1)), glm::normalize(vec3(0.1f, -0.4f, 1)));
    EXPECT_EQ(k.terminator_lift(bowl, 0.3f, 0.3f, 1.0f, kUp), vec3(0.0f));
    // A dome seen from below is a bowl.
    EXPECT_EQ(k.terminator_lift(dome(), 0.3f, 0.3f, -1.0f, -kUp), vec3(0.0f));
}

TEST(TerminatorLift, SeenFromBehindABowlLiftsDownward) {
    Kernel k;
    const Triangle bowl = smooth_triangle(kP0, kP1, kP2, glm::normalize(vec3(0.3f, 0.3f, 1)),
                                          glm::normalize(vec3(-0.4f, 0.1f, 1)), glm::normalize(vec3(0.1f, -0.4f, 1)));
    const vec3 got = k.terminator_lift(bowl, 0.3f, 0.3f, -1.0f, -kUp);
    const dvec3 want = expected_lift(bowl, 0.3, 0.3, -1.0);
    EXPECT_LT(want.z, -1e-3);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], 1e-7);
}

TEST(TerminatorLift, NeverMovesThroughTheSurface) {
    Kernel k;
    // Normals that lean far over and point below the face at two corners: the blend
    // would go down, so the lift is dropped.
    const Triangle broken = smooth_triangle(kP0, kP1, kP2, glm::normalize(vec3(-1, -1, 0.1f)),
                                            glm::normalize(vec3(1, 0, -1)), glm::normalize(vec3(0, 1, -1)));
    ASSERT_LT(expected_lift(broken, 0.3, 0.3, 1.0).z, 0.0);
    EXPECT_EQ(k.terminator_lift(broken, 0.3f, 0.3f, 1.0f, kUp), vec3(0.0f));
}

// Two triangles sharing an edge lift its points alike: the lifted surface has no
// step where the shadows would show one.
TEST(TerminatorLift, AgreesAcrossASharedEdge) {
    Kernel k;
    const vec3 a(0, 0, 0), b(1, 0, 0), c(0.3f, 1, 0.2f), d(0.6f, -1, 0.1f);
    const vec3 na = glm::normalize(vec3(-0.2f, 0.1f, 1)), nb = glm::normalize(vec3(0.3f, -0.1f, 1));
    const vec3 nc = glm::normalize(vec3(0, 0.3f, 1)), nd = glm::normalize(vec3(0.1f, -0.4f, 1));
    const Triangle first = smooth_triangle(a, b, c, na, nb, nc);
    const Triangle second = smooth_triangle(b, a, d, nb, na, nd);
    for (float s : {0.2f, 0.5f, 0.7f}) {
        // The point a + s (b - a): u = s on the first (weight of b), v = 0; on the
        // second a is its p1, so u = 1 - s.
        const vec3 l1 = k.terminator_lift(first, s, 0.0f, 1.0f, kUp);
        const vec3 l2 = k.terminator_lift(second, 1.0f - s, 0.0f, 1.0f, kUp);
        EXPECT_GT(l1.z, 0.0f);
        for (int i = 0; i < 3; ++i) EXPECT_NEAR(l1[i], l2[i], 1e-7f) << "s " << s;
    }
}

// Triangles inscribed in a unit sphere with the sphere's normals: the lifted point is
// nearer the sphere than the hit on the flat triangle, everywhere inside.
TEST(TerminatorLift, MovesTowardTheSphereTheNormalsComeFrom) {
    Kernel k;
    std::mt19937 rng(7);
    std::normal_distribution<float> gauss;
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const auto on_sphere = [&](vec3 around) { return glm::normalize(around + 0.25f * vec3(gauss(rng), gauss(rng), gauss(rng))); };
    int checked = 0;
    for (int i = 0; i < 500; ++i) {
        const vec3 centre = glm::normalize(vec3(gauss(rng), gauss(rng), gauss(rng)));
        vec3 p0 = on_sphere(centre), p1 = on_sphere(centre), p2 = on_sphere(centre);
        vec3 face = glm::cross(p1 - p0, p2 - p0);
        if (glm::length(face) < 1e-3f) continue;
        if (glm::dot(face, p0) < 0.0f) std::swap(p1, p2);  // front face outward
        const Triangle t = smooth_triangle(p0, p1, p2, p0, p1, p2);
        float u = unit(rng), v = unit(rng);
        if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
        const vec3 p = (1.0f - u - v) * p0 + u * p1 + v * p2;
        const vec3 lifted = p + k.terminator_lift(t, u, v, 1.0f, glm::normalize(glm::cross(p1 - p0, p2 - p0)));
        EXPECT_LE(std::abs(glm::length(lifted) - 1.0f), std::abs(glm::length(p) - 1.0f) + 1e-6f);
        EXPECT_GT(glm::length(lifted), glm::length(p) - 1e-6f) << "lifted outward";
        ++checked;
    }
    EXPECT_GT(checked, 400);
}

// ------------------------------------------------------------------ images

// A tube around a tilted loop (a (1, 1) torus knot) lit from the upper left, with
// the given tessellation; grey on a blue background so the tube's pixels are known.
std::string tube_scene(int along, int around, bool terminator) {
    return R"({
      "camera": { "eye": [0.4, -1.5, 4], "look_at": [0.4, 0, 0], "fov": 40, "width": 160, "height": 160 },
      "render": { "aa": 1, "shadows": true, "ambient": [0, 0, 0], "background": [0, 0, 1], "terminator": )" +
           std::string(terminator ? "true" : "false") + R"( },
      "materials": { "grey": { "diffuse": [0.8, 0.8, 0.8] } },
      "lights": [ { "type": "point", "position": [-3, 2.5, 2.5], "intensity": 1 } ],
      "objects": [ { "type": "torus_knot", "p": 1, "q": 1, "radius": 1.2, "tube": 0.3, "segments": [)" +
           std::to_string(along) + ", " + std::to_string(around) + R"(], "material": "grey", "smooth": true } ]
    })";
}

vkrt::Image render_tube(int along, int around, bool terminator) {
    return vkrt::test::render_cpu(vkrt::test::scene_from_text("tube.json", tube_scene(along, around, terminator))).image;
}

// The share of pixels well inside both tubes' silhouettes where the coarse tube is
// much darker than the fine one.
double share_much_darker(const vkrt::Image& coarse, const vkrt::Image& fine) {
    const auto tube = [](const vkrt::Image& im, std::uint32_t x, std::uint32_t y) {
        const float* px = im.pixel(x, y);
        return px[0] == px[2];  // grey, not the blue background
    };
    std::size_t inside = 0, darker = 0;
    for (std::uint32_t y = 1; y + 1 < coarse.height; ++y) {
        for (std::uint32_t x = 1; x + 1 < coarse.width; ++x) {
            bool interior = true;
            for (int dy = -1; dy <= 1; ++dy) {
                for (int dx = -1; dx <= 1; ++dx) {
                    interior = interior && tube(coarse, x + dx, y + dy) && tube(fine, x + dx, y + dy);
                }
            }
            if (!interior) continue;
            ++inside;
            if (fine.pixel(x, y)[0] - coarse.pixel(x, y)[0] > 0.1f) ++darker;
        }
    }
    EXPECT_GT(inside, 5000u);
    return double(darker) / double(inside);
}

// A coarse tube (24 x 8 segments, 384 triangles) against a fine one (100 times as
// many): with the lift, few pixels are much darker than the fine tube's; without it
// (render.terminator false) the terminator's saw teeth and the facets' shadows on
// their neighbours make several times as many so.
TEST(TerminatorImage, ACoarseSmoothTubeShadesLikeAFineOne) {
    const vkrt::Image fine = render_tube(240, 80, true);
    const double with_lift = share_much_darker(render_tube(24, 8, true), fine);
    const double without = share_much_darker(render_tube(24, 8, false), fine);
    // The figures of decision 0028.
    std::printf("pixels much darker than the fine tube: %.2f%% with the lift, %.2f%% without\n", 100.0 * with_lift,
                100.0 * without);
    EXPECT_LT(with_lift, 0.005);
    EXPECT_GT(without, 0.015);
}

}  // namespace
