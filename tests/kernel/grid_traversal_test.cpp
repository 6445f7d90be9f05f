// The kernel's grid walk (shaders/kernel/grid.glsl, through the reference backend's
// view of it) against brute force: the same closest hit and the same shadow answers
// for random rays through random scenes, uniform and split (a dense cluster in a wide
// scene), and the robustness cases a grid walk must survive: +0/-0 and tiny direction components, origins inside, outside and exactly
// on the grid's faces, edges and corners, rays that miss, NaN and infinite rays.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "accel/grid.hpp"
#include "kernel/kernel.hpp"

namespace {

using namespace vkrt;
namespace kernel = vkrt::kernel;
using kernel::Kernel;
using kernel::vec3;
using kernel::vec4;
using kernel::uvec4;

struct GridScene {
    std::vector<kernel::Material> materials{kernel::Material{}};
    std::vector<kernel::Sphere> spheres;
    std::vector<kernel::Triangle> triangles;
    std::vector<kernel::Ring> rings;
    std::vector<kernel::Cylinder> cylinders;
    Grid grid;

    void build(GridRequest request = {}) {
        std::string note;
        grid = build_grid({spheres, triangles, rings, cylinders}, request, note);
    }

    Kernel kernel(bool with_grid) const {
        Kernel k;
        k.HAS_GRID = with_grid;
        k.materials = materials;
        k.spheres = spheres;
        k.triangles = triangles;
        k.rings = rings;
        k.cylinders = cylinders;
        k.GRID_SPLIT = grid.levels > 0;
        k.grid_nodes = grid.nodes;
        k.grid_refs = grid.refs;
        kernel::set_sphere_count(k.params, std::uint32_t(spheres.size()));
        kernel::set_triangle_count(k.params, std::uint32_t(triangles.size()));
        kernel::set_material_count(k.params, 1u);
        kernel::set_ring_count(k.params, std::uint32_t(rings.size()));
        kernel::set_cylinder_count(k.params, std::uint32_t(cylinders.size()));
        kernel::set_loop_budget(k.params, 0xFFFFFFFFu);
        kernel::set_grid_min(k.params, vec3(grid.lo));
        kernel::set_grid_max(k.params, vec3(grid.hi));
        kernel::set_grid_cell(k.params, vec3(grid.cell));
        kernel::set_grid_inv_cell(k.params, vec3(1.0 / grid.cell));
        kernel::set_grid_resolution(k.params, glm::uvec3(grid.resolution[0], grid.resolution[1], grid.resolution[2]));
        k.work_reset();
        return k;
    }
};

kernel::Triangle triangle(vec3 a, vec3 b, vec3 c, std::uint32_t id) {
    kernel::Triangle t{};
    t.p0 = vec4(a, 0.0f);
    t.p1 = vec4(b, 0.0f);
    t.p2 = vec4(c, 0.0f);
    t.meta = uvec4(id, 0u, 0u, 0u);  // the material index tells the primitives apart
    return t;
}

// Spheres and triangles of mixed sizes in [-10, 10]^3, some spanning many cells, and
// a quarter as many rings and cylinders (half of them capped) as spheres and
// triangles together, each kind.
GridScene random_scene(std::uint32_t seed, int spheres, int triangles) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-10.0f, 10.0f);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    GridScene s;
    std::uint32_t id = 0;
    for (int i = 0; i < spheres; ++i) {
        const float r = unit(rng) < 0.05f ? 3.0f * unit(rng) + 0.5f : 0.4f * unit(rng) + 0.02f;
        s.spheres.push_back(kernel::Sphere{vec4(pos(rng), pos(rng), pos(rng), r), uvec4(id++, 0u, 0u, 0u)});
    }
    for (int i = 0; i < triangles; ++i) {
        const vec3 a(pos(rng), pos(rng), pos(rng));
        const float size = unit(rng) < 0.05f ? 8.0f : 1.0f;
        const vec3 b = a + size * vec3(unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng) - 0.5f);
        const vec3 c = a + size * vec3(unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng) - 0.5f);
        s.triangles.push_back(triangle(a, b, c, id++));
    }
    for (int i = 0; i < (spheres + triangles) / 4; ++i) {
        const float big = unit(rng) < 0.05f ? 6.0f : 1.0f;
        const float outer = big * (0.5f * unit(rng) + 0.05f);
        const vec3 n = glm::normalize(vec3(unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng) - 0.5f) + vec3(0, 0, 1e-3f));
        s.rings.push_back(kernel::Ring{vec4(pos(rng), pos(rng), pos(rng), i % 3 == 0 ? 0.0f : 0.5f * outer),
                                       vec4(n, outer), uvec4(id++, 0u, 0u, 0u)});
        const vec3 base(pos(rng), pos(rng), pos(rng));
        const vec3 top = base + big * 2.0f * vec3(unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng) - 0.5f + 1e-3f);
        s.cylinders.push_back(kernel::Cylinder{vec4(base, big * (0.3f * unit(rng) + 0.02f)),
                                               vec4(top, i % 2 == 0 ? 1.0f : 0.0f), uvec4(id++, 0u, 0u, 0u)});
    }
    s.materials.resize(id);
    return s;
}

