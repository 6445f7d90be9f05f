// The numerical-stability suite (docs/numerics.md), cases 4 and 5: intersections at their edge cases.
//   Case 4: grazing and silhouette rays, a camera inside a sphere, rays parallel to a
//   ring's plane or a cylinder's axis: finite hits where real arithmetic says so.
//   Case 5: closed meshes are watertight (no ray aimed at a shared vertex or edge
//   passes through), degenerate triangles are never hit, broken vertex normals fall
//   back to the face normal.
// The unit parts call the shared kernel through the reference backend and compare
// with double-precision geometry computed from the same float inputs; the scene
// parts render tests/scenes/stability/case4_*.json and case5_*.json (and scenes built
// here) on both backends.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "kernel/kernel.hpp"
#include "cpu/cpu_backend.hpp"
#include "render/render.hpp"
#include "scene/load_scene.hpp"
#include "flatten/flat_scene.hpp"
#include "test_support.hpp"

namespace vkrt {
namespace {

using kernel::INFINITY_T;
using kernel::Kernel;
using kernel::vec3;

Kernel::Ray ray(vec3 origin, vec3 dir) { return Kernel::Ray(origin, dir); }

glm::dvec3 wide(vec3 v) { return glm::dvec3(v.x, v.y, v.z); }

constexpr double kEps = 1.0 / 16777216.0;  // 2^-24, float's unit roundoff

// ===================================================== case 5: watertight meshes

// A closed triangle mesh: float vertices shared by index, as the loaders make them.
struct Mesh {
    std::vector<vec3> vertices;
    std::vector<std::array<int, 3>> faces;
};

// Every edge once, as a pair of vertex indices.
std::vector<std::pair<int, int>> edges_of(const Mesh& m) {
    std::map<std::pair<int, int>, int> seen;
    for (const auto& f : m.faces) {
        for (int i = 0; i < 3; ++i) {
            const int a = f[i], b = f[(i + 1) % 3];
            seen[{std::min(a, b), std::max(a, b)}] += 1;
        }
    }
    std::vector<std::pair<int, int>> out;
    for (const auto& [e, count] : seen) {
        EXPECT_EQ(count, 2) << "the mesh is not closed";
        out.push_back(e);
    }
    return out;
}

// The icosahedron, subdivided `levels` times (each triangle into four, new vertices
// pushed out to the unit sphere), in double; then scaled, turned about a skew axis and
// moved in double and rounded once to float, so coordinates are far from exact.
Mesh icosphere(int levels, double scale, glm::dvec3 offset) {
    const double g = (1.0 + std::sqrt(5.0)) / 2.0;
    std::vector<glm::dvec3> v = {{-1, g, 0}, {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
                                 {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
    for (auto& p : v) p = glm::normalize(p);
    std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                         {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                         {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                         {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (int l = 0; l < levels; ++l) {
        std::map<std::pair<int, int>, int> middle;
        auto mid = [&](int a, int b) {
            const std::pair<int, int> key{std::min(a, b), std::max(a, b)};
            auto it = middle.find(key);
            if (it != middle.end()) return it->second;
            v.push_back(glm::normalize(v[a] + v[b]));
            middle[key] = int(v.size()) - 1;
            return int(v.size()) - 1;
        };
        std::vector<std::array<int, 3>> next;
        for (const auto& t : f) {
            const int ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
            next.push_back({t[0], ab, ca});
            next.push_back({t[1], bc, ab});
            next.push_back({t[2], ca, bc});
            next.push_back({ab, bc, ca});
        }
        f = next;
    }
    // A turn of 0.7 radians about (1, 2, 3), by Rodrigues' formula.
    const glm::dvec3 k = glm::normalize(glm::dvec3(1, 2, 3));
    const double c = std::cos(0.7), s = std::sin(0.7);
    Mesh m;
    for (const auto& p : v) {
        const glm::dvec3 r = p * c + glm::cross(k, p) * s + k * glm::dot(k, p) * (1.0 - c);
        const glm::dvec3 q = r * scale + offset;
        m.vertices.push_back(vec3(float(q.x), float(q.y), float(q.z)));
    }
    m.faces = f;
    return m;
}

// The octahedron with vertices on the axes: every coordinate exact.
Mesh octahedron() {
    Mesh m;
    m.vertices = {vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, -1, 0), vec3(0, 0, 1), vec3(0, 0, -1)};
    m.faces = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    return m;
}

// Does the ray hit any triangle of the mesh (brute force, as the kernel without a grid)?
bool hits_mesh(Kernel& k, const Mesh& m, const Kernel::Ray& r) {
    for (const auto& f : m.faces) {
        const auto h = k.intersect_triangle(r, m.vertices[f[0]], m.vertices[f[1]], m.vertices[f[2]], 0.0f,
                                            INFINITY_T);
        if (h.t < INFINITY_T) return true;
    }
    return false;
}

struct EscapeCount {
    std::size_t rays = 0;
    std::size_t escapes = 0;
};

// Rays aimed exactly at every vertex, every edge's midpoint and six more points along
// every edge of a convex closed mesh: from outside (radially out from the centre, and
// from four points beside that, all in front of the faces around the target) and from
// two points inside. Every one of them must hit some triangle.
EscapeCount aim_at_vertices_and_edges(const Mesh& m) {
    Kernel k;
    glm::dvec3 centre(0.0);
    for (const vec3& p : m.vertices) centre += wide(p);
    centre /= double(m.vertices.size());
    std::vector<vec3> targets = m.vertices;
    for (const auto& [a, b] : edges_of(m)) {
        const vec3 pa = m.vertices[a], pb = m.vertices[b];
        for (float f : {0.5f, 1.0f / 3.0f, 0.1f, 0.9f, 0.01f, 0.999f, 2.0f / 7.0f}) {
            targets.push_back(pa + f * (pb - pa));
        }
    }
    const auto to_float = [](glm::dvec3 p) { return vec3(float(p.x), float(p.y), float(p.z)); };
    EscapeCount count;
    for (const vec3& target : targets) {
        const glm::dvec3 out = wide(target) - centre;
        const double len = glm::length(out);
        const glm::dvec3 side1 = glm::normalize(glm::cross(out, glm::dvec3(0.3, 1.0, 0.1))) * (0.25 * len);
        const glm::dvec3 side2 = glm::normalize(glm::cross(out, side1)) * (0.25 * len);
        std::vector<vec3> origins = {to_float(centre + 3.0 * out),           to_float(centre + 3.0 * out + side1),
                                     to_float(centre + 3.0 * out - side1),   to_float(centre + 3.0 * out + side2),
                                     to_float(centre + 3.0 * out - side2),   to_float(centre),
                                     to_float(centre + 0.1 * (side1 + side2))};
        for (const vec3& o : origins) {
            count.rays += 1;
            if (!hits_mesh(k, m, ray(o, k.unit_vector(target - o)))) count.escapes += 1;
        }
    }
    return count;
}

TEST(WatertightMesh, RaysAtSharedVerticesAndEdgesNeverEscape) {
    struct Case {
        const char* name;
        Mesh mesh;
    };
    const Case cases[] = {
        {"octahedron", octahedron()},
        {"icosahedron at (3.7, -1.3, 2.1)", icosphere(0, 1.7, {3.7, -1.3, 2.1})},
        {"icosphere (2 levels) at (3.7, -1.3, 2.1)", icosphere(2, 1.7, {3.7, -1.3, 2.1})},
        {"icosphere (3 levels), radius 1e3 at (1e4, 2e3, -5e3)", icosphere(3, 1e3, {1e4, 2e3, -5e3})},
        {"icosphere (2 levels), radius 1e-3 at (0.01, 0.02, 0.03)", icosphere(2, 1e-3, {0.01, 0.02, 0.03})},
    };
    std::size_t total = 0;
    for (const Case& c : cases) {
        const EscapeCount n = aim_at_vertices_and_edges(c.mesh);
        std::printf("%s: %zu triangles, %zu rays, %zu escapes\n", c.name, c.mesh.faces.size(), n.rays, n.escapes);
        EXPECT_EQ(n.escapes, 0u) << c.name;
        total += n.escapes;
    }
    std::printf("escapes in all: %zu\n", total);
}

// Triangles of zero area: a repeated vertex, three equal vertices, three distinct
// points on one line (with exact float differences, so the float edge vectors are
// parallel too). Rays aimed at their points from every direction, the plane of the
// line included, and a fan of rays across the line: none may hit, and no barycentric
// may be NaN.
TEST(DegenerateTriangles, AreNeverHit) {
    Kernel k;
    const vec3 a(0.5f, -0.25f, 1.0f), b(1.5f, 0.75f, 2.0f), c(3.5f, 2.75f, 4.0f);  // b - a = (1,1,1), c - a = 3(1,1,1)
    const vec3 p(1, 2, 3), q(2, 4, 6), r(3, 6, 9);
    const std::array<std::array<vec3, 3>, 10> triangles = {{{a, a, c}, {a, c, c}, {c, a, c}, {a, a, a},
                                                            {a, b, c}, {b, a, c}, {c, b, a}, {p, q, r},
                                                            {q, r, p}, {vec3(0), vec3(0), vec3(0)}}};
    std::size_t tested = 0, hits = 0, nan = 0;
    for (const auto& t : triangles) {
        for (float f : {0.0f, 0.25f, 0.5f, 1.0f, 1.0f / 3.0f}) {
            const vec3 target = t[0] + f * (t[2] - t[0]);
            for (int i = 0; i < 400; ++i) {
                // Directions spread over the sphere (a Fibonacci lattice), plus the axes
                // and the line's own direction.
                vec3 d;
                if (i < 6) {
                    d = vec3(0.0f);
                    d[i / 2] = (i % 2) ? -1.0f : 1.0f;
                } else if (i < 8) {
                    vec3 line = t[2] - t[0];
                    if (line == vec3(0.0f)) line = vec3(1, 1, 0);
                    d = k.unit_vector((i == 6 ? 1.0f : -1.0f) * line);
                } else {
                    const double z = 1.0 - 2.0 * (i + 0.5) / 400.0, phi = 2.399963229728653 * i;
                    const double s = std::sqrt(1.0 - z * z);
                    d = vec3(float(s * std::cos(phi)), float(s * std::sin(phi)), float(z));
                }
                for (float back : {1.0f, 7.0f}) {
                    for (float off : {0.0f, 1e-7f, -1e-7f}) {
                        const vec3 o = target - back * d + vec3(off, -off, 0.0f);
                        const auto h = k.intersect_triangle(ray(o, d), t[0], t[1], t[2], 0.0f, INFINITY_T);
                        tested += 1;
                        hits += h.t < INFINITY_T ? 1 : 0;
                        nan += (std::isnan(h.t) || std::isnan(h.u) || std::isnan(h.v)) ? 1 : 0;
                    }
                }
            }
        }
    }
    std::printf("degenerate triangles: %zu rays, %zu hits, %zu NaN\n", tested, hits, nan);
    EXPECT_EQ(hits, 0u);
    EXPECT_EQ(nan, 0u);
}


// Rays lying exactly in a triangle's plane, which has no inside to hit: in planes
// z = c every coordinate and the shear are exact, the sheared vertices lie on one
// line through the ray, all three edge functions are zero and every ray misses. In
// the plane x + y + z = 0 (small dyadic coordinates, so every point and direction
// below lies exactly in it) the shear's ratios d_x / d_z round, the sheared vertices
// leave their line by a rounding, and some rays hit the sliver between: those hits
// must still be finite with barycentrics in [0, 1] (Möller-Trumbore's were at
// u = v = -0, docs/grid.md).
TEST(WatertightMesh, RaysLyingInTheTrianglesPlane) {
    Kernel k;
    std::size_t flat_hits = 0, tilted_hits = 0, bad = 0;
    std::uint32_t state = 12345u;
    // A multiple of 2^-20 in [-range, range): 22 to 23 significant bits, so that
    // coordinates, sums of two and differences stay exact and products round.
    auto dyadic = [&state](int range) {
        state = state * 1664525u + 1013904223u;
        const std::uint32_t high = state >> 9;  // 23 random bits
        return float(std::int64_t(high % std::uint32_t(range << 21)) - (std::int64_t(range) << 20)) /
               1048576.0f;
    };
    const int rays = 20000;
    for (int i = 0; i < rays; ++i) {
        const bool tilted = i % 2 == 1;
        auto on_plane = [&](float x, float y) { return tilted ? vec3(x, y, -x - y) : vec3(x, y, 0.75f); };
        const vec3 p0 = on_plane(dyadic(4), dyadic(4)), p1 = on_plane(dyadic(4), dyadic(4)),
                   p2 = on_plane(dyadic(4), dyadic(4));
        const vec3 o = on_plane(dyadic(8), dyadic(8));
        float dx = dyadic(2), dy = dyadic(2);
        if (dx == 0.0f && dy == 0.0f) dx = 1.0f;
        const vec3 d = tilted ? vec3(dx, dy, -dx - dy) : vec3(dx, dy, 0.0f);
        const auto h = k.intersect_triangle(ray(o, d), p0, p1, p2, 0.0f, INFINITY_T);
        if (h.t < INFINITY_T) {
            (tilted ? tilted_hits : flat_hits) += 1;
            const bool sane = std::isfinite(h.t) && h.u >= 0.0f && h.v >= 0.0f && h.u + h.v <= 1.0f + 1e-6f;
            bad += sane ? 0 : 1;
        }
    }
    std::printf("rays in the triangle's plane: %d in z = 0.75, %zu hit; %d in x + y + z = 0, %zu hit\n", rays / 2,
                flat_hits, rays / 2, tilted_hits);
    EXPECT_EQ(flat_hits, 0u);
    EXPECT_EQ(bad, 0u);
}

// ==================================================== case 4: grazing and inside

// Directions spread evenly over the sphere (a Fibonacci lattice), in float.
std::vector<vec3> sphere_directions(int n) {
    Kernel k;
    std::vector<vec3> out;
    for (int i = 0; i < n; ++i) {
        const double z = 1.0 - 2.0 * (i + 0.5) / n, phi = 2.399963229728653 * i;
        const double s = std::sqrt(1.0 - z * z);
        out.push_back(k.unit_vector(vec3(float(s * std::cos(phi)), float(s * std::sin(phi)), float(z))));
    }
    return out;
}

// From inside a sphere every ray meets the wall once, at the far root. The expected t
// is worked out in double from the same float inputs (the real-number answer for
// them). The bound: a few roundings of the lengths involved, L = |o - c| + r, plus
// the conditioning of the square root: the discriminant is known to about eps L^2,
// which moves its root by eps L^2 / (2 sqrt(disc)) (large only for rays grazing the
// wall from just inside it). So |t - exact| <= 8 eps L + 2 eps L^2 / sqrt(disc),
// eps = 2^-24. Origins at the centre, off centre, and a millionth of the radius
// inside the wall; radii from 1e-3 to 1e4, centres away from the origin.
TEST(InsideSphere, EveryRayHitsTheWallAtTheFarRoot) {
    Kernel k;
    const std::vector<vec3> dirs = sphere_directions(2000);
    double worst = 0.0, worst_units = 0.0;
    std::size_t rays = 0;
    for (float radius : {1e-3f, 1.0f, 7.5f, 1e4f}) {
        const vec3 centre = radius * vec3(1.25f, -0.5f, 2.0f);
        for (const vec3 off : {vec3(0.0f), vec3(0.3f, -0.2f, 0.45f), vec3(0.0f, 0.999999f, 0.0f),
                               vec3(-0.57735f, 0.57735f, -0.57735f) * 0.999999f}) {
            const vec3 o = centre + radius * off;
            for (const vec3& d : dirs) {
                const float t = k.intersect_sphere(ray(o, d), centre, radius, 0.0f, INFINITY_T);
                const glm::dvec3 oc = wide(o) - wide(centre), dd = wide(d);
                const double a = glm::dot(dd, dd), b = glm::dot(oc, dd), c = glm::dot(oc, oc) - double(radius) * radius;
                const double disc = b * b - a * c;
                const double exact = (-b + std::sqrt(disc)) / a;
                const double l = glm::length(oc) + radius;
                const double bound = 8.0 * kEps * l + 2.0 * kEps * l * l / std::sqrt(disc);
                rays += 1;
                ASSERT_TRUE(std::isfinite(t) && t < INFINITY_T) << "radius " << radius << " origin off " << off.y;
                worst = std::max(worst, std::abs(t - exact) / bound);
                worst_units = std::max(worst_units, std::abs(t - exact) / (kEps * l));
            }
        }
    }
    std::printf("inside a sphere: %zu rays, largest |t - exact| = %.3f of the bound, %.1f eps L\n", rays, worst,
                worst_units);
    EXPECT_LE(worst, 1.0);
}

// Rays down -z past a sphere's silhouette, at lateral offsets a few float steps
// inside and outside the radius, and exactly at it: inside hits (t within roundings
// of the exact one), exactly at the radius the tangent point is hit at t = 5 (every
// intermediate exact), outside misses. One step either way may round to the
// tangent, so the offsets start at 4 steps. The bound on t is InsideSphere's.
TEST(GrazingSphere, SilhouetteRaysHitExactlyInsideTheRim) {
    Kernel k;
    for (float radius : {1.0f, 3.0f, 0.1f, 1000.0f}) {
        const vec3 centre(0.0f);
        const vec3 down(0, 0, -1);
        EXPECT_EQ(k.intersect_sphere(ray(vec3(radius, 0, 5), down), centre, radius, 0.0f, INFINITY_T), 5.0f);
        EXPECT_EQ(k.intersect_sphere(ray(vec3(0, -radius, 5), down), centre, radius, 0.0f, INFINITY_T), 5.0f);
        float inside = radius, outside = radius;
        for (int steps = 1; steps <= 4096; ++steps) {
            inside = std::nextafter(inside, 0.0f);
            outside = std::nextafter(outside, 2.0f * radius);
            if (steps < 4) continue;
            const float z0 = 5.0f * std::max(1.0f, radius);
            const float t_in = k.intersect_sphere(ray(vec3(inside, 0, z0), down), centre, radius, 0.0f, INFINITY_T);
            const double disc = double(radius) * radius - double(inside) * inside;
            const double exact = z0 - std::sqrt(disc);
            const double l = z0 + radius;
            ASSERT_LT(t_in, INFINITY_T) << radius << " " << steps;
            EXPECT_NEAR(t_in, exact, 8.0 * kEps * l + 2.0 * kEps * l * l / std::sqrt(disc)) << radius << " " << steps;
            EXPECT_EQ(k.intersect_sphere(ray(vec3(outside, 0, z0), down), centre, radius, 0.0f, INFINITY_T),
                      INFINITY_T)
                << radius << " " << steps;
        }
    }
}

// A ray parallel to a ring's plane never meets it: above the plane, in it, with +0
// and -0 and denormal components along the normal, the answer is a clean miss or a
// finite hit far away, never NaN. Nearly parallel rays from just above the plane hit
// at t = h / |d_n|, within roundings.
TEST(GrazingRing, ParallelAndNearlyParallelRays) {
    Kernel k;
    // At height 0, so that heights of 2^-62 above it are representable.
    const vec3 centre(0.5f, 0.0f, -1.0f), normal(0, 1, 0);
    auto ring_t = [&](vec3 o, vec3 d) { return k.intersect_ring(ray(o, d), centre, normal, 1.0f, 3.0f, 0.0f, INFINITY_T); };
    for (float h : {0.0f, -0.0f, 1.0f, 1e-30f}) {
        for (float dn : {0.0f, -0.0f, 1e-45f, -1e-45f, 1e-40f, -1e-38f}) {
            const vec3 d = k.unit_vector(vec3(1.0f, dn, 0.0f));
            const float t = ring_t(centre + vec3(-2.0f, h, 0.0f), d);
            EXPECT_FALSE(std::isnan(t)) << h << " " << dn;
            // In the plane or parallel to it: no hit short of the far horizon.
            if (h == 0.0f || dn == 0.0f) {
                EXPECT_EQ(t, INFINITY_T) << h << " " << dn;
            }
        }
    }
    // From height h above the plane, 2 units from the centre, dipping by 2^-k: the
    // plane is met at t = h / |d_y| and the point must lie in the annulus.
    for (int e = 3; e <= 60; ++e) {
        const float h = std::ldexp(1.0f, -e - 2);
        const vec3 d = k.unit_vector(vec3(1.0f, -std::ldexp(1.0f, -e), 0.0f));
        const vec3 o = centre + vec3(-2.0f, h, 0.0f);
        const float t = ring_t(o, d);
        const double exact = double(h) / -double(d.y);
        ASSERT_LT(t, INFINITY_T) << e;
        EXPECT_NEAR(t, exact, 4.0 * kEps * exact) << e;
    }
}

// A cylinder of radius 1 around the z axis from z = 0 to z = 1e6, seen from a point on
// its axis along directions tilted from the axis by 2^-k. The side is met at
// t = 1 / |d_perp| while that point's height stays below the top; beyond, the open
// cylinder is missed and the capped one hit on its top cap at t = 1e6 / d_z. Along
// the axis itself (tilt 0) the side is never met. All within roundings of the exact
// answer for the float direction.
TEST(GrazingCylinder, RaysAlongAndNearlyAlongTheAxis) {
    Kernel k;
    const vec3 base(0, 0, 0), top(0, 0, 1e6f);
    const vec3 o(0, 0, 0.5f);
    for (bool capped : {false, true}) {
        for (int e = 1; e <= 70; ++e) {
            const float tilt = e == 70 ? 0.0f : std::ldexp(1.0f, -e);
            const vec3 d = k.unit_vector(vec3(tilt, 0.5f * tilt, 1.0f));
            const auto hit = k.intersect_cylinder(ray(o, d), base, top, 1.0f, capped, 0.0f, INFINITY_T);
            const double perp = std::hypot(double(d.x), double(d.y));
            const double t_side = perp > 0.0 ? 1.0 / perp : INFINITY;
            const double t_top = (1e6 - 0.5) / double(d.z);
            SCOPED_TRACE(fmt::format("capped {}, tilt 2^-{}", capped, e));
            ASSERT_FALSE(std::isnan(hit.t));
            if (t_side < t_top * (1.0 - 1e-5)) {
                EXPECT_EQ(hit.part, kernel::CYLINDER_SIDE);
                EXPECT_NEAR(hit.t, t_side, 4.0 * kEps * t_side);
            } else if (t_side > t_top * (1.0 + 1e-5)) {
                if (capped) {
                    EXPECT_EQ(hit.part, kernel::CYLINDER_TOP_CAP);
                    EXPECT_NEAR(hit.t, t_top, 4.0 * kEps * t_top);
                } else {
                    EXPECT_EQ(hit.t, INFINITY_T);
                }
            }
        }
    }
    // Parallel to the axis off it, inside and outside the radius: inside an open
    // cylinder, nothing; a capped one, the top cap at exactly t = 1e6 - 0.5.
    for (float x : {0.0f, 0.5f, 1.0f, 2.0f}) {
        const auto open = k.intersect_cylinder(ray(vec3(x, 0, 0.5f), vec3(0, 0, 1)), base, top, 1.0f, false, 0.0f,
                                               INFINITY_T);
        EXPECT_EQ(open.t, INFINITY_T) << x;
        const auto closed = k.intersect_cylinder(ray(vec3(x, 0, 0.5f), vec3(0, 0, 1)), base, top, 1.0f, true, 0.0f,
                                                 INFINITY_T);
        if (x <= 1.0f) {
            EXPECT_EQ(closed.t, 1e6f - 0.5f) << x;
        } else {
            EXPECT_EQ(closed.t, INFINITY_T) << x;
        }
    }
}

// ======================================================= scenes on both backends

Scene stability_scene(const std::string& name) {
    return load_scene(std::filesystem::path(VKRT_SOURCE_DIR) / "tests/scenes/stability" / name);
}

// What real arithmetic says an eye ray does: hit, miss, or too close to call (within
// a band of relative width 1e-5 around a rim, where the float inputs' roundings may
// decide either way).
enum class Expect { hit, miss, either };

// The scenes paint hits green and misses red (background [1, 0, 0], a material with
// no red), so the hit mask is read off the image.
bool red(const Image& image, std::size_t pixel) { return image.rgb[3 * pixel] > 0.5f; }

// Where a ray from o along d crosses the plane z = z0 (d.z != 0), its distance from
// the z axis, in double.
double radial_at(const glm::dvec3& o, const glm::dvec3& d, double z0) {
    const double t = (z0 - o.z) / d.z;
    return std::hypot(o.x + t * d.x, o.y + t * d.y);
}

Expect within(double value, double lo, double hi) {
    const double band = 1e-5 * std::max(1.0, std::abs(value));
    if (value < lo - band || value > hi + band) return Expect::miss;
    if (value > lo + band && value < hi - band) return Expect::hit;
    return Expect::either;
}

// The analytic masks of the scenes: the cylinder (radius 1, z from -4 to 0) and the
// ring (radii 1 to 3 in the plane y = 0) as the scene files place them.
Expect cylinder_from_outside(glm::dvec3 o, glm::dvec3 d, bool capped) {
    if (!(d.z < 0.0)) return Expect::miss;
    const Expect into_top = within(radial_at(o, d, 0.0), 0.0, 1.0);  // through the top circle
    if (capped || into_top != Expect::hit) return into_top;
    return within(radial_at(o, d, -4.0), 1.0, INFINITY);  // the wall before the bottom circle
}

Expect cylinder_from_inside(glm::dvec3 o, glm::dvec3 d, bool capped) {
    if (capped) return Expect::hit;
    if (d.z == 0.0) return Expect::hit;
    return within(radial_at(o, d, d.z < 0.0 ? -4.0 : 0.0), 1.0, INFINITY);
}

Expect ring_from(glm::dvec3 o, glm::dvec3 d) {
    if (o.y == 0.0 || !(d.y < 0.0)) return Expect::miss;  // in the plane, or never reaching it
    const double t = -o.y / d.y;
    return within(std::hypot(o.x + t * d.x, o.z + t * d.z), 1.0, 3.0);
}

struct MaskScene {
    std::string file;
    Expect (*expect)(glm::dvec3 origin, glm::dvec3 dir);
};

// gtest prints a parameter in the test's description; the file name, not its bytes.
void PrintTo(const MaskScene& scene, std::ostream* os) { *os << scene.file; }

class StabilityScene : public ::testing::TestWithParam<MaskScene> {};

// Each scene on both backends: finite, no truncated sample, the same image and hit
// mask on both, and the mask equal to the analytic one outside the rims' bands.
TEST_P(StabilityScene, FiniteAgreeingAndMatchingTheAnalyticMask) {
    const MaskScene& c = GetParam();
    const Scene scene = stability_scene(c.file);
    const RenderOutcome cpu = test::render_cpu(scene);
    const RenderOutcome vulkan = test::render_vulkan(scene);
    test::expect_sane(cpu);
    test::expect_sane(vulkan);
    EXPECT_EQ(cpu.stats.eye_hits, vulkan.stats.eye_hits);
    EXPECT_LE(test::max_abs_difference(cpu.image, vulkan.image), 1e-5f);
    const FlatScene gpu = flatten_scene(scene);
    Kernel k = make_kernel(gpu);
    std::size_t hits = 0, band = 0, wrong = 0, backends_differ = 0;
    for (std::uint32_t y = 0; y < scene.camera.height; ++y) {
        for (std::uint32_t x = 0; x < scene.camera.width; ++x) {
            const std::size_t pixel = std::size_t(y) * scene.camera.width + x;
            const bool hit = !red(cpu.image, pixel);
            backends_differ += hit != !red(vulkan.image, pixel) ? 1 : 0;
            hits += hit ? 1 : 0;
            const Kernel::Ray r = k.camera_ray(float(x) + 0.5f, float(y) + 0.5f);
            const Expect e = c.expect(wide(r.origin), wide(r.dir));
            band += e == Expect::either ? 1 : 0;
            wrong += (e == Expect::hit && !hit) || (e == Expect::miss && hit) ? 1 : 0;
        }
    }
    std::printf("%s: %zu of %u pixels hit (eye_hits %llu), %zu in a rim's band, %zu against the analytic mask, "
                "%zu differ between backends\n",
                c.file.c_str(), hits, scene.camera.width * scene.camera.height,
                static_cast<unsigned long long>(cpu.stats.eye_hits), band, wrong, backends_differ);
    EXPECT_EQ(hits, cpu.stats.eye_hits);
    EXPECT_EQ(wrong, 0u);
    EXPECT_EQ(backends_differ, 0u);
}

INSTANTIATE_TEST_SUITE_P(
    Stability, StabilityScene,
    ::testing::Values(
        MaskScene{"case4_inside_sphere.json", [](glm::dvec3, glm::dvec3) { return Expect::hit; }},
        MaskScene{"case4_ring_in_plane.json", [](glm::dvec3 o, glm::dvec3 d) { return ring_from(o, d); }},
        MaskScene{"case4_ring_grazing.json", [](glm::dvec3 o, glm::dvec3 d) { return ring_from(o, d); }},
        MaskScene{"case4_cylinder_axis_open.json",
                  [](glm::dvec3 o, glm::dvec3 d) { return cylinder_from_outside(o, d, false); }},
        MaskScene{"case4_cylinder_axis_capped.json",
                  [](glm::dvec3 o, glm::dvec3 d) { return cylinder_from_outside(o, d, true); }},
        MaskScene{"case4_cylinder_inside_open.json",
                  [](glm::dvec3 o, glm::dvec3 d) { return cylinder_from_inside(o, d, false); }},
        MaskScene{"case4_cylinder_inside_capped.json",
                  [](glm::dvec3 o, glm::dvec3 d) { return cylinder_from_inside(o, d, true); }},
        MaskScene{"case5_octahedron_inside.json", [](glm::dvec3, glm::dvec3) { return Expect::hit; }},
        MaskScene{"case5_icosahedron_inside.json", [](glm::dvec3, glm::dvec3) { return Expect::hit; }}),
    [](const ::testing::TestParamInfo<MaskScene>& param) {
        return param.param.file.substr(0, param.param.file.size() - 5);
    });

// A scene of a sphere on a floor, lit, with a triangle in front (whose vertex normals
// the tests below break) and room for degenerate triangles.
Scene base_scene() { return stability_scene("case5_normals_fallback.json"); }

// Degenerate triangles placed where eye and shadow rays pass change nothing: the
// image is the same, bit for bit, on each backend. Two scenes: the lit one above,
// with degenerate triangles across the sphere, on the floor and between light and
// floor; and a head-on view whose middle row and column of eye rays run exactly
// through lines and points of degenerate triangles on the axes (their direction has
// a zero component there), in front of a wall.
TEST(DegenerateTriangles, ChangeNothingInAScene) {
    const Scene lit = stability_scene("case5_normals_fallback.json");
    Scene straight = lit;
    straight.camera.eye = glm::dvec3(0.0, 0.0, 5.0);
    straight.camera.look_at = glm::dvec3(0.0, 0.0, 0.0);
    straight.camera.width = 63;
    straight.camera.height = 47;
    {
        const FlatScene gpu = flatten_scene(straight);
        Kernel k = make_kernel(gpu);
        std::size_t on_axes = 0;
        for (std::uint32_t y = 0; y < 47; ++y) {
            for (std::uint32_t x = 0; x < 63; ++x) {
                const Kernel::Ray r = k.camera_ray(float(x) + 0.5f, float(y) + 0.5f);
                on_axes += (r.dir.x == 0.0f || r.dir.y == 0.0f) ? 1 : 0;
            }
        }
        EXPECT_GT(on_axes, 0u) << "no eye ray runs through the axes: the second scene tests nothing";
    }
    using glm::dvec3;
    const dvec3 a(-0.6, 0.5, 0.2), b(0.0, 0.75, 0.3), c(0.6, 1.0, 0.4);  // b = (a + c) / 2
    const std::vector<std::array<dvec3, 3>> degenerate = {
        {a, b, c}, {a, a, c}, {c, c, c}, {dvec3(-1, 0, 0), dvec3(0, 0, 0), dvec3(1, 0, 0)},
        {dvec3(0.5, 0, 0.5), dvec3(0.5, 0, 0.5), dvec3(0.5, 0, 0.5)}, {dvec3(0, 1, 0), dvec3(1, 2, 1), dvec3(2, 3, 2)},
        {dvec3(-2, 0, 1), dvec3(0.5, 0, 1), dvec3(2, 0, 1)}, {dvec3(0, -2, 1.5), dvec3(0, 0.25, 1.5), dvec3(0, 2, 1.5)},
        {dvec3(-1, 0, 2), dvec3(-1, 0, 2), dvec3(1, 0, 2)}, {dvec3(0, 0, 0.5), dvec3(0, 0, 0.5), dvec3(0, 0, 0.5)},
        {dvec3(0, 0, -0.5), dvec3(0, 0, 0.5), dvec3(0, 0, 1)}};
    for (const Scene* plain : {static_cast<const Scene*>(&lit), static_cast<const Scene*>(&straight)}) {
        Scene with = *plain;
        for (const auto& v : degenerate) with.triangles.push_back(Triangle{v, std::nullopt, 0});
        for (bool vulkan : {false, true}) {
            SCOPED_TRACE(fmt::format("{}, {}", plain == &straight ? "head-on view" : "lit scene",
                                     vulkan ? "vulkan" : "cpu"));
            const RenderOutcome before = vulkan ? test::render_vulkan(*plain) : test::render_cpu(*plain);
            const RenderOutcome after = vulkan ? test::render_vulkan(with) : test::render_cpu(with);
            test::expect_sane(after);
            EXPECT_EQ(after.stats.eye_hits, before.stats.eye_hits);
            EXPECT_EQ(test::max_abs_difference(after.image, before.image), 0.0f);
        }
    }
}

// Vertex normals that are zero, NaN, or opposite at two corners cannot be blended into
// a direction (or, opposite, only into +-the face normal): interpolate_normal falls
// back to the face normal. The triangle then shades like its flat twin: the same
// image within roundings, finite, on both backends.
TEST(BrokenVertexNormals, FallBackToTheFaceNormal) {
    const Scene flat = base_scene();
    ASSERT_FALSE(flat.triangles.empty());
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const glm::dvec3 face = glm::normalize(glm::cross(flat.triangles[0].vertices[1] - flat.triangles[0].vertices[0],
                                                      flat.triangles[0].vertices[2] - flat.triangles[0].vertices[0]));
    const std::array<std::pair<const char*, std::array<glm::dvec3, 3>>, 4> broken = {{
        {"zero", {glm::dvec3(0), glm::dvec3(0), glm::dvec3(0)}},
        {"NaN", {glm::dvec3(nan), glm::dvec3(nan), glm::dvec3(0, nan, 0)}},
        {"one NaN corner", {face, glm::dvec3(nan, 0, 0), face}},
        {"opposing", {face, -face, face}},
    }};
    for (const auto& [name, normals] : broken) {
        Scene smooth = flat;
        smooth.triangles[0].normals = normals;
        for (bool vulkan : {false, true}) {
            SCOPED_TRACE(fmt::format("{} normals, {}", name, vulkan ? "vulkan" : "cpu"));
            const RenderOutcome want = vulkan ? test::render_vulkan(flat) : test::render_cpu(flat);
            const RenderOutcome got = vulkan ? test::render_vulkan(smooth) : test::render_cpu(smooth);
            test::expect_sane(got);
            EXPECT_EQ(got.stats.eye_hits, want.stats.eye_hits);
            // The opposing blend, (1 - 2u) n, made unit, is the face normal within an
            // ULP or two, which the highlight's exponent (40) multiplies.
            EXPECT_LE(test::max_abs_difference(got.image, want.image), 1e-4f);
        }
    }
}

}  // namespace
}  // namespace vkrt