Kernel::Ray make_ray(vec3 origin, vec3 dir) { return Kernel::Ray(origin, dir); }

// Closest hit and shadow answer agree between the grid walk and brute force. With
// `ties`, two primitives hit at exactly the same t (a vertex two triangles share)
// may be answered either way: brute force keeps the first it tests, the walk the first
// its cells list, and a triangle is listed only in the cells it crosses.
::testing::AssertionResult same_answers(Kernel& grid, Kernel& brute, const Kernel::Ray& ray, float t_max,
                                        bool ties = false) {
    const Kernel::Hit a = grid.closest_hit(ray, t_max);
    const Kernel::Hit b = brute.closest_hit(ray, t_max);
    if (a.t != b.t || (a.t < t_max && a.material != b.material && !ties)) {
        return ::testing::AssertionFailure() << "closest hit: grid t " << a.t << " (primitive " << a.material
                                             << "), brute force t " << b.t << " (primitive " << b.material << ")";
    }
    const bool shadow_grid = grid.occluded(ray, t_max);
    const bool shadow_brute = brute.occluded(ray, t_max);
    if (shadow_grid != shadow_brute) {
        return ::testing::AssertionFailure() << "occluded: grid " << shadow_grid << ", brute force " << shadow_brute;
    }
    return ::testing::AssertionSuccess();
}

std::string describe(const Kernel::Ray& r) {
    char text[200];
    std::snprintf(text, sizeof text, "ray (%.9g, %.9g, %.9g) + t (%.9g, %.9g, %.9g)", r.origin.x, r.origin.y,
                  r.origin.z, r.dir.x, r.dir.y, r.dir.z);
    return text;
}

// One random ray of the tests below, `dir` of any length (a zero one is skipped),
// every third one ending at t = 8: false, and a failure added, when grid and brute
// force answer differently.
bool compare_ray(Kernel& grid, Kernel& brute, vec3 origin, vec3 dir, int i) {
    const float len = glm::length(dir);
    if (!(len > 0.0f)) return true;
    const Kernel::Ray ray = make_ray(origin, dir / len);
    const float t_max = i % 3 == 0 ? 8.0f : kernel::INFINITY_T;
    const ::testing::AssertionResult same = same_answers(grid, brute, ray, t_max);
    if (!same) ADD_FAILURE() << describe(ray) << ": " << same.message();
    return bool(same);
}

TEST(GridTraversal, HundredThousandRandomRaysMatchBruteForce) {
    GridScene s = random_scene(1, 400, 400);
    s.build();
    Kernel grid = s.kernel(true);
    Kernel brute = s.kernel(false);
    std::mt19937 rng(2);
    std::uniform_real_distribution<float> pos(-14.0f, 14.0f);
    std::normal_distribution<float> gauss;
    std::uniform_int_distribution<int> kind(0, 9);
    std::uniform_int_distribution<int> axis(0, 2);
    int failures = 0;
    for (int i = 0; i < 100000 && failures < 10; ++i) {
        vec3 origin(pos(rng), pos(rng), pos(rng));
        vec3 dir(gauss(rng), gauss(rng), gauss(rng));
        switch (kind(rng)) {
        case 0: {  // axis-aligned, the other components +0 or -0
            const int a = axis(rng);
            const float sign = gauss(rng) < 0.0f ? -1.0f : 1.0f;
            dir = vec3(gauss(rng) < 0.0f ? -0.0f : 0.0f, gauss(rng) < 0.0f ? -0.0f : 0.0f,
                       gauss(rng) < 0.0f ? -0.0f : 0.0f);
            dir[a] = sign;
            break;
        }
        case 1:  // one tiny component
            dir[axis(rng)] = 1e-30f * gauss(rng);
            break;
        case 2: {  // grazing a sphere: aimed at a point on its silhouette
            const kernel::Sphere& sp = s.spheres[std::size_t(i) % s.spheres.size()];
            const vec3 c(sp.center_radius);
            const vec3 to = glm::normalize(c - origin);
            vec3 side = glm::normalize(glm::cross(to, vec3(0.3f, 1.0f, 0.1f)));
            dir = c + sp.center_radius.w * side - origin;
            break;
        }
        case 3:  // starting on a cell boundary plane
            origin.x = float(s.grid.lo.x + s.grid.cell.x * double(i % s.grid.resolution[0]));
            break;
        case 4: {  // at a cylinder's rim or a ring's outer edge
            const std::size_t k = std::size_t(i) % s.cylinders.size();
            const kernel::Cylinder& c = s.cylinders[k];
            const vec3 along = glm::normalize(vec3(c.top_capped) - vec3(c.base_radius));
            const vec3 across = glm::normalize(glm::cross(along, vec3(0.3f, 1.0f, 0.1f)));
            const kernel::Ring& r = s.rings[k % s.rings.size()];
            const vec3 in_plane = glm::normalize(glm::cross(vec3(r.normal_outer), vec3(0.3f, 1.0f, 0.1f)));
            const vec3 target = i % 2 == 0 ? vec3(c.top_capped) + c.base_radius.w * across
                                           : vec3(r.center_inner) + r.normal_outer.w * in_plane;
            dir = target - origin;
            break;
        }
        default: break;
        }
        failures += compare_ray(grid, brute, origin, dir, i) ? 0 : 1;
    }
}

// Loose primitives (host/accel/grid.cpp): a floor 1,000 wide under the random scene
// is tested once per ray, and so is a whole kind asked to be loose (the rings); the
// walk covers the rest. Rays start inside the cluster and on the floor far outside
// the grid's box, and go every way, so some meet the floor before, after or without
// the cluster.
TEST(GridTraversal, LoosePrimitivesAndTheWalkMatchBruteForce) {
    GridScene s = random_scene(3, 200, 200);
    const std::uint32_t floor = std::uint32_t(s.triangles.size());
    s.triangles.push_back(triangle(vec3(-500, -12, -500), vec3(500, -12, -500), vec3(500, -12, 500), 9001));
    s.triangles.push_back(triangle(vec3(-500, -12, -500), vec3(500, -12, 500), vec3(-500, -12, 500), 9002));
    GridRequest request;
    request.max_loose = 32;
    request.loose_kinds[kernel::REF_RING] = true;
    s.build(request);
    ASSERT_EQ(s.grid.loose, 2u + s.rings.size());
    // In kind order: the floor's two triangles, then every ring.
    EXPECT_EQ(s.grid.refs[0], (kernel::REF_TRIANGLE << kernel::REF_KIND_SHIFT) | floor);
    EXPECT_EQ(s.grid.refs[1], (kernel::REF_TRIANGLE << kernel::REF_KIND_SHIFT) | (floor + 1u));
    EXPECT_EQ(s.grid.refs[2], kernel::REF_RING << kernel::REF_KIND_SHIFT);
    EXPECT_LT(s.grid.hi.y - s.grid.lo.y, 40.0) << "the floor still sets the box";
    Kernel grid = s.kernel(true);
    Kernel brute = s.kernel(false);
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> pos(-14.0f, 14.0f);
    std::uniform_real_distribution<float> far(-400.0f, 400.0f);
    std::normal_distribution<float> gauss;
    int failures = 0;
    for (int i = 0; i < 20000 && failures < 10; ++i) {
        vec3 origin(pos(rng), pos(rng), pos(rng));
        vec3 dir(gauss(rng), gauss(rng), gauss(rng));
        if (i % 4 == 0) {   // from the floor, far outside the grid, toward the cluster
            origin = vec3(far(rng), -11.99f, far(rng));
            dir = vec3(pos(rng), pos(rng), pos(rng)) - origin;
        }
        failures += compare_ray(grid, brute, origin, dir, i) ? 0 : 1;
    }
}

TEST(GridTraversal, SkipsMostOfTheScene) {
    GridScene s = random_scene(4, 3000, 0);
    s.build();
    Kernel grid = s.kernel(true);
    grid.closest_hit(make_ray(vec3(-20, 0.1f, 0.2f), vec3(1, 0, 0)), kernel::INFINITY_T);
    EXPECT_GT(grid.g_cells_visited, 1u);
    EXPECT_LT(grid.g_intersection_tests, 300u) << "of 3000 spheres";
}

// A grid of 4 x 4 x 4 cells over [0, 4]^3 (grown a little by the padding), one small
// sphere in each corner cell.
GridScene cube_scene() {
    GridScene s;
    std::uint32_t id = 0;
    for (float x : {0.5f, 3.5f}) {
        for (float y : {0.5f, 3.5f}) {
            for (float z : {0.5f, 3.5f}) {
                s.spheres.push_back(kernel::Sphere{vec4(x, y, z, 0.5f), uvec4(id++, 0u, 0u, 0u)});
            }
        }
    }
    s.materials.resize(id);
    GridRequest request;
    request.resolution = {4, 4, 4};
    s.build(request);
    return s;
}

TEST(GridTraversal, AxisRaysWithPlusAndMinusZeroVisitTheSameCells) {
    GridScene s = cube_scene();
    for (float zero : {0.0f, -0.0f}) {
        for (float sign : {1.0f, -1.0f}) {
            Kernel k = s.kernel(true);
            // Along x through the row of cells y = 1, z = 2: no sphere there.
            const Kernel::Ray ray = make_ray(vec3(sign > 0 ? -1.0f : 5.0f, 1.5f, 2.5f), vec3(sign, zero, zero));
            EXPECT_EQ(k.closest_hit(ray, kernel::INFINITY_T).t, kernel::INFINITY_T);
            EXPECT_EQ(k.g_cells_visited, 4u) << "zero " << zero << " sign " << sign;
        }
    }
}

TEST(GridTraversal, OriginsOnFacesEdgesAndCornersOfTheGridAndItsCells) {
    GridScene s = cube_scene();
    Kernel grid = s.kernel(true);
    Kernel brute = s.kernel(false);
    // Coordinates exactly on the grid's faces and on inner cell boundaries, as floats.
    auto on = [&](int a, int boundary) { return float(s.grid.lo[a] + s.grid.cell[a] * boundary); };
    std::vector<vec3> origins = {{-0.0f, -0.0f, -0.0f}, {2, 2, 2}, {1, 2, 3}};
    for (const auto& [bx, by, bz] : std::vector<std::array<int, 3>>{
             {0, 0, 0}, {4, 4, 4}, {0, 2, 2}, {4, 2, 2}, {2, 0, 2}, {2, 2, 4}, {1, 1, 1}, {0, 0, 2}, {4, 4, 1},
             {3, 3, 0}, {0, 4, 0}}) {
        origins.push_back(vec3(on(0, bx), on(1, by), on(2, bz)));
    }
    std::vector<vec3> dirs;
    for (float x : {-1.0f, -0.0f, 0.0f, 1.0f}) {
        for (float y : {-1.0f, -0.0f, 0.0f, 1.0f}) {
            for (float z : {-1.0f, -0.0f, 0.0f, 1.0f}) {
                const vec3 d(x, y, z);
                if (glm::length(d) > 0.0f) dirs.push_back(glm::normalize(d));
            }
        }
    }
    for (const vec3& o : origins) {
        for (const vec3& d : dirs) {
            const Kernel::Ray ray = make_ray(o, d);
            EXPECT_TRUE(same_answers(grid, brute, ray, kernel::INFINITY_T)) << describe(ray);
        }
    }
}

// Random rays from `eye` and from inside the scene, grid against brute force.
void expect_random_rays_match(GridScene& s, vec3 eye, float spread, int count, std::uint32_t seed) {
    Kernel grid = s.kernel(true);
    Kernel brute = s.kernel(false);
    std::mt19937 rng(seed);
    const std::size_t kinds[] = {s.spheres.size(), s.triangles.size(), s.rings.size(), s.cylinders.size()};
    std::uniform_int_distribution<std::size_t> pick(0, kinds[0] + kinds[1] + kinds[2] + kinds[3] - 1);
    std::normal_distribution<float> gauss;
    int failures = 0;
    for (int i = 0; i < count && failures < 10; ++i) {
        std::size_t k = pick(rng);
        vec3 target;
        if (k < kinds[0]) {
            target = vec3(s.spheres[k].center_radius);
        } else if ((k -= kinds[0]) < kinds[1]) {
            target = vec3(s.triangles[k].p1);
        } else if ((k -= kinds[1]) < kinds[2]) {
            target = vec3(s.rings[k].center_inner);
        } else {
            target = vec3(s.cylinders[k - kinds[2]].top_capped);
        }
        const vec3 origin = i % 2 == 0 ? eye : target + spread * vec3(gauss(rng), gauss(rng), gauss(rng));
        const vec3 aim = target + 0.5f * spread * vec3(gauss(rng), gauss(rng), gauss(rng));
        const vec3 dir = aim - origin;
        if (!(glm::length(dir) > 0.0f)) continue;
        const Kernel::Ray ray = make_ray(origin, glm::normalize(dir));
        const ::testing::AssertionResult same = same_answers(grid, brute, ray, kernel::INFINITY_T);
        if (!same) {
            ADD_FAILURE() << describe(ray) << ": " << same.message();
            ++failures;
        }
    }
}

// Rays aimed within a hair of a primitive's corner that lies on the grid box's
// boundary: before the box was grown by the padding, rounding in the slab test gave
// these an empty interval and the grid lost hits brute force found.
TEST(GridTraversal, RaysGrazingCornersOnTheGridBoundaryKeepTheirHits) {
    GridScene s;
    const float h = 5.0f;
    s.triangles.push_back(triangle(vec3(-h, 0, -h), vec3(h, 0, -h), vec3(h, 0, h), 0));
    s.triangles.push_back(triangle(vec3(-h, 0, -h), vec3(h, 0, h), vec3(-h, 0, h), 1));
    std::uint32_t id = 2;
    for (float x : {-3.0f, 0.0f, 3.0f}) {
        s.spheres.push_back(kernel::Sphere{vec4(x, 1.0f, 0.0f, 1.0f), uvec4(id++, 0u, 0u, 0u)});
    }
    s.materials.resize(id);
    s.build();
    Kernel grid = s.kernel(true);
    Kernel brute = s.kernel(false);
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> jitter(-1e-6f, 1e-6f);
    std::uniform_real_distribution<float> pos(-20.0f, 20.0f);
    std::uniform_real_distribution<float> height(0.5f, 20.0f);
    std::uniform_real_distribution<float> along(-h, h);
    int failures = 0;
    for (int i = 0; i < 20000 && failures < 10; ++i) {
        // A floor corner, or a point on a floor edge, nudged by a millionth. The two
        // triangles share two corners, where either may be the answer.
        vec3 target(i % 4 < 2 ? -h : h, 0.0f, i % 2 == 0 ? -h : h);
        if (i % 3 == 0) target[i % 2 == 0 ? 0 : 2] = along(rng);
        target += vec3(jitter(rng), 0.0f, jitter(rng));
        const vec3 origin(pos(rng), height(rng), pos(rng));
        const Kernel::Ray ray = make_ray(origin, glm::normalize(target - origin));
        const ::testing::AssertionResult same = same_answers(grid, brute, ray, kernel::INFINITY_T, true);
        if (!same) {
            ADD_FAILURE() << describe(ray) << ": " << same.message();
            ++failures;
        }
    }
}

TEST(GridTraversal, AFarEyeAndScenesAtOddScalesAndOffsets) {
    // The scene shrunk to a ten-thousandth, and moved far from the origin; rays from a
    // distant eye, which the builder pads the boxes for, and from within.
    for (const auto& [scale, offset] : std::vector<std::pair<float, vec3>>{
             {1.0f, vec3(0.0f)}, {1e-4f, vec3(0.0f)}, {1.0f, vec3(1e4f, -2e4f, 3e4f)}, {1e3f, vec3(5e5f)}}) {
        GridScene s = random_scene(9, 150, 150);
        for (kernel::Sphere& sp : s.spheres) {
            sp.center_radius = vec4(vec3(sp.center_radius) * scale + offset, sp.center_radius.w * scale);
        }
        for (kernel::Triangle& t : s.triangles) {
            t.p0 = vec4(vec3(t.p0) * scale + offset, 0.0f);
            t.p1 = vec4(vec3(t.p1) * scale + offset, 0.0f);
            t.p2 = vec4(vec3(t.p2) * scale + offset, 0.0f);
        }
        for (kernel::Ring& r : s.rings) {
            r.center_inner = vec4(vec3(r.center_inner) * scale + offset, r.center_inner.w * scale);
            r.normal_outer.w *= scale;
        }
        for (kernel::Cylinder& c : s.cylinders) {
            c.base_radius = vec4(vec3(c.base_radius) * scale + offset, c.base_radius.w * scale);
            c.top_capped = vec4(vec3(c.top_capped) * scale + offset, c.top_capped.w);
        }
        const vec3 eye = offset + scale * vec3(3e3f, 1e3f, -2e3f);
        GridRequest request;
        request.eye = glm::dvec3(eye);
        s.build(request);
        SCOPED_TRACE(testing::Message() << "scale " << scale << " offset " << offset.x);
        expect_random_rays_match(s, eye, 0.5f * scale, 4000, 21);
    }
}

TEST(GridTraversal, RaysThatMissTheGridVisitNoCell) {
    GridScene s = cube_scene();
    Kernel k = s.kernel(true);
    // Beside the box, parallel to it; and pointing away from it.
    k.work_reset();
    EXPECT_EQ(k.closest_hit(make_ray(vec3(-1, 5, 2), vec3(1, 0, 0)), kernel::INFINITY_T).t, kernel::INFINITY_T);
    EXPECT_EQ(k.g_cells_visited, 0u);
    k.work_reset();
    EXPECT_EQ(k.closest_hit(make_ray(vec3(-1, 2, 2), vec3(-1, 0, 0)), kernel::INFINITY_T).t, kernel::INFINITY_T);
    EXPECT_EQ(k.g_cells_visited, 0u);
    // Ending before the box.
    k.work_reset();
    EXPECT_FALSE(k.occluded(make_ray(vec3(-3, 0.5f, 0.5f), vec3(1, 0, 0)), 2.0f));
    EXPECT_EQ(k.g_cells_visited, 0u);
}

TEST(GridTraversal, NonFiniteRaysTerminateWithoutAHit) {
    GridScene s = cube_scene();
    Kernel k = s.kernel(true);
    kernel::set_loop_budget(k.params, kernel::DEFAULT_LOOP_BUDGET);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    const std::vector<Kernel::Ray> rays = {
        make_ray(vec3(2, 2, -1), vec3(nan, 0, 1)), make_ray(vec3(nan, 2, 2), vec3(0, 0, 1)),
        make_ray(vec3(2, 2, -1), vec3(0, inf, 1)), make_ray(vec3(-inf, 2, 2), vec3(1, 0, 0)),
        make_ray(vec3(2, 2, -1), vec3(0, 0, 0)),  // zero direction: parallel to every axis
    };
    for (const Kernel::Ray& r : rays) {
        k.work_reset();
        EXPECT_EQ(k.closest_hit(r, kernel::INFINITY_T).t, kernel::INFINITY_T) << describe(r);
        EXPECT_FALSE(k.occluded(r, kernel::INFINITY_T)) << describe(r);
        EXPECT_FALSE(k.budget_exhausted()) << describe(r);
    }
}

TEST(GridTraversal, WalkEndsWithinTheCellsOfTheGrid) {
    // A long diagonal through a fine, empty-ish grid: steps are bounded by the sum of
    // the resolutions, whatever the direction.
    GridScene s;
    s.spheres.push_back(kernel::Sphere{vec4(0, 0, 0, 0.01f), uvec4(0u)});
    s.spheres.push_back(kernel::Sphere{vec4(10, 10, 10, 0.01f), uvec4(0u)});
    GridRequest request;
    request.resolution = {50, 60, 70};
    s.build(request);
    Kernel k = s.kernel(true);
    std::mt19937 rng(5);
    std::normal_distribution<float> gauss;
    for (int i = 0; i < 2000; ++i) {
        k.work_reset();
        const vec3 d = glm::normalize(vec3(gauss(rng), gauss(rng), gauss(rng)));
        k.closest_hit(make_ray(vec3(5, 5, 5), d), kernel::INFINITY_T);
        EXPECT_LE(k.g_cells_visited, 50u + 60u + 70u);
    }
}

// A dense cluster in a wide scene, the teapot in a stadium: `count` small spheres,
// triangles, rings and cylinders in a cube of side `size` around `centre`, and a floor
// and walls of large triangles `room` times wider. The builder splits the cluster's
// root cells.
GridScene cluster_scene(std::uint32_t seed, int count, float size, vec3 centre, float room = 1000.0f) {
    GridScene s = random_scene(seed, count, count);
    const float k = size / 20.0f;   // random_scene fills [-10, 10]^3
    for (kernel::Sphere& sp : s.spheres) {
        sp.center_radius = vec4(vec3(sp.center_radius) * k + centre, std::min(sp.center_radius.w, 0.5f) * k);
    }
    for (kernel::Triangle& t : s.triangles) {
        const vec3 a = vec3(t.p0) * k + centre;
        // Not smaller: a triangle a few float steps wide, seen from afar, can pass the
        // watertight test's edge signs by rounding, whatever the grid does.
        t.p1 = vec4(vec3(t.p1) * k + centre, 0.0f);
        t.p2 = vec4(vec3(t.p2) * k + centre, 0.0f);
        t.p0 = vec4(a, 0.0f);
    }
    for (kernel::Ring& r : s.rings) {
        r.center_inner = vec4(vec3(r.center_inner) * k + centre, 0.0f);
        r.normal_outer.w = std::min(r.normal_outer.w, 0.5f) * k;
    }
    for (kernel::Cylinder& c : s.cylinders) {
        const vec3 base = vec3(c.base_radius) * k + centre;
        c.top_capped = vec4(base + glm::normalize(vec3(c.top_capped) - vec3(c.base_radius)) * 0.5f * k, c.top_capped.w);
        c.base_radius = vec4(base, std::min(c.base_radius.w, 0.3f) * k);
    }
    const float w = room * size;
    std::uint32_t id = std::uint32_t(s.materials.size());
    const vec3 f = centre - vec3(0.0f, size, 0.0f);
    for (int i = 0; i < 40; ++i) {   // a floor of 40 strips, and two walls
        const float x0 = f.x - w + 2.0f * w * float(i) / 40.0f, x1 = x0 + 2.0f * w / 40.0f;
        s.triangles.push_back(triangle(vec3(x0, f.y, f.z - w), vec3(x1, f.y, f.z + w), vec3(x1, f.y, f.z - w), id++));
        s.triangles.push_back(triangle(vec3(x0, f.y, f.z - w), vec3(x0, f.y, f.z + w), vec3(x1, f.y, f.z + w), id++));
    }
    s.triangles.push_back(triangle(vec3(f.x - w, f.y, f.z - w), vec3(f.x + w, f.y + w, f.z - w),
                                   vec3(f.x + w, f.y, f.z - w), id++));
    s.triangles.push_back(triangle(vec3(f.x - w, f.y, f.z + w), vec3(f.x - w, f.y + w, f.z - w),
                                   vec3(f.x - w, f.y, f.z - w), id++));
    s.materials.resize(id);
    return s;
}

// The cluster's cells are split, several levels deep, and every answer equals brute
// force: rays from inside the cluster in every direction, axis-aligned with +0 and -0,
// with tiny components, starting on the faces of the split cells, and from far away.
TEST(GridSplit, AClusterInAWideSceneMatchesBruteForce) {
    GridScene s = cluster_scene(31, 600, 1.0f, vec3(0.0f));
    s.build();
    ASSERT_GE(s.grid.levels, 3u) << "the cluster's cells are not split";
    Kernel grid = s.kernel(true);
    Kernel brute = s.kernel(false);
    std::mt19937 rng(32);
    std::uniform_real_distribution<float> in(-0.6f, 0.6f);
    std::uniform_real_distribution<float> far(-800.0f, 800.0f);
    std::normal_distribution<float> gauss;
    std::uniform_int_distribution<int> axis(0, 2);
    std::uniform_int_distribution<std::uint32_t> fine(0, std::uint32_t(kernel::GRID_FINE) - 1u);
    int failures = 0;
    for (int i = 0; i < 60000 && failures < 10; ++i) {
        vec3 origin(in(rng), in(rng), in(rng));
        vec3 dir(gauss(rng), gauss(rng), gauss(rng));
        switch (i % 6) {
        case 0: {  // axis-aligned, the other components +0 or -0
            const int a = axis(rng);
            dir = vec3(gauss(rng) < 0.0f ? -0.0f : 0.0f, gauss(rng) < 0.0f ? -0.0f : 0.0f,
                       gauss(rng) < 0.0f ? -0.0f : 0.0f);
            dir[a] = gauss(rng) < 0.0f ? -1.0f : 1.0f;
            break;
        }
        case 1:  // one tiny component
            dir[axis(rng)] = 1e-30f * gauss(rng);
            break;
        case 2: {  // starting on a face of a finest cell, in the cluster's root cell
            const int a = axis(rng);
            const glm::dvec3 root = glm::floor((glm::dvec3(origin) - s.grid.lo) / s.grid.cell);
            const double step = s.grid.cell[a] / double(1u << (kernel::GRID_SPLIT_BITS * s.grid.levels));
            const double within = double(fine(rng) >> (kernel::GRID_FRACTION_BITS - kernel::GRID_SPLIT_BITS *
                                                                                          s.grid.levels));
            origin[a] = float(s.grid.lo[a] + root[a] * s.grid.cell[a] + within * step);
            break;
        }
        case 3:  // from far away, toward the cluster
            origin = vec3(far(rng), std::abs(far(rng)), far(rng));
            dir = vec3(in(rng), in(rng), in(rng)) - origin;
            break;
        default: break;
        }
        failures += compare_ray(grid, brute, origin, dir, i) ? 0 : 1;
    }
}

// The cluster 10^4 times smaller than its room, near the origin as eye-centred
// coordinates put it: its padding is the rounding of positions near it, not at the
// room's scale, so its cells split to the finest level. Rays from the eye, from the
// room's far corners and walls toward the cluster (the longest reach, whose rounding
// the padding must cover), and from the cluster out to the walls.
TEST(GridSplit, AClusterTenThousandTimesSmallerThanItsRoomMatchesBruteForce) {
    GridScene s = cluster_scene(71, 400, 1.0f, vec3(0.0f), 1e4f);
    const vec3 eye(2.6f, 1.5f, 3.2f);
    GridRequest request;
    request.eye = glm::dvec3(eye);
    s.build(request);
    EXPECT_EQ(s.grid.levels, kernel::GRID_MAX_LEVELS) << "the cluster's cells do not reach the finest level";
    Kernel grid = s.kernel(true);
    Kernel brute = s.kernel(false);
    std::mt19937 rng(72);
    std::uniform_real_distribution<float> in(-0.6f, 0.6f);
    std::uniform_real_distribution<float> wall(-1e4f, 1e4f);
    std::uniform_int_distribution<int> side(0, 1);
    int failures = 0;
    for (int i = 0; i < 40000 && failures < 10; ++i) {
        const vec3 inside(in(rng), in(rng), in(rng));
        const float x = side(rng) != 0 ? 1e4f : -1e4f, z = side(rng) != 0 ? 1e4f : -1e4f;
        vec3 origin = eye, dir = inside - eye;
        switch (i % 4) {
        case 1:  // from a far corner of the room
            origin = vec3(x, std::abs(wall(rng)), z);
            dir = inside - origin;
            break;
        case 2:  // from a point on a far wall
            origin = vec3(x, std::abs(wall(rng)), wall(rng));
            dir = inside - origin;
            break;
        case 3:  // from the cluster out to a wall
            origin = inside;
            dir = vec3(wall(rng), std::abs(wall(rng)), z) - inside;
            break;
        default: break;
        }
        failures += compare_ray(grid, brute, origin, dir, i) ? 0 : 1;
    }
}

// Tiny spheres (far smaller than the rounding of a ray from across the room) in a
// cluster 10^4 times smaller than its room, each aimed at from a far corner or wall:
// where such a ray leaves a cell near another face, its rounded position may skip a
// sliver of the cell it meets, and only the padding keeps the spheres in that sliver
// listed in the cell it finds.
TEST(GridSplit, TinySpheresAimedAtFromAcrossTheRoomAreAllHit) {
    GridScene s = cluster_scene(91, 0, 1.0f, vec3(0.0f), 1e4f);
    std::mt19937 rng(92);
    std::uniform_real_distribution<float> in(-0.5f, 0.5f);
    std::uint32_t id = std::uint32_t(s.materials.size());
    for (int i = 0; i < 3000; ++i) {
        s.spheres.push_back(kernel::Sphere{vec4(in(rng), in(rng), in(rng), 2e-4f), uvec4(id++, 0u, 0u, 0u)});
    }
    s.materials.resize(id);
    GridRequest request;
    request.eye = glm::dvec3(2.6, 1.5, 3.2);
    s.build(request);
    ASSERT_GE(s.grid.levels, 5u) << "the cluster's cells are not split";
    Kernel grid = s.kernel(true);
    Kernel brute = s.kernel(false);
    std::uniform_real_distribution<float> wall(-1e4f, 1e4f);
    std::uniform_int_distribution<int> side(0, 1);
    int failures = 0;
    for (std::size_t i = 0; i < s.spheres.size() && failures < 10; ++i) {
        const vec3 target(s.spheres[i].center_radius);
        const float x = side(rng) != 0 ? 1e4f : -1e4f, z = side(rng) != 0 ? 1e4f : -1e4f;
        for (const vec3& origin : {vec3(x, std::abs(wall(rng)), z), vec3(x, std::abs(wall(rng)), wall(rng)),
                                   vec3(wall(rng), std::abs(wall(rng)), z)}) {
            failures += compare_ray(grid, brute, origin, target - origin, 1) ? 0 : 1;
        }
    }
}

// The same at odd scales and far from the origin, rays from a distant eye and from
// within.
TEST(GridSplit, AClusterAtOddScalesAndOffsetsMatchesBruteForce) {
    for (const auto& [scale, offset] : std::vector<std::pair<float, vec3>>{
             {1e-3f, vec3(0.0f)}, {1.0f, vec3(2e3f, -1e3f, 5e2f)}, {1e2f, vec3(-3e5f, 1e5f, 2e5f)}}) {
        GridScene s = cluster_scene(41, 400, scale, offset);
        const vec3 eye = offset + scale * vec3(30.0f, 12.0f, -20.0f);
        GridRequest request;
        request.eye = glm::dvec3(eye);
        s.build(request);
        SCOPED_TRACE(testing::Message() << "scale " << scale << " offset " << offset.x << ", " << s.grid.levels
                                        << " levels");
        EXPECT_GE(s.grid.levels, 1u) << "the cluster's cells are not split";
        expect_random_rays_match(s, eye, 0.05f * scale, 6000, 42);
    }
}

// Every walk ends: the sum over axes of step times fine coordinate grows each step,
// so a walk through a split grid visits at most as many cells as the fine grid has
// along the ray, whatever the ray.
TEST(GridSplit, WalksEndWithinTheFineCellsTheyCross) {
    GridScene s = cluster_scene(51, 400, 1.0f, vec3(0.0f));
    s.build();
    ASSERT_GE(s.grid.levels, 1u);
    Kernel k = s.kernel(true);
    std::mt19937 rng(52);
    std::normal_distribution<float> gauss;
    for (int i = 0; i < 2000; ++i) {
        const Kernel::Ray ray = make_ray(vec3(0.3f * gauss(rng), 0.3f * gauss(rng), 0.3f * gauss(rng)),
                                         glm::normalize(vec3(gauss(rng), gauss(rng), gauss(rng))));
        Kernel::GridWalk w = k.grid_walk_start(ray, kernel::INFINITY_T);
        std::uint64_t steps = 0;
        kernel::uvec3 last = w.at;
        while (k.grid_walk_step(ray, w)) {
            ++steps;
            // Never behind the last lookup on any axis the ray moves along.
            for (int a = 0; a < 3; ++a) {
                if (w.step[a] > 0) {
                    ASSERT_GE(w.at[a], last[a]);
                }
                if (w.step[a] < 0) {
                    ASSERT_LE(w.at[a], last[a]);
                }
            }
            last = w.at;
            ASSERT_LT(steps, 3u * 4096u) << describe(ray);
        }
    }
}

}  // namespace
